#include "geometry/polyhedron.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

namespace polyfloe::geometry {

namespace {

// Second moment of the tetrahedron (r, a, b, c) about the origin, times 6 (to keep the determinant whole):
// integral of x x^T dV = V / 20 (sum v v^T + s s^T), s the vertex sum.
void add_tetrahedron(const Vec3& r, const Vec3& a, const Vec3& b, const Vec3& c, double& six_volume, Vec3& moment,
                     Mat3& second) {
  const double d = (a - r).dot((b - r).cross(c - r));  // 6 V (signed)
  const Vec3 s = r + a + b + c;
  six_volume += d;
  moment += d * s / 24.0;  // V s / 4
  second +=
      d / 120.0 * (r * r.transpose() + a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
}

}  // namespace

ConvexPolyhedron ConvexPolyhedron::prism(const ConvexPolygon& base, double thickness) {
  if (!(thickness > 0.0) || !std::isfinite(thickness)) {
    throw GeometryError("prism thickness must be finite and > 0 m, got " + std::to_string(thickness));
  }
  const auto& p = base.vertices();
  const int n = static_cast<int>(p.size());
  ConvexPolyhedron s;
  s.vertices_.reserve(2 * n);
  for (const auto& v : p) s.vertices_.emplace_back(v.x(), v.y(), -0.5 * thickness);
  for (const auto& v : p) s.vertices_.emplace_back(v.x(), v.y(), 0.5 * thickness);
  PolyhedronFace bottom, top;
  for (int i = n - 1; i >= 0; --i) bottom.loop.push_back(i);  // clockwise from above = counter-clockwise from below
  for (int i = 0; i < n; ++i) top.loop.push_back(n + i);
  s.faces_.push_back(bottom);
  s.faces_.push_back(top);
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    s.faces_.push_back(PolyhedronFace{{i, j, n + j, n + i}});
  }
  s.finish();
  return s;
}

ConvexPolyhedron ConvexPolyhedron::box(const Vec3& size) {
  if (!size.allFinite() || !(size.minCoeff() > 0.0)) {
    throw GeometryError("box edge lengths must be finite and > 0 m");
  }
  return prism(ConvexPolygon::rectangle(size.x(), size.y()), size.z());
}

double ConvexPolyhedron::equivalent_radius() const { return std::cbrt(3.0 * volume_ / (4.0 * std::numbers::pi)); }

void ConvexPolyhedron::finish() {
  if (vertices_.size() < 4 || faces_.size() < 4) throw GeometryError("a polyhedron needs >= 4 vertices and faces");
  double size = 0.0;
  for (const auto& v : vertices_) size = std::max(size, (v - vertices_[0]).lpNorm<Eigen::Infinity>());
  // Newell normals (robust for slightly non-planar loops), then volume and moments by tetrahedra from vertex 0.
  double six_volume = 0.0;
  Vec3 moment = Vec3::Zero();
  Mat3 second = Mat3::Zero();
  const Vec3& r = vertices_[0];
  for (auto& f : faces_) {
    if (f.loop.size() < 3) throw GeometryError("a polyhedron face needs >= 3 vertices");
    Vec3 n = Vec3::Zero();
    for (std::size_t k = 0; k < f.loop.size(); ++k) {
      const Vec3& a = vertices_[f.loop[k]];
      const Vec3& b = vertices_[f.loop[(k + 1) % f.loop.size()]];
      n += (a - b).cross(a + b) * 0.5;  // = a x b
    }
    const double len = n.norm();
    if (!(len > 1e-24 * size * size)) throw GeometryError("a polyhedron face has zero area");
    f.normal = n / len;
    for (std::size_t k = 1; k + 1 < f.loop.size(); ++k) {
      add_tetrahedron(r, vertices_[f.loop[0]], vertices_[f.loop[k]], vertices_[f.loop[k + 1]], six_volume, moment,
                      second);
    }
  }
  volume_ = six_volume / 6.0;
  if (!(volume_ > 0.0) || !std::isfinite(volume_)) throw GeometryError("a polyhedron must enclose a positive volume");
  const Vec3 c = moment / volume_;
  for (auto& v : vertices_) v -= c;
  const Mat3 central = second - volume_ * c * c.transpose();  // integral of x x^T about the centroid
  unit_inertia_ = central.trace() * Mat3::Identity() - central;
  circumradius_ = 0.0;
  for (const auto& v : vertices_) circumradius_ = std::max(circumradius_, v.norm());
  edges_.clear();
  edge_directions_.clear();
  for (const auto& f : faces_) {
    for (std::size_t k = 0; k < f.loop.size(); ++k) {
      const int i = f.loop[k], j = f.loop[(k + 1) % f.loop.size()];
      const std::pair<int, int> e{std::min(i, j), std::max(i, j)};
      if (std::find(edges_.begin(), edges_.end(), e) != edges_.end()) continue;
      edges_.push_back(e);
      const Vec3 d = (vertices_[e.second] - vertices_[e.first]).normalized();
      const bool parallel = std::any_of(edge_directions_.begin(), edge_directions_.end(),
                                        [&](const Vec3& u) { return u.cross(d).norm() < 1e-9; });
      if (!parallel) edge_directions_.push_back(d);
    }
  }
  for (auto& f : faces_) {
    f.offset = f.normal.dot(vertices_[f.loop[0]]);
    for (const auto& v : vertices_) {
      if (f.normal.dot(v) - f.offset > 1e-9 * size) throw GeometryError("the polyhedron is not convex");
    }
  }
}

SubmergedPart submerged_part(const ConvexPolyhedron& shape, std::span<const Vec3> world_vertices, double level) {
  // With coordinates y = x - (0, 0, level): V = 1/3 sum_f (y_f . n_f) A_f and integral of y_k dV =
  // 1/2 sum_f n_fk integral over f of y_k^2 dS. On the cap (the waterplane) y_z = 0 and n = +z, so the cap adds
  // nothing to either: only the submerged parts of the faces are needed.
  // y is also measured from a vertex horizontally (any horizontal origin will do: n_x = n_y = 0 on the cap), so that
  // the quadratic integrals do not lose digits to the body's distance from the world origin.
  SubmergedPart out;
  if (world_vertices.empty()) return out;
  const Vec3 origin{world_vertices[0].x(), world_vertices[0].y(), level};
  double volume = 0.0;
  Vec3 first = Vec3::Zero();
  // A convex face cut by a plane keeps at most its vertex count + 1 points (the buffer is kept: no allocation once
  // warm).
  thread_local std::vector<Vec3> poly;
  for (const auto& f : shape.faces()) {
    poly.clear();
    const std::size_t n = f.loop.size();
    for (std::size_t k = 0; k < n; ++k) {
      const Vec3 a = world_vertices[f.loop[k]] - origin;
      const Vec3 b = world_vertices[f.loop[(k + 1) % n]] - origin;
      const bool ina = a.z() <= 0.0, inb = b.z() <= 0.0;
      if (ina) poly.push_back(a);
      if (ina != inb) {
        const double t = a.z() / (a.z() - b.z());
        Vec3 x = a + t * (b - a);
        x.z() = 0.0;
        poly.push_back(x);
      }
    }
    const int m = static_cast<int>(poly.size());
    if (m < 3) continue;
    // normal from the rotated shape (world_vertices are a rigid motion of the body frame)
    Vec3 nw = (poly[1] - poly[0]).cross(poly[2] - poly[0]);
    for (int k = 2; k + 1 < m; ++k) nw += (poly[k] - poly[0]).cross(poly[k + 1] - poly[0]);
    const double twice_area = nw.norm();
    if (!(twice_area > 0.0)) continue;
    const Vec3 nrm = nw / twice_area;
    volume += poly[0].dot(nrm) * 0.5 * twice_area / 3.0;
    for (int k = 1; k + 1 < m; ++k) {
      const Vec3 &p0 = poly[0], &p1 = poly[k], &p2 = poly[k + 1];
      const double area = 0.5 * (p1 - p0).cross(p2 - p0).norm();
      // exact for quadratics: the mean over the edge midpoints
      const Vec3 m01 = 0.5 * (p0 + p1), m12 = 0.5 * (p1 + p2), m20 = 0.5 * (p2 + p0);
      const Vec3 sq = (m01.cwiseProduct(m01) + m12.cwiseProduct(m12) + m20.cwiseProduct(m20)) * (area / 3.0);
      first += 0.5 * nrm.cwiseProduct(sq);
    }
  }
  if (volume > 0.0) {
    out.volume = volume;
    out.centroid = first / volume + origin;
  }
  return out;
}

}  // namespace polyfloe::geometry
