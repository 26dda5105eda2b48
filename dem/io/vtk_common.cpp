// The pieces of the VTK writers that vtk_writer.cpp and spatial_vtk_writer.cpp share (io/vtk_common.h), and the
// .pvd collection (PvdCollection, io/vtk_writer.h).
#include "io/vtk_common.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkTypeUInt64Array.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLWriter.h>

#include <charconv>
#include <cstdio>
#include <system_error>
#include <vector>

#include "formats/atomic_file.h"
#include "formats/output_manifest.h"
#include "io/vtk_writer.h"

namespace polyfloe::io {
namespace fs = std::filesystem;

namespace {

std::string xml_escape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// Collects VTK error messages of one object instead of letting them go to the output window.
class ErrorCatcher {
 public:
  explicit ErrorCatcher(vtkObject* watched) {
    callback_->SetCallback(&ErrorCatcher::on_error);
    callback_->SetClientData(&messages_);
    watched->AddObserver(vtkCommand::ErrorEvent, callback_);
  }
  const std::string& messages() const { return messages_; }

 private:
  static void on_error(vtkObject*, unsigned long, void* client, void* call) {
    auto* messages = static_cast<std::string*>(client);
    if (!messages->empty()) *messages += "; ";
    *messages += call ? static_cast<const char*>(call) : "unknown VTK error";
  }
  vtkNew<vtkCallbackCommand> callback_;
  std::string messages_;
};

// The frame number of `name` if it is one of a frame's files, else -1: <stem>_<digits> and then <extension> (the
// frame), .pvtp (its list of pieces) or _<digits><extension> (a piece). `leading`: the name need only begin so
// (a temporary file of the frame's, named so and more).
long frame_number(const std::string& name, const std::string& stem, const std::string& extension,
                  bool leading = false) {
  const std::string prefix = stem + "_";
  if (name.rfind(prefix, 0) != 0) return -1;
  const std::size_t digits = name.find_first_not_of("0123456789", prefix.size());
  if (digits == prefix.size() || digits == std::string::npos || digits - prefix.size() > 9) return -1;
  auto ends_so = [&](std::size_t at, const std::string& tail) {
    return leading ? name.compare(at, tail.size(), tail) == 0 : name.compare(at, std::string::npos, tail) == 0;
  };
  bool frame_file = ends_so(digits, extension) || ends_so(digits, ".pvtp");
  if (!frame_file && name[digits] == '_') {
    const std::size_t piece = name.find_first_not_of("0123456789", digits + 1);
    frame_file = piece != digits + 1 && piece != std::string::npos && ends_so(piece, extension);
  }
  return frame_file ? std::stol(name.substr(prefix.size(), digits - prefix.size())) : -1;
}

}  // namespace

namespace detail {

// Shortest text that reads back to the same double.
std::string exact(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

// Writes `data` to `target` via a temporary sibling with `writer` (a vtkXML*Writer): binary appended,
// zlib-compressed, 64-bit headers.
void write_xml(vtkXMLWriter* writer, vtkDataObject* data, const fs::path& target) {
  const fs::path tmp = temporary_sibling(target);
  ErrorCatcher errors(writer);
  writer->SetFileName(tmp.c_str());
  writer->SetInputData(data);
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  writer->SetCompressorTypeToZLib();
  writer->SetHeaderTypeToUInt64();
  const int ok = writer->Write();
  if (ok != 1 || writer->GetErrorCode() != 0 || !errors.messages().empty()) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw IoError("cannot write " + target.string() + ": " +
                  (errors.messages().empty() ? std::string(writer->GetClassName()) + " failed" : errors.messages()));
  }
  commit_file_atomic(tmp, target);
}

std::string frame_name(const std::string& stem, int frame, const char* extension) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "_%06d", frame);
  return stem + buf + extension;
}

void write_polydata(vtkPolyData* data, const fs::path& target) {
  vtkNew<vtkXMLPolyDataWriter> writer;
  write_xml(writer, data, target);
}

void add_time(vtkDataObject* data, double t, std::uint64_t step) {
  auto time = make_array<vtkDoubleArray>("TIME", 1, 1);
  time->SetValue(0, t);
  data->GetFieldData()->AddArray(time);
  auto cycle = make_array<vtkTypeUInt64Array>("CYCLE", 1, 1);
  cycle->SetValue(0, step);
  data->GetFieldData()->AddArray(cycle);
}

// 0, 1, ..., count - 1
vtkSmartPointer<vtkIdTypeArray> iota(vtkIdType count) {
  auto a = vtkSmartPointer<vtkIdTypeArray>::New();
  a->SetNumberOfValues(count);
  for (vtkIdType c = 0; c < count; ++c) a->SetValue(c, c);
  return a;
}

// Removes the files of frames N >= first of DIR/<stem> (<stem>_NNNNNN<extension>, or a .pvtp and its pieces): with a
// manifest, the listed ones only; without, every such file (and hidden temporaries of such frames).
void remove_frames_from(const fs::path& dir, const std::string& stem, const char* extension, int first,
                        const OutputManifest* manifest) {
  if (manifest) {
    std::vector<std::string> doomed;
    for (const std::string& e : manifest->entries())
      if (e.rfind(stem + "/", 0) == 0 && frame_number(e.substr(stem.size() + 1), stem, extension) >= first)
        doomed.push_back(e);
    for (const std::string& e : doomed) manifest->remove_file(e);
    manifest->remove_temporaries(stem + "/");
    return;
  }
  std::error_code ec;
  const fs::path sub = dir / stem;
  if (!fs::is_directory(sub, ec)) return;
  std::vector<fs::path> doomed;
  for (const auto& entry : fs::directory_iterator(sub, ec)) {
    std::string f = entry.path().filename().string();
    if (!f.empty() && f[0] == '.') f.erase(0, 1);
    if (frame_number(f, stem, extension, true) >= first) doomed.push_back(entry.path());
  }
  for (const fs::path& p : doomed) {
    fs::remove(p, ec);
    if (ec) throw IoError("cannot remove " + p.string() + " (a frame after the restart point): " + ec.message());
  }
}

}  // namespace detail

using detail::exact;
using detail::frame_name;

PvdCollection::PvdCollection(fs::path file, OutputManifest* manifest) : file_(std::move(file)), manifest_(manifest) {}

void PvdCollection::record(const std::string& relative) {
  if (manifest_) manifest_->record(relative);
}

void PvdCollection::add(double time, const std::string& relative_file) {
  record(file_.filename().string());
  entries_ += "    <DataSet timestep=\"" + exact(time) + "\" group=\"\" part=\"0\" file=\"" +
              xml_escape(relative_file) + "\"/>\n";
  ++count_;
  write_file_atomic(file_, text());
}

void PvdCollection::resume(std::span<const double> times, const std::string& stem, const char* extension) {
  entries_.clear();
  count_ = 0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    const std::string pieces = stem + "/" + frame_name(stem, static_cast<int>(k), ".pvtp");
    std::error_code ec;
    const bool in_pieces = fs::exists(file_.parent_path() / pieces, ec);
    entries_ += "    <DataSet timestep=\"" + exact(times[k]) + "\" group=\"\" part=\"0\" file=\"" +
                xml_escape(in_pieces ? pieces : stem + "/" + frame_name(stem, static_cast<int>(k), extension)) +
                "\"/>\n";
    ++count_;
  }
  record(file_.filename().string());
  write_file_atomic(file_, text());
}

std::string PvdCollection::text() const {
  return "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "  <Collection>\n" +
         entries_ +
         "  </Collection>\n"
         "</VTKFile>\n";
}

}  // namespace polyfloe::io
