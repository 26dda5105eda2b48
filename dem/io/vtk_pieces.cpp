// Planar VTK frames in pieces (io/vtk_writer.h): each rank's piece of a frame, the .pvtp file that lists a frame's
// pieces, and the manifest entries and folders they need first.
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDataSetAttributes.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkType.h>

#include <cstdio>
#include <stdexcept>
#include <system_error>

#include "dynamics/world.h"
#include "formats/atomic_file.h"
#include "formats/output_manifest.h"
#include "io/vtk_common.h"
#include "io/vtk_writer.h"

namespace polyfloe::io {
namespace fs = std::filesystem;

namespace {

// The XML name of an array's value type, as VTK's own XML writers name it.
std::string xml_type(vtkDataArray* a) {
  const int bits = 8 * a->GetDataTypeSize();
  switch (a->GetDataType()) {
    case VTK_FLOAT:
    case VTK_DOUBLE: return "Float" + std::to_string(bits);
    case VTK_CHAR:
    case VTK_SIGNED_CHAR:
    case VTK_SHORT:
    case VTK_INT:
    case VTK_LONG:
    case VTK_LONG_LONG:
    case VTK_ID_TYPE: return "Int" + std::to_string(bits);
    case VTK_UNSIGNED_CHAR:
    case VTK_UNSIGNED_SHORT:
    case VTK_UNSIGNED_INT:
    case VTK_UNSIGNED_LONG:
    case VTK_UNSIGNED_LONG_LONG: return "UInt" + std::to_string(bits);
    default: throw std::logic_error(std::string("no XML type for VTK array ") + a->GetName());
  }
}

std::string array_xml(vtkDataArray* a, const char* indent) {
  return std::string(indent) + "<PDataArray type=\"" + xml_type(a) + "\" Name=\"" + a->GetName() +
         "\" NumberOfComponents=\"" + std::to_string(a->GetNumberOfComponents()) + "\"/>\n";
}

// <PPointData> or <PCellData>: the attributes' arrays, and which is the active scalar.
std::string attributes_xml(vtkDataSetAttributes* d, const char* tag) {
  std::string out = std::string("    <") + tag;
  if (vtkDataArray* s = d->GetScalars()) out += std::string(" Scalars=\"") + s->GetName() + "\"";
  out += ">\n";
  for (int k = 0; k < d->GetNumberOfArrays(); ++k)
    if (vtkDataArray* a = d->GetArray(k)) out += array_xml(a, "      ");
  return out + "    </" + tag + ">\n";
}

}  // namespace

namespace detail {

std::string piece_name(const std::string& stem, int frame, int piece) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "_%06d_%d.vtp", frame, piece);
  return stem + buf;
}

void write_pvtp(vtkPolyData* header, const std::vector<std::string>& pieces, const fs::path& target) {
  std::string xml =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"PPolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
      "  <PPolyData GhostLevel=\"0\">\n";
  xml += attributes_xml(header->GetPointData(), "PPointData");
  xml += attributes_xml(header->GetCellData(), "PCellData");
  xml += "    <PPoints>\n" + array_xml(header->GetPoints()->GetData(), "      ") + "    </PPoints>\n";
  for (const std::string& p : pieces) xml += "    <Piece Source=\"" + p + "\"/>\n";
  xml += "  </PPolyData>\n</VTKFile>\n";
  write_file_atomic(target, xml);
}

}  // namespace detail

void VtkSeriesWriter::make_bonds_folder() {
  std::error_code ec;
  bonds_pvd_.record("bonds/");
  fs::create_directories(dir_ / "bonds", ec);
  if (ec) throw IoError("cannot create VTK output folder " + (dir_ / "bonds").string() + ": " + ec.message());
}

void VtkSeriesWriter::begin_pieces(bool bonds) {
  if (bonds) make_bonds_folder();
  for (int k = 0; k < pieces_; ++k) {
    floes_pvd_.record("floes/" + detail::piece_name("floes", frames_, k));
    if (write_contacts_) contacts_pvd_.record("contacts/" + detail::piece_name("contacts", frames_, k));
    if (bonds) bonds_pvd_.record("bonds/" + detail::piece_name("bonds", frames_, k));
  }
}

void write_vtk_piece(const fs::path& dir, const dynamics::World& world, int frame, int piece, bool contacts,
                     double water_density) {
  using namespace detail;
  write_polydata(floes_polydata(world, water_density, false), dir / "floes" / piece_name("floes", frame, piece));
  if (contacts)
    write_polydata(contacts_polydata(world, water_density, false),
                   dir / "contacts" / piece_name("contacts", frame, piece));
  if (world.bonds())
    write_polydata(bonds_polydata(world, water_density, false), dir / "bonds" / piece_name("bonds", frame, piece));
}

}  // namespace polyfloe::io
