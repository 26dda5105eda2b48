// VTK output for ParaView: one .vtp file per frame plus a .pvd collection that lists them with their times.
//
//   DIR/floes.pvd, DIR/floes/floes_NNNNNN.vtp          every body (walls too) as a prism
//   DIR/contacts.pvd, DIR/contacts/contacts_NNNNNN.vtp  one vertex per active contact (optional)
//   DIR/bonds.pvd, DIR/bonds/bonds_NNNNNN.vtp          one line per bond face where it is now (worlds with bonds)
//
// Each .vtp is written under a temporary name and renamed into place, and each .pvd is rewritten atomically
// after the frame it lists, so a run killed at any moment leaves a collection that parses and lists only
// complete frames. VTK itself stays behind this header (only the .cpp includes it).
//
// Or in pieces (output.vtk_pieces; ParaView's parallel convention): frame NNNNNN of each series is a PPolyData file
// DIR/floes/floes_NNNNNN.pvtp listing its pieces DIR/floes/floes_NNNNNN_K.vtp, K = 0 .. pieces - 1, and the .pvd
// lists the .pvtp. Under mpirun piece K is rank K's: the floes it owns, the contacts it evaluated and the bonded
// faces whose lower-id element it owns, each written by that rank (write_vtk_piece); one process writes one piece.
// Each body, contact and face is in exactly one piece, with the values the single file gives it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace polyfloe::dynamics {
class World;
class SpatialWorld;
}  // namespace polyfloe::dynamics

namespace polyfloe::io {

class OutputManifest;

// A .pvd collection file: (time, relative file) entries, rewritten atomically on every add(). With a manifest
// (io/output_manifest.h: the list of what a run wrote into its folder), the collection and the frame files named
// to record() are listed in it before they are written.
class PvdCollection {
 public:
  explicit PvdCollection(std::filesystem::path file, OutputManifest* manifest = nullptr);
  // Lists `relative` (a frame file or folder, relative to the .pvd's folder) in the manifest, if there is one.
  void record(const std::string& relative);
  // Appends a DataSet entry; `relative_file` is relative to the .pvd's folder. Rewrites the file.
  void add(double time, const std::string& relative_file);
  const std::filesystem::path& path() const { return file_; }
  std::size_t size() const { return count_; }
  // The whole XML text as it is on disk.
  std::string text() const;
  // Replaces the entries by frames 0..times.size()-1 named <stem>/<stem>_NNNNNN<extension>, or .pvtp where that is
  // on disk (a frame written in pieces), for a resumed run, and rewrites the file.
  void resume(std::span<const double> times, const std::string& stem, const char* extension);

 private:
  std::filesystem::path file_;
  OutputManifest* manifest_;
  std::string entries_;  // the <DataSet .../> lines so far
  std::size_t count_ = 0;
};

class VtkSeriesWriter {
 public:
  // Creates DIR (and DIR/floes, DIR/contacts) if needed; existing .pvd files there are replaced on the first
  // frame. `water_density` [kg/m^3] sets each floe's draft, so prisms float at their equilibrium level.
  // `manifest` (optional): where every file is listed before it is made; a resumed run then removes only listed
  // frames.
  // `pieces` > 0: frames in that many pieces (the header), which write_frame() does not write itself.
  VtkSeriesWriter(const std::filesystem::path& dir, bool write_contacts, double water_density,
                  OutputManifest* manifest = nullptr, int pieces = 0);

  // Writes frame number frames() at time world.time() [s]. Throws IoError naming the file on failure. In pieces:
  // lists the pieces in each series' .pvtp (they must be on disk, written since begin_pieces()) and the .pvtp in the
  // .pvd; `world` gives the arrays' names and types.
  void write_frame(const dynamics::World& world);
  // In pieces, before they are written: every piece of frame frames() listed in the manifest, and its folders made.
  // `bonds`: the world has bonds.
  void begin_pieces(bool bonds);
  int pieces() const { return pieces_; }
  int frames() const { return frames_; }
  // Continues a run whose frames 0..frame_times.size()-1 are on disk: the collections list exactly those, and the
  // frame files of later frames (written after the checkpoint the run resumes from) are removed. `bonds`: the
  // world has bonds.
  void resume(std::span<const double> frame_times, bool bonds);

  const std::filesystem::path& directory() const { return dir_; }

 private:
  void make_bonds_folder();  // DIR/bonds, listed in the manifest

  std::filesystem::path dir_;
  bool write_contacts_;
  double water_density_;  // [kg/m^3]
  OutputManifest* manifest_;
  int pieces_ = 0;
  int frames_ = 0;
  PvdCollection floes_pvd_;
  PvdCollection contacts_pvd_;
  PvdCollection bonds_pvd_;
};

// Piece `piece` of frame `frame` of DIR's series (floes; contacts where `contacts`; bonds where the world has them):
// what `world` owns, as VtkSeriesWriter's header says, each file written under a temporary name and renamed into
// place. The folders must exist (VtkSeriesWriter::begin_pieces). Throws IoError naming the file on failure.
void write_vtk_piece(const std::filesystem::path& dir, const dynamics::World& world, int frame, int piece,
                     bool contacts, double water_density);

// VTK output of a spatial scene (dynamics/spatial_world.h):
//   DIR/bodies.pvd, DIR/bodies/bodies_NNNNNN.vtp        every polyhedron, one polygon per face; cell data: id,
//                                                      motion, velocity [m/s], angular_velocity [rad/s]
//   DIR/contacts.pvd, DIR/contacts/contacts_NNNNNN.vtp  one vertex per contact (optional): normal, force [N],
//                                                      depth [m], manifold_points
class SpatialVtkSeriesWriter {
 public:
  SpatialVtkSeriesWriter(const std::filesystem::path& dir, bool write_contacts, OutputManifest* manifest = nullptr);
  void write_frame(const dynamics::SpatialWorld& world);
  // As VtkSeriesWriter::resume.
  void resume(std::span<const double> frame_times);
  int frames() const { return frames_; }

 private:
  std::filesystem::path dir_;
  bool write_contacts_;
  OutputManifest* manifest_;
  int frames_ = 0;
  PvdCollection bodies_pvd_;
  PvdCollection contacts_pvd_;
};

// A regular grid of cells in the plane z = 0: cell (j, i) spans x0 + [i, i+1] cell, y0 + [j, j+1] cell.
struct ImageGrid {
  double x0 = 0.0, y0 = 0.0;  // lower-left corner [m]
  double cell = 1.0;          // cell size [m]
  int nx = 1, ny = 1;         // cells along x and y
  std::size_t cells() const { return static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny); }
};

// One cell-centred array: values [ny * nx * components], x fastest. Two-component arrays are written as 3-vectors
// with z = 0 so ParaView can draw them as glyphs and stream lines.
struct CellField {
  std::string name;
  int components = 1;
  std::span<const float> values;
};

// A series of grids as VTK image data: DIR/<stem>.pvd and DIR/<stem>/<stem>_NNNNNN.vti, written like the floe
// frames (temporary file + rename, collection rewritten after each complete frame).
class VtkImageSeriesWriter {
 public:
  VtkImageSeriesWriter(const std::filesystem::path& dir, std::string stem, const ImageGrid& grid,
                       OutputManifest* manifest = nullptr);
  // Writes frame number frames() at `time` [s] (step `step`). Throws IoError naming the file on failure, or if a
  // field's size does not match the grid.
  void write_frame(double time, std::uint64_t step, std::span<const CellField> fields);
  int frames() const { return frames_; }
  // As VtkSeriesWriter::resume.
  void resume(std::span<const double> frame_times);

 private:
  std::filesystem::path dir_;
  std::string stem_;
  ImageGrid grid_;
  OutputManifest* manifest_;
  int frames_ = 0;
  PvdCollection pvd_;
};

}  // namespace polyfloe::io
