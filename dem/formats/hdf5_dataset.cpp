// The HDF5 wrapper's datasets (hdf5_file.h): extents and types, writing, appending rows (the time series),
// reading rows, and copying rows from another file's dataset.
#include "formats/hdf5_file.h"

#include <hdf5.h>

#include <algorithm>
#include <string>
#include <vector>

#include "formats/hdf5_detail.h"

namespace polyfloe::io::hdf5 {

using namespace detail;

// --------------------------------------------------------------------------------------------------- Dataset

std::uint64_t Dataset::element_count(const Dims& dims) {
  std::uint64_t n = 1;
  for (auto d : dims) n *= d;
  return n;
}

std::uint64_t Dataset::row_size(const Dims& dims) {
  std::uint64_t n = 1;
  for (std::size_t k = 1; k < dims.size(); ++k) n *= dims[k];
  return n;
}

Dims Dataset::dims() const {
  ErrorScope scope(where());
  Handle space = scratch(scope, H5Dget_space(handle_.id()), "H5Dget_space");
  const int rank = scope.check(H5Sget_simple_extent_ndims(space.id()), "H5Sget_simple_extent_ndims");
  std::vector<hsize_t> d(static_cast<std::size_t>(rank));
  scope.check(H5Sget_simple_extent_dims(space.id(), d.data(), nullptr), "H5Sget_simple_extent_dims");
  return {d.begin(), d.end()};
}

std::uint64_t Dataset::rows() const {
  const Dims d = dims();
  return d.empty() ? 1 : d[0];
}

DType Dataset::dtype() const {
  ErrorScope scope(where());
  Handle t = scratch(scope, H5Dget_type(handle_.id()), "H5Dget_type");
  const std::size_t size = H5Tget_size(t.id());
  switch (H5Tget_class(t.id())) {
    case H5T_FLOAT:
      if (size == 4) return DType::f32;
      if (size == 8) return DType::f64;
      break;
    case H5T_INTEGER: {
      const bool is_signed = H5Tget_sign(t.id()) == H5T_SGN_2;
      if (size == 1) return is_signed ? DType::i8 : DType::u8;
      if (size == 4) return is_signed ? DType::i32 : DType::u32;
      if (size == 8) return is_signed ? DType::i64 : DType::u64;
      break;
    }
    default: break;
  }
  scope.fail("mapping its element type (unsupported class or size)");
}

void Dataset::write_raw(const void* data, DType type, std::size_t count) {
  const Dims d = dims();
  ErrorScope scope(where());
  if (count != element_count(d)) {
    scope.fail("writing " + std::to_string(count) + " values into " + std::to_string(element_count(d)) + " elements");
  }
  if (count == 0) return;
  scope.check(H5Dwrite(handle_.id(), memory_type(type), H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "H5Dwrite");
}

void Dataset::append_raw(const void* data, DType type, std::size_t count, std::uint64_t rows) {
  Dims d = dims();
  ErrorScope scope(where());
  if (d.empty()) scope.fail("appending to a scalar dataset");
  const std::uint64_t row = row_size(d);
  if (rows == kRowsFromSize) {
    if (row == 0 || count == 0 || count % row != 0) {
      scope.fail("appending " + std::to_string(count) + " values in rows of " + std::to_string(row));
    }
    rows = count / row;
  } else if (rows * row != count) {
    scope.fail("appending " + std::to_string(rows) + " rows of " + std::to_string(row) + " from " +
               std::to_string(count) + " values");
  }
  if (rows == 0) return;
  std::vector<hsize_t> start(d.size(), 0), extent = to_hsize(d);
  start[0] = d[0];
  extent[0] = d[0] + rows;
  scope.check(H5Dset_extent(handle_.id(), extent.data()), "H5Dset_extent");
  if (count == 0) return;
  std::vector<hsize_t> block = to_hsize(d);
  block[0] = rows;
  Handle fspace = scratch(scope, H5Dget_space(handle_.id()), "H5Dget_space");
  scope.check(H5Sselect_hyperslab(fspace.id(), H5S_SELECT_SET, start.data(), nullptr, block.data(), nullptr),
              "H5Sselect_hyperslab");
  const hsize_t n = count;
  Handle mspace = scratch(scope, H5Screate_simple(1, &n, nullptr), "H5Screate_simple");
  scope.check(H5Dwrite(handle_.id(), memory_type(type), mspace.id(), fspace.id(), H5P_DEFAULT, data), "H5Dwrite");
}

void Dataset::read_rows_raw(void* out, DType type, std::uint64_t first, std::uint64_t count, std::size_t size) const {
  const Dims d = dims();
  ErrorScope scope(where());
  if (d.empty()) {  // scalar
    if (first != 0 || count != 1 || size != 1) scope.fail("reading rows of a scalar dataset");
    scope.check(H5Dread(handle_.id(), memory_type(type), H5S_ALL, H5S_ALL, H5P_DEFAULT, out), "H5Dread");
    return;
  }
  if (first + count > d[0]) {
    scope.fail("reading rows " + std::to_string(first) + ".." + std::to_string(first + count) + " of " +
               std::to_string(d[0]));
  }
  if (size == 0) return;
  std::vector<hsize_t> start(d.size(), 0), block = to_hsize(d);
  start[0] = first;
  block[0] = count;
  Handle fspace = scratch(scope, H5Dget_space(handle_.id()), "H5Dget_space");
  scope.check(H5Sselect_hyperslab(fspace.id(), H5S_SELECT_SET, start.data(), nullptr, block.data(), nullptr),
              "H5Sselect_hyperslab");
  const hsize_t n = size;
  Handle mspace = scratch(scope, H5Screate_simple(1, &n, nullptr), "H5Screate_simple");
  scope.check(H5Dread(handle_.id(), memory_type(type), mspace.id(), fspace.id(), H5P_DEFAULT, out), "H5Dread");
}

bool Dataset::extendible() const {
  ErrorScope scope(where());
  Handle space = scratch(scope, H5Dget_space(handle_.id()), "H5Dget_space");
  const int rank = scope.check(H5Sget_simple_extent_ndims(space.id()), "H5Sget_simple_extent_ndims");
  if (rank < 1) return false;
  std::vector<hsize_t> d(static_cast<std::size_t>(rank)), max(static_cast<std::size_t>(rank));
  scope.check(H5Sget_simple_extent_dims(space.id(), d.data(), max.data()), "H5Sget_simple_extent_dims");
  return max[0] == H5S_UNLIMITED;
}

void Dataset::append_rows_from(const Dataset& source, std::uint64_t rows) {
  const Dims from = source.dims(), to = dims();
  if (from.size() != to.size() ||
      !std::equal(from.begin() + (from.empty() ? 0 : 1), from.end(), to.begin() + (to.empty() ? 0 : 1))) {
    ErrorScope(where()).fail("copying rows from " + source.where() + " (a different row shape)");
  }
  if (!from.empty() && rows > from[0]) {
    ErrorScope(where()).fail("copying " + std::to_string(rows) + " rows from " + source.where() + ", which has " +
                             std::to_string(from[0]));
  }
  const DType type = source.dtype();
  const std::uint64_t row = row_size(from);
  std::size_t bytes = 8;
  if (type == DType::f32 || type == DType::i32 || type == DType::u32) bytes = 4;
  if (type == DType::i8 || type == DType::u8) bytes = 1;
  // About 64 MiB at a time, at least one row.
  const std::uint64_t batch =
      std::max<std::uint64_t>(1, (std::uint64_t{64} << 20) / std::max<std::uint64_t>(1, row * bytes));
  std::vector<std::uint64_t> buffer;  // 8-byte aligned for every type
  for (std::uint64_t first = 0; first < rows; first += batch) {
    const std::uint64_t count = std::min(batch, rows - first);
    const std::size_t values = count * row;
    buffer.resize((values * bytes + 7) / 8 + 1);
    source.read_rows_raw(buffer.data(), type, first, count, values);
    append_raw(buffer.data(), type, values, count);
  }
}

}  // namespace polyfloe::io::hdf5
