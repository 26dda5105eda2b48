// The HDF5 wrapper of hdf5_file.h: handles, objects and attributes, groups and files (datasets: hdf5_dataset.cpp).
#include "formats/hdf5_file.h"

#include <hdf5.h>

#include "formats/hdf5_detail.h"

#include <algorithm>
#include <type_traits>

namespace polyfloe::io::hdf5 {
namespace fs = std::filesystem;

static_assert(std::is_same_v<hid_t, std::int64_t>, "HDF5 >= 1.10 uses 64-bit identifiers");
static_assert(sizeof(hsize_t) == sizeof(std::uint64_t));

using namespace detail;

// ---------------------------------------------------------------------------------------------------- Handle

Handle::Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, -1)), where_(std::move(o.where_)) {}

Handle& Handle::operator=(Handle&& o) noexcept {
  if (this != &o) {
    reset();
    id_ = std::exchange(o.id_, -1);
    where_ = std::move(o.where_);
  }
  return *this;
}

std::int64_t Handle::release() noexcept { return std::exchange(id_, -1); }

void Handle::reset() noexcept {
  if (id_ < 0) return;
  const hid_t id = std::exchange(id_, -1);
  H5E_auto2_t old_func = nullptr;
  void* old_data = nullptr;
  H5Eget_auto2(H5E_DEFAULT, &old_func, &old_data);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  switch (H5Iget_type(id)) {
    case H5I_FILE: H5Fclose(id); break;
    case H5I_GROUP: H5Gclose(id); break;
    case H5I_DATASET: H5Dclose(id); break;
    case H5I_ATTR: H5Aclose(id); break;
    case H5I_DATASPACE: H5Sclose(id); break;
    case H5I_DATATYPE: H5Tclose(id); break;
    case H5I_GENPROP_LST: H5Pclose(id); break;
    default: H5Idec_ref(id); break;
  }
  H5Eset_auto2(H5E_DEFAULT, old_func, old_data);
}

// ---------------------------------------------------------------------------------------------------- Object

std::string Object::child_name(std::string_view child) const {
  if (name_ == "/") return "/" + std::string(child);
  return name_ + "/" + std::string(child);
}

std::string Object::where_of(std::string_view child) const { return file_.string() + ":" + child_name(child); }

bool Object::has_attribute(std::string_view attr) const {
  const std::string a(attr);
  ErrorScope scope(where());
  return scope.check(H5Aexists(handle_.id(), a.c_str()), "H5Aexists") > 0;
}

namespace {

// Removes an existing attribute and creates a scalar one of the given type.
Handle fresh_scalar_attribute(const ErrorScope& scope, hid_t owner, const std::string& name, hid_t type) {
  if (scope.check(H5Aexists(owner, name.c_str()), "H5Aexists") > 0) {
    scope.check(H5Adelete(owner, name.c_str()), "H5Adelete");
  }
  Handle space = scratch(scope, H5Screate(H5S_SCALAR), "H5Screate");
  return scratch(scope, H5Acreate2(owner, name.c_str(), type, space.id(), H5P_DEFAULT, H5P_DEFAULT), "H5Acreate2");
}

}  // namespace

void Object::set_attribute(std::string_view attr, std::string_view value) {
  const std::string a(attr), v(value);
  ErrorScope scope(where() + " attribute " + a);
  Handle type = variable_string_type(scope);
  Handle at = fresh_scalar_attribute(scope, handle_.id(), a, type.id());
  const char* p = v.c_str();
  scope.check(H5Awrite(at.id(), type.id(), &p), "H5Awrite");
}

void Object::set_attribute(std::string_view attr, double value) {
  const std::string a(attr);
  ErrorScope scope(where() + " attribute " + a);
  Handle at = fresh_scalar_attribute(scope, handle_.id(), a, H5T_IEEE_F64LE);
  scope.check(H5Awrite(at.id(), H5T_NATIVE_DOUBLE, &value), "H5Awrite");
}

void Object::set_attribute(std::string_view attr, std::int64_t value) {
  const std::string a(attr);
  ErrorScope scope(where() + " attribute " + a);
  Handle at = fresh_scalar_attribute(scope, handle_.id(), a, H5T_STD_I64LE);
  scope.check(H5Awrite(at.id(), H5T_NATIVE_INT64, &value), "H5Awrite");
}

std::string Object::string_attribute(std::string_view attr) const {
  const std::string a(attr);
  ErrorScope scope(where() + " attribute " + a);
  Handle at = scratch(scope, H5Aopen(handle_.id(), a.c_str(), H5P_DEFAULT), "H5Aopen");
  Handle ftype = scratch(scope, H5Aget_type(at.id()), "H5Aget_type");
  if (H5Tget_class(ftype.id()) != H5T_STRING) scope.fail("reading a string (the attribute is not one)");
  if (scope.check(H5Tis_variable_str(ftype.id()), "H5Tis_variable_str") > 0) {
    Handle mtype = variable_string_type(scope);
    char* p = nullptr;
    scope.check(H5Aread(at.id(), mtype.id(), &p), "H5Aread");
    std::string out = p ? p : "";
    H5free_memory(p);
    return out;
  }
  const std::size_t size = H5Tget_size(ftype.id());
  Handle mtype = scratch(scope, H5Tcopy(H5T_C_S1), "H5Tcopy");
  scope.check(H5Tset_size(mtype.id(), size + 1), "H5Tset_size");
  scope.check(H5Tset_strpad(mtype.id(), H5T_STR_NULLTERM), "H5Tset_strpad");
  std::string buf(size + 1, '\0');
  scope.check(H5Aread(at.id(), mtype.id(), buf.data()), "H5Aread");
  buf.resize(buf.find('\0'));
  if (H5Tget_strpad(ftype.id()) == H5T_STR_SPACEPAD) {
    buf.erase(buf.find_last_not_of(' ') + 1);
  }
  return buf;
}

double Object::double_attribute(std::string_view attr) const {
  const std::string a(attr);
  ErrorScope scope(where() + " attribute " + a);
  Handle at = scratch(scope, H5Aopen(handle_.id(), a.c_str(), H5P_DEFAULT), "H5Aopen");
  double value = 0.0;
  scope.check(H5Aread(at.id(), H5T_NATIVE_DOUBLE, &value), "H5Aread");
  return value;
}

std::int64_t Object::int_attribute(std::string_view attr) const {
  const std::string a(attr);
  ErrorScope scope(where() + " attribute " + a);
  Handle at = scratch(scope, H5Aopen(handle_.id(), a.c_str(), H5P_DEFAULT), "H5Aopen");
  std::int64_t value = 0;
  scope.check(H5Aread(at.id(), H5T_NATIVE_INT64, &value), "H5Aread");
  return value;
}

// ----------------------------------------------------------------------------------------------------- Group

std::vector<Group::Child> Group::children() const {
  ErrorScope scope(where());
  std::vector<Child> out;
  auto visit = [](hid_t group, const char* name, const H5L_info_t*, void* data) -> herr_t {
    auto* list = static_cast<std::vector<Child>*>(data);
    H5O_info_t info;
    if (H5Oget_info_by_name2(group, name, &info, H5O_INFO_BASIC, H5P_DEFAULT) < 0) return -1;
    list->push_back({name, info.type == H5O_TYPE_GROUP});
    return 0;
  };
  scope.check(H5Literate(handle_.id(), H5_INDEX_NAME, H5_ITER_INC, nullptr, visit, &out), "H5Literate");
  return out;
}

void Group::append_series_rows_from(const Group& from, std::uint64_t rows) const {
  for (const Child& c : children()) {
    auto missing = [&] {
      return IoError(from.where() + "/" + c.name + ": missing in the file of the interrupted run");
    };
    if (c.group) {
      if (!from.exists(c.name)) throw missing();
      open_group(c.name).append_series_rows_from(from.open_group(c.name), rows);
      continue;
    }
    Dataset to = open_dataset(c.name);
    if (!to.extendible()) continue;
    if (!from.exists(c.name)) throw missing();
    const Dataset source = from.open_dataset(c.name);
    if (source.rows() < rows)
      throw IoError(source.where() + ": has " + std::to_string(source.rows()) + " frames, the restart needs " +
                    std::to_string(rows));
    to.append_rows_from(source, rows);
  }
}

bool Group::exists(std::string_view child) const {
  const std::string c(child);
  ErrorScope scope(where_of(child));
  return scope.check(H5Lexists(handle_.id(), c.c_str(), H5P_DEFAULT), "H5Lexists") > 0;
}

Group Group::create_group(std::string_view child) {
  const std::string c(child), w = where_of(child);
  ErrorScope scope(w);
  Handle lcpl = intermediate_groups(scope);
  const hid_t id = scope.check(H5Gcreate2(handle_.id(), c.c_str(), lcpl.id(), H5P_DEFAULT, H5P_DEFAULT), "H5Gcreate2");
  return Group(Handle(id, w), child_name(child), file_);
}

Group Group::open_group(std::string_view child) const {
  const std::string c(child), w = where_of(child);
  ErrorScope scope(w);
  const hid_t id = scope.check(H5Gopen2(handle_.id(), c.c_str(), H5P_DEFAULT), "H5Gopen2");
  return Group(Handle(id, w), child_name(child), file_);
}

Group Group::require_group(std::string_view child) { return exists(child) ? open_group(child) : create_group(child); }

Dataset Group::create_dataset(std::string_view child, DType type, const Dims& dims) {
  const std::string c(child), w = where_of(child);
  ErrorScope scope(w);
  if (dims.empty()) scope.fail("creating a dataset of rank 0");
  const auto d = to_hsize(dims);
  Handle space = scratch(scope, H5Screate_simple(static_cast<int>(d.size()), d.data(), nullptr), "H5Screate_simple");
  Handle lcpl = intermediate_groups(scope);
  const hid_t id =
      scope.check(H5Dcreate2(handle_.id(), c.c_str(), file_type(type), space.id(), lcpl.id(), H5P_DEFAULT, H5P_DEFAULT),
                  "H5Dcreate2");
  return Dataset(Handle(id, w), child_name(child), file_);
}

Dataset Group::create_series(std::string_view child, DType type, const Dims& row_dims, std::uint64_t chunk_rows,
                             int deflate_level) {
  const std::string c(child), w = where_of(child);
  ErrorScope scope(w);
  const std::size_t rank = row_dims.size() + 1;
  std::vector<hsize_t> dims(rank, 0), max_dims(rank, H5S_UNLIMITED), chunk(rank, 1);
  hsize_t row_bytes = H5Tget_size(file_type(type));
  for (std::size_t k = 1; k < rank; ++k) {
    dims[k] = row_dims[k - 1];
    // A zero extent can only be chunked if it may grow; any other extent is fixed.
    if (dims[k] > 0) max_dims[k] = dims[k];
    chunk[k] = std::max<hsize_t>(dims[k], 1);
    row_bytes *= chunk[k];
  }
  // Keep a chunk well under HDF5's 4 GiB limit, and at least one row.
  constexpr hsize_t kMaxChunkBytes = hsize_t{1} << 28;
  chunk[0] = std::clamp<hsize_t>(chunk_rows, 1, std::max<hsize_t>(1, kMaxChunkBytes / row_bytes));

  Handle space =
      scratch(scope, H5Screate_simple(static_cast<int>(rank), dims.data(), max_dims.data()), "H5Screate_simple");
  Handle dcpl = scratch(scope, H5Pcreate(H5P_DATASET_CREATE), "H5Pcreate");
  scope.check(H5Pset_chunk(dcpl.id(), static_cast<int>(rank), chunk.data()), "H5Pset_chunk");
  if (deflate_level > 0 && H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) {
    scope.check(H5Pset_shuffle(dcpl.id()), "H5Pset_shuffle");
    scope.check(H5Pset_deflate(dcpl.id(), static_cast<unsigned>(std::min(deflate_level, 9))), "H5Pset_deflate");
  }
  Handle lcpl = intermediate_groups(scope);
  const hid_t id =
      scope.check(H5Dcreate2(handle_.id(), c.c_str(), file_type(type), space.id(), lcpl.id(), dcpl.id(), H5P_DEFAULT),
                  "H5Dcreate2");
  return Dataset(Handle(id, w), child_name(child), file_);
}

Dataset Group::open_dataset(std::string_view child) const {
  const std::string c(child), w = where_of(child);
  ErrorScope scope(w);
  const hid_t id = scope.check(H5Dopen2(handle_.id(), c.c_str(), H5P_DEFAULT), "H5Dopen2");
  return Dataset(Handle(id, w), child_name(child), file_);
}

// ------------------------------------------------------------------------------------------------------ File

File::File(const fs::path& path, Mode mode) : path_(path) {
  const std::string name = path.string();
  ErrorScope scope(name);
  hid_t id = -1;
  // New files use the latest format, which single-writer/multiple-reader (SWMR) writing needs (start_swmr_write).
  Handle fapl = scratch(scope, H5Pcreate(H5P_FILE_ACCESS), "H5Pcreate");
  if (mode == Mode::truncate || mode == Mode::exclusive)
    scope.check(H5Pset_libver_bounds(fapl.id(), H5F_LIBVER_LATEST, H5F_LIBVER_LATEST), "H5Pset_libver_bounds");
  switch (mode) {
    case Mode::truncate: id = H5Fcreate(name.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.id()); break;
    case Mode::exclusive: id = H5Fcreate(name.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, fapl.id()); break;
    case Mode::read_only:
      id = H5Fopen(name.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
      // A file whose SWMR writer is still running, or was killed, is marked as open for writing: it is read as a
      // SWMR reader, which sees it as of the writer's last flush. A SWMR reader retries a metadata block whose
      // checksum fails (it may be in the middle of a write), by default 100 times with a doubling sleep: on a block
      // that a killed writer left torn that never ends. A few tries, then an error.
      if (id < 0) {
        scope.check(H5Pset_metadata_read_attempts(fapl.id(), 4), "H5Pset_metadata_read_attempts");
        id = H5Fopen(name.c_str(), H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, fapl.id());
      }
      break;
    case Mode::read_write: id = H5Fopen(name.c_str(), H5F_ACC_RDWR, H5P_DEFAULT); break;
  }
  file_ = Handle(scope.check(id, mode == Mode::truncate || mode == Mode::exclusive ? "H5Fcreate" : "H5Fopen"), name);
  const hid_t root = scope.check(H5Gopen2(file_.id(), "/", H5P_DEFAULT), "H5Gopen2");
  root_ = Group(Handle(root, name + ":/"), "/", path_);
}

void File::start_swmr_write() {
  ErrorScope scope(path_.string());
  scope.check(H5Fstart_swmr_write(file_.id()), "H5Fstart_swmr_write");
}

void File::flush() {
  ErrorScope scope(path_.string());
  scope.check(H5Fflush(file_.id(), H5F_SCOPE_GLOBAL), "H5Fflush");
}

void File::close() {
  if (!file_.valid()) return;
  root_ = Group();
  ErrorScope scope(path_.string());
  scope.check(H5Fclose(static_cast<hid_t>(file_.release())), "H5Fclose");
}

}  // namespace polyfloe::io::hdf5
