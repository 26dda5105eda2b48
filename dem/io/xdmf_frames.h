// results.xmf: the frames of a planar run's results.h5 as ParaView's XDMF readers read them. ParaView's Xdmf3
// readers (its default) cannot read a frame out of a time series: they drop an attribute given as a hyperslab and
// crash on a geometry given as one. So every array results.xmf names is a whole dataset, in files of their own
// beside it: xdmf/frames_FIRST-LAST.h5, one per write() with the frames written since the last, each written
// atomically and not changed after (results.xmf opens while the run goes on; a restart rewrites the files of
// frames past its checkpoint). Each holds
//   /time [k] [s], /floes/id [N] uint64, thickness [N] [m], motion [N] int8, topology [L] int64 (XDMF's mixed
//   topology: per body 3, its vertex count, its rows of vertices_xy), and per frame K (global index, 6 digits)
//   /frames/K/vertices_xy [V,2] float32 [m], velocity [N,3] [m/s], angular_velocity [N,3] [rad/s],
// copied from results.h5's rows.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace polyfloe::io {

class OutputManifest;
namespace hdf5 {
class Group;
}

class XdmfFrames {
 public:
  // What does not change of the bodies, in results.h5's order.
  struct Bodies {
    std::vector<std::uint64_t> id;
    std::vector<double> thickness;
    std::vector<std::int8_t> motion;
    std::vector<std::int64_t> topology;
    std::uint64_t vertices = 0;  // V, the rows of state/vertices_xy
  };
  explicit XdmfFrames(Bodies bodies) : bodies_(std::move(bodies)) {}

  // Writes the frames of `results` (results.h5's root, flushed: its time and state/ series) not yet in a file
  // into a new xdmf/ file beside `xmf`, then `xmf` itself (atomically) naming every frame. `results_name`: the
  // results file's name, for the texts. With `manifest` (the output folder's), the files are listed in it; on the
  // first call, the interrupted run's files it lists (a restart) are kept where they hold only adopted frames
  // (adopt()), from frame 0 on, with results.h5's times bit for bit; the others are removed once `xmf` is written
  // (a file of the same name is rewritten in place first: the one change a file sees after it is written). Throws
  // IoError naming the file.
  void write(const hdf5::Group& results, const std::string& results_name, const std::filesystem::path& xmf,
             OutputManifest* manifest);
  // A restart: frames 0..frames-1 are the interrupted run's (results.h5 adopted them), the files that hold only
  // those may be kept.
  void adopt(int frames) { adopted_ = frames; }

 private:
  struct Batch {
    int first = 0, last = 0;  // frames first..last
    std::string name;         // relative to the folder of results.xmf
  };
  void scan(const std::filesystem::path& folder, OutputManifest* manifest, const std::vector<double>& times);
  void write_batch(const hdf5::Group& results, const std::string& results_name, const std::filesystem::path& folder,
                   OutputManifest* manifest, int first, int last, const std::vector<double>& times);
  void write_xmf(const std::string& results_name, const std::filesystem::path& xmf,
                 const std::vector<double>& times) const;

  Bodies bodies_;
  std::vector<Batch> batches_;
  bool scanned_ = false;
  int adopted_ = 0;                 // frames a restart took over from the interrupted run
  std::vector<std::string> stale_;  // an interrupted run's files this run does not keep
};

}  // namespace polyfloe::io
