// Placing floes without overlap (scene/floe_placement.h).
#include "scene/floe_placement.h"

namespace polyfloe::scene::detail {

namespace {

// True when some edge normal of `a` has all of `b` at least `gap` beyond the edge line.
bool separated_along_normals_of(const std::vector<Vec2>& an, const std::vector<double>& ad, const Vec2& a_shift,
                                const std::vector<Vec2>& bv, const Vec2& b_shift, double gap) {
  for (std::size_t i = 0; i < an.size(); ++i) {
    const double d = ad[i] + an[i].dot(a_shift) - an[i].dot(b_shift) + gap;
    bool all_beyond = true;
    for (const Vec2& x : bv) {
      if (an[i].dot(x) < d) {
        all_beyond = false;
        break;
      }
    }
    if (all_beyond) return true;
  }
  return false;
}

}  // namespace

PreparedPolygon prepare(std::span<const Vec2> v) {
  PreparedPolygon p;
  p.v.assign(v.begin(), v.end());
  const std::size_t k = v.size();
  p.n.resize(k);
  p.d.resize(k);
  p.box.lo = p.box.hi = v[0];
  for (std::size_t i = 0; i < k; ++i) {
    const Vec2 e = v[(i + 1) % k] - v[i];
    const double len = e.norm();
    p.n[i] = len > 0.0 ? Vec2(geometry::perp_right(e) / len) : Vec2(0.0, 0.0);
    p.d[i] = p.n[i].dot(v[i]);
    p.box.lo = p.box.lo.cwiseMin(v[i]);
    p.box.hi = p.box.hi.cwiseMax(v[i]);
  }
  return p;
}

// `a` (translated by a_shift) and `b` (translated by b_shift) are at least `gap` apart along some edge normal.
bool separated(const PreparedPolygon& a, const Vec2& a_shift, const PreparedPolygon& b, const Vec2& b_shift,
               double gap) {
  return separated_along_normals_of(a.n, a.d, a_shift, b.v, b_shift, gap) ||
         separated_along_normals_of(b.n, b.d, b_shift, a.v, a_shift, gap);
}

}  // namespace polyfloe::scene::detail
