// Per-body arrays gathered into a new order of the bodies (a World storing its bodies anew, a state's rows in the
// order of a World's bodies).
#pragma once

#include <algorithm>
#include <cstddef>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

namespace polyfloe::dynamics {

// Row k of `rows` becomes row from[k] of before; `rows` has a row per entry of `from`, or none (left empty).
template <class T>
void gather_rows(std::vector<T>& rows, std::span<const int> from) {
  if (rows.empty()) return;
  std::vector<T> out(from.size());
  for (std::size_t k = 0; k < from.size(); ++k) out[k] = rows[static_cast<std::size_t>(from[k])];
  rows = std::move(out);
}

// The same for rows of varying length: row i of each of `values` is values[off[i] .. off[i+1]-1].
template <class... V>
void gather_ranges(std::vector<int>& off, std::span<const int> from, V&... values) {
  std::vector<int> new_off(from.size() + 1, 0);
  for (std::size_t k = 0; k < from.size(); ++k) {
    const auto i = static_cast<std::size_t>(from[k]);
    new_off[k + 1] = new_off[k] + (off[i + 1] - off[i]);
  }
  auto one = [&](auto& v) {
    std::remove_reference_t<decltype(v)> out(v.size());
    for (std::size_t k = 0; k < from.size(); ++k) {
      const auto i = static_cast<std::size_t>(from[k]);
      std::copy(v.begin() + off[i], v.begin() + off[i + 1], out.begin() + new_off[k]);
    }
    v = std::move(out);
  };
  (one(values), ...);
  off = std::move(new_off);
}

}  // namespace polyfloe::dynamics
