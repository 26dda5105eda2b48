// Pieces of the HDF5 wrapper that hdf5_file.cpp and hdf5_dataset.cpp share (internal to dem/io: it includes
// hdf5.h): the error scope that turns HDF5's error stack into an Hdf5Error naming the object, and the type maps.
#pragma once

#include <hdf5.h>

#include <string>
#include <vector>

#include "formats/hdf5_file.h"

namespace polyfloe::io::hdf5::detail {

// While alive, HDF5's automatic error report goes to this object instead of stderr: the error callback walks
// the error stack of a failing API call into `messages`, and check() turns it into an Hdf5Error naming the
// object. The previous handler is restored on destruction, so other HDF5 users in the process are unaffected.
class ErrorScope {
 public:
  explicit ErrorScope(std::string where) : where_(std::move(where)) {
    H5Eget_auto2(H5E_DEFAULT, &old_func_, &old_data_);
    H5Eset_auto2(H5E_DEFAULT, &ErrorScope::on_error, this);
  }
  ErrorScope(const ErrorScope&) = delete;
  ErrorScope& operator=(const ErrorScope&) = delete;
  ~ErrorScope() { H5Eset_auto2(H5E_DEFAULT, old_func_, old_data_); }

  // Throws if `rc` is negative (HDF5's failure value for herr_t, hid_t, htri_t and ssize_t).
  template <class R>
  R check(R rc, const char* call) const {
    if (rc < 0) fail(call);
    return rc;
  }
  [[noreturn]] void fail(const std::string& what) const {
    std::string msg = where_ + ": " + what + " failed";
    if (!messages_.empty()) msg += " (" + messages_ + ")";
    throw Hdf5Error(msg);
  }

 private:
  static herr_t on_error(hid_t stack, void* client) noexcept {
    auto* self = static_cast<ErrorScope*>(client);
    try {
      self->messages_.clear();  // the latest failure's stack (a call retried in another mode fails twice)
      H5Ewalk2(stack, H5E_WALK_DOWNWARD, &ErrorScope::on_frame, &self->messages_);
    } catch (...) {
      // out of memory while formatting: the exception still follows, only less detailed
    }
    return 0;
  }
  static herr_t on_frame(unsigned n, const H5E_error2_t* e, void* client) {
    auto* messages = static_cast<std::string*>(client);
    if (n > 0) *messages += "; ";
    *messages += e->func_name ? e->func_name : "?";
    *messages += ": ";
    *messages += e->desc ? e->desc : "?";
    return 0;
  }

  std::string where_;
  std::string messages_;
  H5E_auto2_t old_func_ = nullptr;
  void* old_data_ = nullptr;
};

inline hid_t memory_type(DType t) {
  switch (t) {
    case DType::f32: return H5T_NATIVE_FLOAT;
    case DType::f64: return H5T_NATIVE_DOUBLE;
    case DType::i8: return H5T_NATIVE_INT8;
    case DType::u8: return H5T_NATIVE_UINT8;
    case DType::i32: return H5T_NATIVE_INT32;
    case DType::u32: return H5T_NATIVE_UINT32;
    case DType::i64: return H5T_NATIVE_INT64;
    case DType::u64: return H5T_NATIVE_UINT64;
  }
  return H5T_NATIVE_DOUBLE;
}

// Stored types: little-endian standard types, whatever the machine.
inline hid_t file_type(DType t) {
  switch (t) {
    case DType::f32: return H5T_IEEE_F32LE;
    case DType::f64: return H5T_IEEE_F64LE;
    case DType::i8: return H5T_STD_I8LE;
    case DType::u8: return H5T_STD_U8LE;
    case DType::i32: return H5T_STD_I32LE;
    case DType::u32: return H5T_STD_U32LE;
    case DType::i64: return H5T_STD_I64LE;
    case DType::u64: return H5T_STD_U64LE;
  }
  return H5T_IEEE_F64LE;
}

inline std::vector<hsize_t> to_hsize(const Dims& d) { return {d.begin(), d.end()}; }

// A scratch identifier (dataspace, datatype, property list) closed at scope exit.
inline Handle scratch(const ErrorScope& scope, hid_t id, const char* call) { return Handle(scope.check(id, call), {}); }

inline Handle variable_string_type(const ErrorScope& scope) {
  Handle type = scratch(scope, H5Tcopy(H5T_C_S1), "H5Tcopy");
  scope.check(H5Tset_size(type.id(), H5T_VARIABLE), "H5Tset_size");
  scope.check(H5Tset_cset(type.id(), H5T_CSET_UTF8), "H5Tset_cset");
  return type;
}

// Link creation property list that creates missing intermediate groups ("a/b/c").
inline Handle intermediate_groups(const ErrorScope& scope) {
  Handle lcpl = scratch(scope, H5Pcreate(H5P_LINK_CREATE), "H5Pcreate");
  scope.check(H5Pset_create_intermediate_group(lcpl.id(), 1), "H5Pset_create_intermediate_group");
  return lcpl;
}

}  // namespace polyfloe::io::hdf5::detail
