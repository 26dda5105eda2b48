#include "formats/field_file.h"

#include <sstream>

#include "formats/atomic_file.h"
#include "formats/hdf5_file.h"

namespace polyfloe::io {

namespace fs = std::filesystem;
using hdf5::Dims;

namespace {

constexpr const char* kFormat = "polyfloe-ocean-field";
constexpr std::int64_t kFormatVersion = 1;
constexpr int kDeflateLevel =
    1;  // [1, 9]: with the shuffle filter, level 1 compresses a field nearly as well as 9, fastest
// Nodes (t x z x y x x) a field file may have: 2.4 GB of velocities as doubles, read twice over.
constexpr double kMaxFieldNodes = 1e8;

std::string dims_text(const Dims& d) {
  std::ostringstream os;
  os << "[";
  for (std::size_t i = 0; i < d.size(); ++i) os << (i ? ", " : "") << d[i];
  os << "]";
  return os.str();
}

[[noreturn]] void fail(const fs::path& path, const std::string& what) {
  throw FieldFileError(path.string() + ": " + what);
}

std::vector<double> read_axis(const fs::path& path, const hdf5::Group& root, const char* name, const char* unit) {
  if (!root.exists(name)) fail(path, std::string("no dataset /") + name + " (the " + unit + " axis)");
  const hdf5::Dataset d = root.open_dataset(name);
  if (d.rank() != 1) fail(path, std::string("/") + name + " must be 1-D, has shape " + dims_text(d.dims()));
  if (static_cast<double>(d.dims()[0]) > kMaxFieldNodes)
    fail(path, std::string("/") + name + " declares " + std::to_string(d.dims()[0]) + " values (at most " +
                   std::to_string(static_cast<long long>(kMaxFieldNodes)) + " nodes are read)");
  return d.read<double>();
}

}  // namespace

void write_field_file(const fs::path& path, const FieldFile& f) {
  const forcing::GridData& g = f.grid;
  if (std::string e = forcing::grid_data_error(g); !e.empty()) fail(path, "cannot write this field: " + e);
  const std::size_t total = g.u.size();
  if (!f.w.empty() && f.w.size() != total)
    fail(path,
         "cannot write this field: w has " + std::to_string(f.w.size()) + " values, expected " + std::to_string(total));
  std::vector<double> uvw(3 * total);
  for (std::size_t k = 0; k < total; ++k) {
    uvw[3 * k] = g.u[k];
    uvw[3 * k + 1] = g.v[k];
    uvw[3 * k + 2] = f.w.empty() ? 0.0 : f.w[k];
  }
  const fs::path tmp = temporary_sibling(path);
  try {
    hdf5::File file(tmp, hdf5::File::Mode::truncate);
    hdf5::Group& root = file.root();
    root.set_attribute("format", kFormat);
    root.set_attribute("format_version", kFormatVersion);
    root.set_attribute("source", f.info.source);
    root.set_attribute("created_by", f.info.created_by);
    for (auto [a, name, unit] : {std::tuple{&g.x, "x", "m"}, {&g.y, "y", "m"}, {&g.z, "z", "m"}, {&g.t, "t", "s"}})
      root.write_dataset<double>(name, *a).set_attribute("units", unit);
    // Chunked one snapshot a chunk and compressed (shuffle + deflate): land, still water and smooth currents
    // compress well, and a reader of one snapshot reads one chunk.
    hdf5::Dataset u = root.create_series("U", hdf5::dtype_of<double>(), Dims{g.z.size(), g.y.size(), g.x.size(), 3}, 1,
                                         kDeflateLevel);
    u.append_rows<double>(uvw, g.t.size());
    u.set_attribute("units", "m/s");
    root.write_dataset<std::uint8_t>("mask", g.wet, Dims{g.z.size(), g.y.size(), g.x.size()})
        .set_attribute("meaning", "1 = water, 0 = land or outside the fluid mesh");
    file.close();
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
  commit_file_atomic(tmp, path);
}

FieldFile read_field_file(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) fail(path, "no such file");
  if (!fs::is_regular_file(path, ec)) fail(path, "not a regular file");
  FieldFile f;
  try {
    const hdf5::File file(path, hdf5::File::Mode::read_only);
    const hdf5::Group& root = file.root();
    if (!root.has_attribute("format") || root.string_attribute("format") != kFormat)
      fail(path, std::string("not an ocean field file (the root attribute 'format' is not \"") + kFormat +
                     "\"; write one with `polyfloe field import`)");
    if (const std::int64_t v = root.has_attribute("format_version") ? root.int_attribute("format_version") : 0;
        v != kFormatVersion)
      fail(path, "format_version " + std::to_string(v) + " is not supported (this build reads version " +
                     std::to_string(kFormatVersion) + ")");
    if (root.has_attribute("source")) f.info.source = root.string_attribute("source");
    if (root.has_attribute("created_by")) f.info.created_by = root.string_attribute("created_by");
    forcing::GridData& g = f.grid;
    g.x = read_axis(path, root, "x", "x [m]");
    g.y = read_axis(path, root, "y", "y [m]");
    g.z = read_axis(path, root, "z", "z [m]");
    g.t = read_axis(path, root, "t", "time [s]");
    const Dims expect_u{g.t.size(), g.z.size(), g.y.size(), g.x.size(), 3};
    const Dims expect_mask{g.z.size(), g.y.size(), g.x.size()};
    for (auto [name, expect, what] :
         {std::tuple{"U", &expect_u, "[nt, nz, ny, nx, 3]"}, {"mask", &expect_mask, "[nz, ny, nx]"}}) {
      if (!root.exists(name)) fail(path, std::string("no dataset /") + name);
      const Dims d = root.open_dataset(name).dims();
      if (d != *expect)
        fail(path, std::string("/") + name + " has shape " + dims_text(d) + ", expected " + what + " = " +
                       dims_text(*expect) + " from the axes");
    }
    // Nodes counted in double before anything is allocated (a file may declare any shape).
    const double nodes = static_cast<double>(g.t.size()) * g.z.size() * g.y.size() * g.x.size();
    if (nodes > kMaxFieldNodes)
      fail(path, "the axes make " + dims_text(expect_u) + " = " + std::to_string(static_cast<long long>(nodes)) +
                     " nodes, " + std::to_string(static_cast<long long>(nodes * 3 * 8 / (1 << 20))) +
                     " MiB of velocities (at most " + std::to_string(static_cast<long long>(kMaxFieldNodes)) +
                     " nodes are read): import the case on a coarser grid or fewer times");
    const std::vector<double> uvw = root.open_dataset("U").read<double>();
    const std::size_t total = uvw.size() / 3;
    g.u.resize(total);
    g.v.resize(total);
    f.w.resize(total);
    for (std::size_t k = 0; k < total; ++k) {
      g.u[k] = uvw[3 * k];
      g.v[k] = uvw[3 * k + 1];
      f.w[k] = uvw[3 * k + 2];
    }
    g.wet = root.open_dataset("mask").read<std::uint8_t>();
  } catch (const FieldFileError&) {
    throw;
  } catch (const std::exception& e) {
    fail(path, std::string("cannot read: ") + e.what());
  }
  if (std::string e = forcing::grid_data_error(f.grid); !e.empty()) fail(path, e);
  return f;
}

}  // namespace polyfloe::io
