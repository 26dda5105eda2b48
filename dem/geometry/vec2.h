// 2-D vector helpers on top of Eigen. All lengths in metres unless stated.
#pragma once

#include <Eigen/Core>

namespace polyfloe::geometry {

using Vec2 = Eigen::Vector2d;

// z-component of the 3-D cross product of (a, 0) and (b, 0).
inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// k x v: v rotated +90 degrees (velocity of a point at v from the centre of a body spinning at 1 rad/s).
inline Vec2 perp_left(const Vec2& v) { return {-v.y(), v.x()}; }

// v rotated -90 degrees: the outward normal direction of an edge vector of a counter-clockwise polygon.
inline Vec2 perp_right(const Vec2& v) { return {v.y(), -v.x()}; }

// Rotation of v by angle (c = cos, s = sin).
inline Vec2 rotate(const Vec2& v, double c, double s) { return {c * v.x() - s * v.y(), s * v.x() + c * v.y()}; }

struct Aabb {
  Vec2 lo{0.0, 0.0};  // [m]
  Vec2 hi{0.0, 0.0};  // [m]
  bool overlaps(const Aabb& o) const {
    return lo.x() <= o.hi.x() && o.lo.x() <= hi.x() && lo.y() <= o.hi.y() && o.lo.y() <= hi.y();
  }
};

}  // namespace polyfloe::geometry
