// Pieces of the VTK writers shared by vtk_writer.cpp (floes, bonds, contacts, images) and spatial_vtk_writer.cpp
// (spatial bodies). Internal to dem/io: it includes VTK, which only dem/io/*.cpp may see.
#pragma once

#include <vtkDataObject.h>
#include <vtkIdTypeArray.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

class vtkXMLWriter;

namespace polyfloe::io {
class OutputManifest;
}
namespace polyfloe::dynamics {
class World;
}

namespace polyfloe::io::detail {

// Shortest text that reads back to the same double.
std::string exact(double x);
// Writes `data` to `target` via a temporary sibling with `writer` (a vtkXML*Writer): binary appended,
// zlib-compressed, 64-bit headers; throws IoError naming the file with VTK's messages.
void write_xml(vtkXMLWriter* writer, vtkDataObject* data, const std::filesystem::path& target);
// Removes DIR/<stem>/<stem>_NNNNNN<extension> for every N >= first: with a manifest, the listed ones only; without,
// every such file (and hidden temporaries of such frames).
void remove_frames_from(const std::filesystem::path& dir, const std::string& stem, const char* extension, int first,
                        const OutputManifest* manifest);

// "stem_NNNNNN.ext": the file name of frame `frame`.
std::string frame_name(const std::string& stem, int frame, const char* extension = ".vtp");
// Writes `data` as XML PolyData (binary appended, zlib) via a temporary sibling renamed into place; throws IoError.
void write_polydata(vtkPolyData* data, const std::filesystem::path& target);
// The planar frames (vtk_writer.cpp): what the World owns of its bodies, contacts and bonded faces, or none of them
// (`header_only`: the arrays, empty, for a .pvtp's list).
vtkSmartPointer<vtkPolyData> floes_polydata(const dynamics::World& world, double water_density, bool header_only);
vtkSmartPointer<vtkPolyData> contacts_polydata(const dynamics::World& world, double water_density, bool header_only);
vtkSmartPointer<vtkPolyData> bonds_polydata(const dynamics::World& world, double water_density, bool header_only);
// A PPolyData file (.pvtp) at `target` that lists `pieces` (file names relative to its folder) with the arrays of
// `header`, written atomically; throws IoError naming the file.
void write_pvtp(vtkPolyData* header, const std::vector<std::string>& pieces, const std::filesystem::path& target);
// "stem_NNNNNN_K.vtp": piece K of frame `frame`.
std::string piece_name(const std::string& stem, int frame, int piece);
// Field data TIME [s] and CYCLE (the step) that ParaView reads.
void add_time(vtkDataObject* data, double t, std::uint64_t step);
// 0, 1, ..., count - 1
vtkSmartPointer<vtkIdTypeArray> iota(vtkIdType count);

template <class Array>
vtkSmartPointer<Array> make_array(const char* name, int components, vtkIdType tuples) {
  auto a = vtkSmartPointer<Array>::New();
  a->SetName(name);
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(tuples);
  return a;
}

}  // namespace polyfloe::io::detail
