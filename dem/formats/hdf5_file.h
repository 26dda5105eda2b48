// A small RAII wrapper over the HDF5 C API: files, groups, datasets and attributes, for series output and
// checkpoints. HDF5 itself stays behind this header (only the .cpp includes it).
//
// Every failing HDF5 call throws Hdf5Error whose message names the file and object ("run.h5:/state/position")
// and carries HDF5's own error stack. HDF5's automatic error printing is suspended inside each wrapper call
// (and restored afterwards), so nothing is printed to stderr behind the caller's back.
//
// Datasets are either fixed (shape given at creation) or extendible along dimension 0 (a time series: rows are
// appended one frame at a time, chunked by rows). Element types are chosen by the C++ type (see DType).
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "formats/atomic_file.h"

namespace polyfloe::io::hdf5 {

class Hdf5Error : public IoError {
 public:
  using IoError::IoError;
};

// Element types stored in files (native byte order in memory; HDF5 converts on read).
enum class DType : std::uint8_t { f32, f64, i8, u8, i32, u32, i64, u64 };

template <class T>
constexpr DType dtype_of() {
  if constexpr (std::is_same_v<T, float>)
    return DType::f32;
  else if constexpr (std::is_same_v<T, double>)
    return DType::f64;
  else if constexpr (std::is_same_v<T, std::int8_t>)
    return DType::i8;
  else if constexpr (std::is_same_v<T, std::uint8_t>)
    return DType::u8;
  else if constexpr (std::is_same_v<T, std::int32_t>)
    return DType::i32;
  else if constexpr (std::is_same_v<T, std::uint32_t>)
    return DType::u32;
  else if constexpr (std::is_same_v<T, std::int64_t>)
    return DType::i64;
  else if constexpr (std::is_same_v<T, std::uint64_t>)
    return DType::u64;
  else
    static_assert(sizeof(T) == 0, "unsupported HDF5 element type");
}

using Dims = std::vector<std::uint64_t>;

// Owns one HDF5 identifier (file, group, dataset, attribute, ...) and closes it with the matching H5*close.
// `where` names it for error messages: "file.h5:/group/name".
class Handle {
 public:
  Handle() = default;
  Handle(std::int64_t id, std::string where) : id_(id), where_(std::move(where)) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& o) noexcept;
  Handle& operator=(Handle&& o) noexcept;
  ~Handle() { reset(); }

  std::int64_t id() const { return id_; }
  bool valid() const { return id_ >= 0; }
  const std::string& where() const { return where_; }
  void reset() noexcept;            // closes now (errors on close are ignored here; File::close() reports them)
  std::int64_t release() noexcept;  // gives up ownership without closing

 private:
  std::int64_t id_ = -1;
  std::string where_;
};

// Something that carries attributes: a group (the file's root included) or a dataset.
class Object {
 public:
  const std::string& where() const { return handle_.where(); }  // "file.h5:/path"
  const std::string& name() const { return name_; }             // "/path" inside the file

  bool has_attribute(std::string_view attr) const;
  // Creates or replaces a scalar attribute. Strings are stored as variable-length UTF-8 (any length).
  void set_attribute(std::string_view attr, std::string_view value);
  void set_attribute(std::string_view attr, const char* value) { set_attribute(attr, std::string_view(value)); }
  void set_attribute(std::string_view attr, double value);
  void set_attribute(std::string_view attr, std::int64_t value);
  // Reads a scalar attribute (strings: fixed or variable length; numbers: converted).
  std::string string_attribute(std::string_view attr) const;
  double double_attribute(std::string_view attr) const;
  std::int64_t int_attribute(std::string_view attr) const;

 protected:
  Object() = default;
  Object(Handle handle, std::string name, std::filesystem::path file)
      : handle_(std::move(handle)), name_(std::move(name)), file_(std::move(file)) {}
  std::string child_name(std::string_view child) const;  // name of a child of this group
  std::string where_of(std::string_view child) const;    // file:child_name

  Handle handle_;
  std::string name_;
  std::filesystem::path file_;
};

class Dataset : public Object {
 public:
  Dataset() = default;

  Dims dims() const;  // current extent
  int rank() const { return static_cast<int>(dims().size()); }
  DType dtype() const;
  std::uint64_t rows() const;  // extent of dimension 0

  // Whole dataset: data.size() must equal the product of dims().
  template <class T>
  void write(std::span<const T> data) {
    write_raw(data.data(), dtype_of<T>(), data.size());
  }
  // Appends data.size() / row_size rows along dimension 0 of an extendible dataset; data.size() must be a
  // positive multiple of the row size (the product of dims 1..rank-1).
  template <class T>
  void append(std::span<const T> data) {
    append_raw(data.data(), dtype_of<T>(), data.size(), kRowsFromSize);
  }
  // Appends `rows` rows (data.size() == rows * row size); also works when a row is empty (e.g. [T, 0, 3]).
  template <class T>
  void append_rows(std::span<const T> data, std::uint64_t rows) {
    append_raw(data.data(), dtype_of<T>(), data.size(), rows);
  }
  template <class T>
  std::vector<T> read() const {
    std::vector<T> out(element_count(dims()));
    read_rows_raw(out.data(), dtype_of<T>(), 0, rows(), out.size());
    return out;
  }
  // Rows [first, first + count) of dimension 0, flattened.
  template <class T>
  std::vector<T> read_rows(std::uint64_t first, std::uint64_t count) const {
    const Dims d = dims();
    std::vector<T> out(count * row_size(d));
    read_rows_raw(out.data(), dtype_of<T>(), first, count, out.size());
    return out;
  }

  // True for a series: unlimited along dimension 0.
  bool extendible() const;
  // Appends rows [0, rows) of `source` (same element type class and row shape), a bounded number of rows at a time.
  void append_rows_from(const Dataset& source, std::uint64_t rows);

  static std::uint64_t element_count(const Dims& dims);
  static std::uint64_t row_size(const Dims& dims);  // product of dims 1..rank-1 (1 for rank 1)

 private:
  friend class Group;
  Dataset(Handle handle, std::string name, std::filesystem::path file)
      : Object(std::move(handle), std::move(name), std::move(file)) {}
  void write_raw(const void* data, DType type, std::size_t count);
  static constexpr std::uint64_t kRowsFromSize = ~std::uint64_t{0};
  void append_raw(const void* data, DType type, std::size_t count, std::uint64_t rows);
  void read_rows_raw(void* out, DType type, std::uint64_t first, std::uint64_t count, std::size_t size) const;
};

class Group : public Object {
 public:
  Group() = default;

  bool exists(std::string_view child) const;  // a link of that name (group or dataset)
  struct Child {
    std::string name;
    bool group = false;  // else a dataset (or another object kind: named types are not used here)
  };
  std::vector<Child> children() const;  // in name order
  Group create_group(std::string_view child);
  Group open_group(std::string_view child) const;
  // Opens the child group, creating it when absent.
  Group require_group(std::string_view child);

  // Fixed-shape dataset (any rank >= 1; zero extents allowed). Contents are written separately.
  Dataset create_dataset(std::string_view child, DType type, const Dims& dims);
  // Creates a fixed dataset of shape `dims` holding `data` (data.size() == product of dims).
  template <class T>
  Dataset write_dataset(std::string_view child, std::span<const T> data, const Dims& dims) {
    Dataset d = create_dataset(child, dtype_of<T>(), dims);
    d.write(data);
    return d;
  }
  // Shorthand for a 1-D dataset.
  template <class T>
  Dataset write_dataset(std::string_view child, std::span<const T> data) {
    return write_dataset(child, data, Dims{data.size()});
  }
  // Extendible dataset of shape [0, row_dims...] (rank 1 + row_dims.size()), unlimited along dimension 0,
  // chunked by `chunk_rows` rows, optionally shuffle+deflate compressed (level 1..9; 0 = none).
  Dataset create_series(std::string_view child, DType type, const Dims& row_dims, std::uint64_t chunk_rows,
                        int deflate_level = 0);
  Dataset open_dataset(std::string_view child) const;
  // A run's restart: appends the first `rows` rows of every series (extendible dataset) under this group, at any
  // depth, from the dataset of the same path under `from`. Throws IoError naming a series that `from` lacks or
  // that has fewer rows. Fixed datasets are left as they are.
  void append_series_rows_from(const Group& from, std::uint64_t rows) const;

 private:
  friend class File;
  Group(Handle handle, std::string name, std::filesystem::path file)
      : Object(std::move(handle), std::move(name), std::move(file)) {}
};

// Sets the "units" attribute of a dataset and, where given, its "description".
inline void units(Dataset& d, const char* u, const char* description = nullptr) {
  d.set_attribute("units", u);
  if (description) d.set_attribute("description", description);
}
inline void units(Dataset&& d, const char* u, const char* description = nullptr) { units(d, u, description); }

class File {
 public:
  enum class Mode {
    truncate,   // create, replacing an existing file
    exclusive,  // create, failing if the file exists
    read_only,
    read_write,
  };
  File(const std::filesystem::path& path, Mode mode);
  File(File&&) noexcept = default;
  File& operator=(File&&) noexcept = default;
  ~File() = default;  // closes quietly; call close() to see errors

  Group& root() { return root_; }
  const Group& root() const { return root_; }
  const std::filesystem::path& path() const { return path_; }

  // Writes everything buffered (data and metadata) to the file, so it reads back as it is now.
  void flush();
  // Switches a new file to single-writer/multiple-reader mode: from now on no object or attribute may be created,
  // only series appended, and HDF5 orders its metadata writes so that the file on disk is consistent at every
  // moment (a kill in the middle of a flush leaves the previous flush readable; readers, this class's read_only
  // mode among them, may open it while it is written).
  void start_swmr_write();
  // Closes the file (after this only destruction is valid). Throws on failure.
  void close();

 private:
  std::filesystem::path path_;
  Handle file_;
  Group root_;
};

}  // namespace polyfloe::io::hdf5
