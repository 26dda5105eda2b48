// The drift forcing stage (dynamics/forcing_stage.h) on its own, over a hand-made view of the bodies, no World:
// skin drag on a floe at rest in a uniform current against its closed form 1/2 rho_w c_w A |u| u (force and
// damping matrix), nothing on a fixed body, no kept load under the explicit treatment, the lowest failing body
// named when a field has no water, and the same bits on 2 threads as on 1 in a sheared current.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include "dynamics/forcing_stage.h"
#include "forcing/analytic_fields.h"
#include "forcing/field.h"
#include "forcing/quadrature.h"
#include "geometry/polygon.h"

using namespace polyfloe;
using dynamics::DriftBodies;
using dynamics::DriftForcing;
using dynamics::DriftModel;
using geometry::Vec2;

namespace {

constexpr double kSide = 10.0, kThickness = 1.0, kDensity = 900.0, kWater = 1025.0;  // [m], [m], [kg/m^3]

// n squares of kSide in a row along x (40 m apart) at yaw 0, at rest; body 0 fixed when `wall`. The view's arrays
// live here.
struct Floes {
  std::vector<dynamics::BodyId> id;
  std::vector<std::uint8_t> dynamic;
  std::vector<Vec2> position, velocity, rotation, world_xy;
  std::vector<double> omega, mass, thickness, draft, side_area, equivalent_radius, plan_area;
  std::vector<int> vert_begin, vert_off{0}, quad_off{0};
  std::vector<double> quad_lx, quad_ly, quad_weight;
  std::size_t max_quad = 0;

  Floes(int n, bool wall, forcing::Quadrature q = forcing::Quadrature::degree2) {
    const geometry::ConvexPolygon sq = geometry::ConvexPolygon::rectangle(kSide, kSide);
    for (int i = 0; i < n; ++i) {
      id.push_back(static_cast<dynamics::BodyId>(10 + i));
      dynamic.push_back(wall && i == 0 ? 0 : 1);
      position.emplace_back(40.0 * i, 3.0 * i);
      velocity.emplace_back(0.0, 0.0);
      rotation.emplace_back(1.0, 0.0);
      omega.push_back(0.0);
      mass.push_back(kDensity * sq.area() * kThickness);
      thickness.push_back(kThickness);
      draft.push_back(kThickness * kDensity / kWater);
      side_area.push_back(sq.perimeter() * draft.back());
      equivalent_radius.push_back(sq.equivalent_radius());
      plan_area.push_back(sq.area());
      vert_begin.push_back(vert_off.back());
      for (const Vec2& v : sq.vertices()) world_xy.push_back(position.back() + v);
      vert_off.push_back(vert_off.back() + static_cast<int>(sq.size()));
      std::vector<forcing::QuadraturePoint> pts;
      forcing::polygon_quadrature(sq.vertices(), q, pts);
      for (const forcing::QuadraturePoint& p : pts) {
        quad_lx.push_back(p.point.x());
        quad_ly.push_back(p.point.y());
        quad_weight.push_back(p.weight);
      }
      quad_off.push_back(quad_off.back() + static_cast<int>(pts.size()));
      max_quad = std::max(max_quad, pts.size());
    }
  }
  DriftBodies view() const {
    return {.id = id,
            .dynamic = dynamic,
            .position = position,
            .velocity = velocity,
            .omega = omega,
            .rotation = rotation,
            .mass = mass,
            .thickness = thickness,
            .draft = draft,
            .side_area = side_area,
            .equivalent_radius = equivalent_radius,
            .plan_area = plan_area,
            .world_xy = world_xy,
            .vert_begin = vert_begin,
            .vert_off = vert_off,
            .quad_off = quad_off,
            .quad_lx = quad_lx,
            .quad_ly = quad_ly,
            .quad_weight = quad_weight,
            .max_vertices = 4,
            .max_quad_points = max_quad};
  }
};

forcing::DriftSettings skin_only(const Vec2& current) {
  forcing::DriftSettings s = forcing::DriftSettings::none();
  s.skin_drag = true;
  s.ocean = forcing::make_field(forcing::FieldSpec::uniform(current));
  return s;
}

// Water only left of x = `edge`: the field throws for any sample beyond it.
class HalfOcean : public forcing::VelocityField {
 public:
  explicit HalfOcean(double edge) : edge_(edge) {}
  void sample(double, std::span<const forcing::Vec3> points, std::span<Vec2> out) const override {
    for (std::size_t k = 0; k < points.size(); ++k) {
      if (points[k].x() > edge_) throw forcing::FieldError("no water at x = " + std::to_string(points[k].x()));
      out[k] = {0.3, 0.0};
    }
  }

 private:
  double edge_;
};

}  // namespace

TEST(ForcingStage, SkinDragOnAFloeAtRestIsHalfRhoCAUAbsUWithItsDampingMatrix) {
  // A floe at rest in a current u: F = 1/2 rho_w c_w A |u| u, no torque (symmetric); the drag's derivative
  // D = 1/2 rho_w c_w A |u| (I + u^ u^T): twice as much along u as across. A fixed body feels nothing.
  const Floes f(2, true);
  const Vec2 u{0.5, 0.0};
  const forcing::DriftSettings s = skin_only(u);
  DriftForcing stage;
  DriftModel model;
  std::vector<Vec2> force(2, Vec2{1.0, 2.0});
  std::vector<double> torque(2, 3.0);
  stage.apply(s, f.view(), 0.0, 1, model, force, torque);
  const double c = 0.5 * kWater * s.skin_drag_coefficient * kSide * kSide * u.norm();
  EXPECT_NEAR(force[1].x() - 1.0, c * u.x(), 1e-12 * c);
  EXPECT_NEAR(force[1].y() - 2.0, 0.0, 1e-12 * c);
  EXPECT_NEAR(torque[1] - 3.0, 0.0, 1e-9 * c);
  EXPECT_NEAR(model.load(1).dxx, 2.0 * c, 1e-12 * c);
  EXPECT_NEAR(model.load(1).dyy, c, 1e-12 * c);
  EXPECT_NEAR(model.load(1).force.x(), c * u.x(), 1e-12 * c);
  EXPECT_EQ(force[0], (Vec2{1.0, 2.0}));  // the fixed body: untouched, no load
  EXPECT_EQ(torque[0], 3.0);
  EXPECT_FALSE(model.load(0).has_damping());
  // Explicit treatment: the same force, no load kept for the final kick.
  const Vec2 semi_implicit_load = model.load(1).force;
  forcing::DriftSettings e = s;
  e.treatment = forcing::DriftTreatment::explicit_step;
  std::vector<Vec2> force_e(2, Vec2{0.0, 0.0});
  std::vector<double> torque_e(2, 0.0);
  stage.apply(e, f.view(), 0.0, 1, model, force_e, torque_e);
  EXPECT_EQ(force_e[1], semi_implicit_load);
  EXPECT_FALSE(model.load(1).has_damping());
}

TEST(ForcingStage, AFieldWithoutWaterNamesTheLowestFailingBody) {
  // Floes at x = 0, 40, 80, 120: water ends at x = 50, so bodies 12 and 13 fail; 12 is named, on any thread count.
  const Floes f(4, false);
  forcing::DriftSettings s = forcing::DriftSettings::none();
  s.form_drag = true;
  s.ocean = std::make_shared<HalfOcean>(50.0);
  for (int threads : {1, 2}) {
    DriftForcing stage;
    DriftModel model;
    std::vector<Vec2> force(4, Vec2{0.0, 0.0});
    std::vector<double> torque(4, 0.0);
    try {
      stage.apply(s, f.view(), 7.0, threads, model, force, torque);
      FAIL() << "a sample without water must throw";
    } catch (const forcing::FieldError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("body 12 at (80, 6) m, t = 7 s: no water at x = "), std::string::npos) << m;
    }
  }
}

TEST(ForcingStage, TwoThreadsGiveTheOneThreadLoadsBitwise) {
  // 200 moving, turning floes in a sheared current with wind and Coriolis: every term, sampled per point.
  Floes f(200, false);
  for (std::size_t i = 0; i < f.id.size(); ++i) {
    f.velocity[i] = {0.1 * std::sin(0.3 * static_cast<double>(i)), 0.05};
    f.omega[i] = 0.01 * std::cos(0.7 * static_cast<double>(i));
  }
  forcing::DriftSettings s;
  s.coriolis = true;
  forcing::FieldSpec shear;
  shear.kind = forcing::FieldKind::linear;
  shear.velocity = {0.2, 0.0};
  shear.gradient << 0.0, 1e-3, -2e-4, 0.0;
  s.ocean = forcing::make_field(shear);
  s.wind = forcing::make_field(forcing::FieldSpec::uniform({5.0, -3.0}));
  std::vector<Vec2> f1(200, Vec2{0.0, 0.0}), f2 = f1;
  std::vector<double> t1(200, 0.0), t2 = t1;
  DriftForcing a, b;
  DriftModel m1, m2;
  a.apply(s, f.view(), 0.0, 1, m1, f1, t1);
  b.apply(s, f.view(), 0.0, 2, m2, f2, t2);
  EXPECT_EQ(std::memcmp(f1.data(), f2.data(), f1.size() * sizeof(Vec2)), 0);
  EXPECT_EQ(std::memcmp(t1.data(), t2.data(), t1.size() * sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(m1.loads().data(), m2.loads().data(), m1.size() * sizeof(forcing::DriftLoad)), 0);
  EXPECT_GT(m1.load(7).mf, 0.0);
}
