#include "contact/manifold.h"

#include <cmath>

namespace polyfloe::contact {

namespace {

constexpr int kMaxClip = 2 * 64 + 8;  // an incident face of up to 64 vertices grows by one per side plane at most

struct Face {
  int index = -1;
  double alignment = -2.0;
};

Face most_aligned(const geometry::ConvexPolyhedron& s, const Mat3& rot, const Vec3& dir) {
  Face best;
  const auto& faces = s.faces();
  for (int f = 0; f < static_cast<int>(faces.size()); ++f) {
    const double c = (rot * faces[f].normal).dot(dir);
    if (c > best.alignment) best = {f, c};
  }
  return best;
}

}  // namespace

double ContactManifold::max_depth() const {
  double d = 0.0;
  for (int k = 0; k < count; ++k) d = std::max(d, depths[k]);
  return d;
}

Vec3 ContactManifold::centre() const {
  Vec3 c = Vec3::Zero();
  double w = 0.0;
  for (int k = 0; k < count; ++k) {
    c += depths[k] * points[k];
    w += depths[k];
  }
  return w > 0.0 ? Vec3(c / w) : points[0];
}

ContactManifold clip_manifold(const geometry::ConvexPolyhedron& a, const Mat3& rot_a, std::span<const Vec3> world_a,
                              const geometry::ConvexPolyhedron& b, const Mat3& rot_b, std::span<const Vec3> world_b,
                              const Vec3& normal) {
  ContactManifold m;
  const Face fa = most_aligned(a, rot_a, normal);
  const Face fb = most_aligned(b, rot_b, -normal);
  const double cos_max = std::cos(kMaxFaceAngle);
  if (std::max(fa.alignment, fb.alignment) < cos_max) return m;
  // Ties (a face on a face) go to A, so that the choice does not flip from step to step.
  const bool ref_is_a = fa.alignment >= fb.alignment - 1e-12;
  const auto& ref_shape = ref_is_a ? a : b;
  const auto& inc_shape = ref_is_a ? b : a;
  const Mat3& ref_rot = ref_is_a ? rot_a : rot_b;
  const Mat3& inc_rot = ref_is_a ? rot_b : rot_a;
  const auto ref_world = ref_is_a ? world_a : world_b;
  const auto inc_world = ref_is_a ? world_b : world_a;
  const auto& ref_face = ref_shape.faces()[ref_is_a ? fa.index : fb.index];
  const Vec3 nr = ref_rot * ref_face.normal;  // outward from the reference body, towards the other
  const Face fi = most_aligned(inc_shape, inc_rot, -nr);
  const auto& inc_face = inc_shape.faces()[fi.index];

  std::array<Vec3, kMaxClip> buf0{}, buf1{};
  int n = 0;
  for (int v : inc_face.loop) {
    if (n == kMaxClip) return m;
    buf0[n++] = inc_world[v];
  }
  Vec3* in = buf0.data();
  Vec3* out = buf1.data();
  const std::size_t nl = ref_face.loop.size();
  for (std::size_t k = 0; k < nl && n > 0; ++k) {
    const Vec3& p = ref_world[ref_face.loop[k]];
    const Vec3& q = ref_world[ref_face.loop[(k + 1) % nl]];
    const Vec3 side = (q - p).cross(nr);  // outward side-plane normal of a loop counter-clockwise about nr
    int o = 0;
    for (int i = 0; i < n; ++i) {
      const Vec3& x = in[i];
      const Vec3& y = in[(i + 1) % n];
      const double dx = side.dot(x - p), dy = side.dot(y - p);
      if (dx <= 0.0) out[o++] = x;
      if ((dx < 0.0 && dy > 0.0) || (dx > 0.0 && dy < 0.0)) out[o++] = x + (dx / (dx - dy)) * (y - x);
      if (o >= kMaxClip - 1) break;
    }
    std::swap(in, out);
    n = o;
  }
  // Points below the reference plane.
  const Vec3& p0 = ref_world[ref_face.loop[0]];
  std::array<Vec3, kMaxClip> pts{};
  std::array<double, kMaxClip> dep{};
  int np = 0;
  for (int i = 0; i < n; ++i) {
    const double sep = nr.dot(in[i] - p0);
    if (sep < 0.0 && std::isfinite(sep)) {
      dep[np] = -sep;
      pts[np] = in[i] + (0.5 * -sep) * nr;
      ++np;
    }
  }
  if (np == 0) return m;
  m.normal = ref_is_a ? nr : Vec3(-nr);
  if (np <= kMaxManifoldPoints) {
    for (int i = 0; i < np; ++i) {
      m.points[i] = pts[i];
      m.depths[i] = dep[i];
    }
    m.count = np;
    return m;
  }
  // Reduce: deepest, farthest from it, then the two that add the most area on either side of that chord.
  int i0 = 0;
  for (int i = 1; i < np; ++i) {
    if (dep[i] > dep[i0]) i0 = i;
  }
  int i1 = i0 == 0 ? 1 : 0;
  for (int i = 0; i < np; ++i) {
    if (i != i0 && (pts[i] - pts[i0]).squaredNorm() > (pts[i1] - pts[i0]).squaredNorm()) i1 = i;
  }
  int i2 = -1, i3 = -1;
  double best_pos = 0.0, best_neg = 0.0;
  for (int i = 0; i < np; ++i) {
    if (i == i0 || i == i1) continue;
    const double s = nr.dot((pts[i1] - pts[i0]).cross(pts[i] - pts[i0]));
    if (s > best_pos) best_pos = s, i2 = i;
    if (s < best_neg) best_neg = s, i3 = i;
  }
  for (int i : {i0, i1, i2, i3}) {
    if (i < 0) continue;
    m.points[m.count] = pts[i];
    m.depths[m.count] = dep[i];
    ++m.count;
  }
  return m;
}

}  // namespace polyfloe::contact
