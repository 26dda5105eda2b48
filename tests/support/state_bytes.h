// Every field of a world state as its name and the bytes of its values: states compared bit for bit, field by field
// (restart, threads and the domain decomposition's tests).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "dynamics/state_fields.h"

namespace polyfloe::tsupport {

// Every field of a world state (its visit_fields) as its name and the bytes of its values.
class StateBytes {
 public:
  std::vector<std::pair<std::string, std::string>> fields;
  template <class T>
  void attribute(const char* name, const T& x) {
    add(name, &x, sizeof x);
  }
  void count(const char* name, const char*, const std::uint64_t& x, double) { add(name, &x, sizeof x); }
  template <class T>
  void bodies(const char* name, const std::vector<T>& rows) {
    add_rows(name, rows);
  }
  template <class T>
  void bodies_or_none(const char* name, const std::vector<T>& rows) {
    add_rows(name, rows);
  }
  template <class T>
  void rows(const char* name, const std::vector<T>& rows) {
    add_rows(name, rows);
  }
  template <class E>
  void history(const std::vector<E>& entries) {
    std::string bytes;
    for (const E& e : entries) {
      bytes.append(reinterpret_cast<const char*>(&e.first), sizeof e.first);
      bytes.append(reinterpret_cast<const char*>(&e.second), sizeof e.second);
    }
    fields.emplace_back("contact_history", std::move(bytes));
  }
  template <class F>
  void group(const char*, F&& f) {
    f();
  }
  template <class T, class F>
  void optional_group(const char* name, const std::optional<T>& value, F&& f) {
    add(name, "", value ? 1 : 0);
    if (value) f(*value);
  }

 private:
  void add(const char* name, const void* p, std::size_t n) {
    fields.emplace_back(name, std::string(static_cast<const char*>(p), n));
  }
  template <class T>
  void add_rows(const char* name, const std::vector<T>& rows) {
    const auto flat = dynamics::pack_rows(rows);
    add(name, flat.data(), flat.size() * sizeof(flat[0]));
  }
};

template <class State>
std::vector<std::pair<std::string, std::string>> state_bytes(const State& s) {
  StateBytes v;
  visit_fields(v, s);
  return v.fields;
}

}  // namespace polyfloe::tsupport
