#include "io/xdmf_frames.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <optional>
#include <sstream>
#include <system_error>
#include <utility>

#include "formats/atomic_file.h"
#include "formats/hdf5_file.h"
#include "formats/output_manifest.h"

namespace polyfloe::io {

using hdf5::Dataset;
using hdf5::Dims;
using hdf5::units;

namespace {

constexpr const char* kViewFolder = "xdmf";

// "frames_000012-000020.h5": the view file of frames 12..20.
std::string view_name(int first, int last) {
  char name[48];
  std::snprintf(name, sizeof name, "frames_%06d-%06d.h5", first, last);
  return name;
}

// Frames first..last of a view file's name, or nothing when `name` is not one.
std::optional<std::pair<int, int>> view_range(const std::string& name) {
  int first = 0, last = 0;
  char tail = 0;
  if (name.size() != view_name(0, 0).size() ||
      std::sscanf(name.c_str(), "frames_%6d-%6d.h%c", &first, &last, &tail) != 3 || tail != '5' || first > last ||
      name != view_name(first, last))
    return std::nullopt;
  return std::make_pair(first, last);
}

}  // namespace

// The view files of an interrupted run (this folder's manifest lists them) that hold only frames this run adopted
// (frames past the checkpoint it continues from were computed anew, even where their times match), each checked
// against results.h5's times, are kept from frame 0 on without a gap; the others are stale.
void XdmfFrames::scan(const std::filesystem::path& folder, OutputManifest* manifest, const std::vector<double>& times) {
  scanned_ = true;
  if (manifest == nullptr) return;
  const std::string prefix = std::string(kViewFolder) + "/";
  std::vector<std::pair<std::pair<int, int>, std::string>> listed;
  for (const std::string& entry : manifest->entries()) {
    if (entry.rfind(prefix, 0) != 0) continue;
    if (const auto range = view_range(entry.substr(prefix.size()))) listed.emplace_back(*range, entry);
  }
  std::sort(listed.begin(), listed.end());
  for (const auto& [range, entry] : listed) {
    const auto [first, last] = range;
    bool keep = first == (batches_.empty() ? 0 : batches_.back().last + 1) && last < adopted_ &&
                std::filesystem::is_regular_file(folder / entry);
    if (keep) {
      try {
        const hdf5::File f(folder / entry, hdf5::File::Mode::read_only);
        const std::vector<double> t = f.root().open_dataset("time").read<double>();
        keep = t.size() == static_cast<std::size_t>(last - first + 1) &&
               std::equal(t.begin(), t.end(), times.begin() + first,
                          [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; });
      } catch (const std::exception&) {
        keep = false;
      }
    }
    if (keep)
      batches_.push_back({first, last, entry});
    else
      stale_.push_back(entry);
  }
}

// xdmf/frames_FIRST-LAST.h5 (atomically): the polygons where they are (frames/NNNNNN/vertices_xy [V,2] float32, as
// state/vertices_xy), velocity and angular_velocity [N,3] of each frame, with the bodies' topology, id, thickness
// and motion and the frames' times: every array results.xmf names, each a whole dataset (no hyperslab).
void XdmfFrames::write_batch(const hdf5::Group& results, const std::string& results_name,
                             const std::filesystem::path& folder, OutputManifest* manifest, int first, int last,
                             const std::vector<double>& times) {
  const std::string entry = std::string(kViewFolder) + "/" + view_name(first, last);
  if (manifest) {
    manifest->record(std::string(kViewFolder) + "/");
    manifest->record(entry);
  }
  const std::filesystem::path target = folder / entry;
  std::error_code ec;
  std::filesystem::create_directories(target.parent_path(), ec);
  if (ec) throw IoError("cannot create the folder " + target.parent_path().string() + ": " + ec.message());
  const std::filesystem::path tmp = temporary_sibling(target);
  {
    hdf5::File f(tmp, hdf5::File::Mode::truncate);
    auto& root = f.root();
    root.set_attribute("created_by", "PolyFloe");
    root.set_attribute("description", "frames " + std::to_string(first) + " to " + std::to_string(last) + " of " +
                                          results_name + ", as results.xmf reads them");
    units(root.write_dataset<double>("time", std::span(times).subspan(first, last - first + 1)), "s");
    auto floes = root.create_group("floes");
    units(floes.write_dataset<std::uint64_t>("id", bodies_.id), "1", "stable body id");
    units(floes.write_dataset<double>("thickness", bodies_.thickness), "m");
    units(floes.write_dataset<std::int8_t>("motion", bodies_.motion), "1", "0 dynamic, 1 fixed, 2 kinematic");
    units(floes.write_dataset<std::int64_t>("topology", bodies_.topology), "1",
          "XDMF mixed topology: per body 3 (polygon), its vertex count, its rows of vertices_xy");
    auto frames_group = root.create_group("frames");
    const std::uint64_t v = bodies_.vertices, n = bodies_.id.size();
    const Dataset vertices_xy = results.open_dataset("state/vertices_xy");
    const Dataset velocity = results.open_dataset("state/velocity");
    const Dataset angular_velocity = results.open_dataset("state/angular_velocity");
    for (int k = first; k <= last; ++k) {
      char name[16];
      std::snprintf(name, sizeof name, "%06d", k);
      auto g = frames_group.create_group(name);
      const auto row = static_cast<std::uint64_t>(k);
      units(g.write_dataset<float>("vertices_xy", vertices_xy.read_rows<float>(row, 1), Dims{v, 2}), "m");
      units(g.write_dataset<double>("velocity", velocity.read_rows<double>(row, 1), Dims{n, 3}), "m/s");
      units(g.write_dataset<double>("angular_velocity", angular_velocity.read_rows<double>(row, 1), Dims{n, 3}),
            "rad/s");
    }
    f.close();
  }
  commit_file_atomic(tmp, target);
  batches_.push_back({first, last, entry});
}

void XdmfFrames::write(const hdf5::Group& results, const std::string& results_name, const std::filesystem::path& xmf,
                       OutputManifest* manifest) {
  const std::vector<double> times = results.open_dataset("time").read<double>();
  const std::filesystem::path folder = xmf.parent_path();
  if (!scanned_) scan(folder, manifest, times);
  const int written = batches_.empty() ? 0 : batches_.back().last + 1;
  const int frames = static_cast<int>(times.size());
  if (frames > written) write_batch(results, results_name, folder, manifest, written, frames - 1, times);
  write_xmf(results_name, xmf, times);
  // an interrupted run's files that this run rewrote or does not keep: results.xmf no longer names them
  for (const std::string& entry : stale_)
    if (std::none_of(batches_.begin(), batches_.end(), [&](const Batch& b) { return b.name == entry; }))
      manifest->remove_file(entry);
  stale_.clear();
}

void XdmfFrames::write_xmf(const std::string& results_name, const std::filesystem::path& xmf,
                           const std::vector<double>& times) const {
  const std::uint64_t n = bodies_.id.size(), v = bodies_.vertices;
  std::ostringstream x;
  x.precision(17);
  std::string h5;  // "xdmf/frames_FIRST-LAST.h5:" of the frame at hand
  auto item = [&](const std::string& dims, const char* type, int precision, const std::string& path) {
    x << "<DataItem Dimensions=\"" << dims << "\" NumberType=\"" << type << "\" Precision=\"" << precision
      << "\" Format=\"HDF\">" << h5 << path << "</DataItem>";
  };
  auto attribute = [&](const char* name, const char* kind, const char* units, auto&& data) {
    x << "    <Attribute Name=\"" << name << "\" AttributeType=\"" << kind << "\" Center=\"Cell\">"
      << "<Information Name=\"units\" Value=\"" << units << "\"/>";
    data();
    x << "</Attribute>\n";
  };
  const std::string rows = std::to_string(n) + " 3";
  x << "<?xml version=\"1.0\" ?>\n<!-- PolyFloe: the frames of " << results_name
    << " for ParaView (File > Open; any of its XDMF readers), their arrays in the files of " << kViewFolder
    << "/; written with each checkpoint, at the end of the run and when it stops early -->\n"
    << "<Xdmf Version=\"2.0\">\n<Domain>\n<Grid Name=\"floes\" GridType=\"Collection\" "
       "CollectionType=\"Temporal\">\n";
  for (const Batch& b : batches_) {
    h5 = b.name + ":";
    for (int k = b.first; k <= b.last; ++k) {
      char frame[32];
      std::snprintf(frame, sizeof frame, "/frames/%06d/", k);
      x << "  <Grid Name=\"frame " << k << "\" GridType=\"Uniform\">\n    <Time Value=\"" << times[k] << "\"/>\n"
        << "    <Topology TopologyType=\"Mixed\" NumberOfElements=\"" << n << "\">";
      item(std::to_string(bodies_.topology.size()), "Int", 8, "/floes/topology");
      x << "</Topology>\n    <Geometry GeometryType=\"XY\">";
      item(std::to_string(v) + " 2", "Float", 4, frame + std::string("vertices_xy"));
      x << "</Geometry>\n";
      attribute("velocity", "Vector", "m/s", [&] { item(rows, "Float", 8, frame + std::string("velocity")); });
      attribute("angular_velocity", "Vector", "rad/s",
                [&] { item(rows, "Float", 8, frame + std::string("angular_velocity")); });
      attribute("id", "Scalar", "1", [&] { item(std::to_string(n), "UInt", 8, "/floes/id"); });
      attribute("thickness", "Scalar", "m", [&] { item(std::to_string(n), "Float", 8, "/floes/thickness"); });
      attribute("motion", "Scalar", "1 (0 dynamic, 1 fixed, 2 kinematic)",
                [&] { item(std::to_string(n), "Char", 1, "/floes/motion"); });
      x << "  </Grid>\n";
    }
  }
  x << "</Grid>\n</Domain>\n</Xdmf>\n";
  write_file_atomic(xmf, x.str());
}

}  // namespace polyfloe::io
