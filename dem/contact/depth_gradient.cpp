// The gradient force model's depth gradient (contact/narrow_phase_planar.h), from the terms planar_overlap measured.
#include "contact/narrow_phase_planar.h"

namespace polyfloe::contact {

using geometry::cross;

DepthGradient depth_gradient(const PlanarContact& g, const Vec2& x_a, const Vec2& x_b) {
  DepthGradient d;
  const Vec2 da = x_a - g.point, db = x_b - g.point;  // body centres relative to the centroid
  if (g.chord > 0.0) {
    // depth = S/L: d(depth) = dS/L - S/L^2 dL, with dS/dv_b = -N and dS/dw_b = -(M - cross(x_b - c, N)).
    const double inv_l = 1.0 / g.chord, s_l2 = g.area * inv_l * inv_l;
    const Vec2 n_vec = g.chord * g.normal;
    d.grad_b = -g.normal - s_l2 * g.gb;
    d.grad_wb = -(g.moment - cross(db, n_vec)) * inv_l - s_l2 * (g.hb - cross(db, g.gb));
  } else {
    d.grad_b = -g.normal;
    d.grad_wb = cross(db, g.normal);
  }
  d.grad_a = -d.grad_b;
  d.grad_wa = -d.grad_wb + cross(da - db, d.grad_b);
  return d;
}

}  // namespace polyfloe::contact
