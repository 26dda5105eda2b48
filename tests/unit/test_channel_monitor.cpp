// Channel diagnostics (run/channel_monitor.h) on floes moved by hand: the net area through the strait entrance and
// its rate, the floes in the strait and their mean speed, the ice upstream and in the funnel, and jam detection
// (no net flow for channel.jam_window with the funnel's ice slower than channel.jam_speed), each against the values
// worked out below.
#include <gtest/gtest.h>

#include "dynamics/world.h"
#include "run/channel_monitor.h"
#include "test_support.h"

using namespace polyfloe;
using geometry::Vec2;

namespace {

std::shared_ptr<const geometry::ConvexPolygon> square(double side) {
  const double h = side / 2;
  return tsupport::shape_of({{-h, -h}, {h, -h}, {h, h}, {-h, h}});
}

TEST(ChannelMonitor, SamplesMatchHandValuesAndAJamIsFlaggedOnlyAJamWindowAfterTheLastNetFlow) {
  scene::ChannelSpec spec;  // defaults: gate at x = 1100 + 300 = 1400, strait to 2000, opening y in [375, 625]
  dynamics::WorldSettings ws;
  ws.drift = forcing::DriftSettings::none();
  dynamics::World w(ws);
  w.add_body({.id = 1, .shape = square(10), .position = {1395.0, 500.0}, .velocity = {1.0, 0.0}});  // A, 100 m^2
  w.add_body({.id = 2, .shape = square(20), .position = {1390.0, 560.0}, .velocity = {2.0, 0.0}});  // B, 400 m^2
  w.add_body({.id = 3, .shape = square(10), .position = {500.0, 500.0}});                           // C, basin
  w.add_body({.id = 4, .shape = square(10), .position = {1200.0, 300.0}});                          // D, funnel
  w.add_body({.id = 5, .shape = square(50), .position = {1300.0, 900.0}, .motion = dynamics::Motion::fixed});
  run::ChannelMonitor m(spec, w);
  EXPECT_EQ(m.gate_x(), 1400.0);
  w.compute_forces(0.0);
  auto advance_to = [&](double t) {
    while (w.time() < t - 1e-9) w.step(0.25);
  };
  advance_to(5.0);  // A at 1400 (on the gate: through), B at 1400: both through
  run::ChannelSample s = m.sample(w);
  EXPECT_NEAR(s.area_passed, 500.0, 1e-9);
  EXPECT_NEAR(s.area_flux, 100.0, 1e-9);
  EXPECT_EQ(s.strait_floes, 2);
  EXPECT_NEAR(s.strait_mean_speed, 1.5, 1e-12);
  EXPECT_NEAR(s.upstream_area, 200.0, 1e-9);  // C and D; the fixed wall does not count
  EXPECT_NEAR(s.funnel_area, 100.0, 1e-9);    // D
  EXPECT_EQ(s.funnel_mean_speed, 0.0);
  EXPECT_FALSE(s.jammed);
  advance_to(20.0);
  s = m.sample(w);
  EXPECT_EQ(s.area_flux, 0.0);
  EXPECT_FALSE(s.jammed) << "15 s without flow < jam_window = 20 s";
  advance_to(25.0);
  s = m.sample(w);
  EXPECT_TRUE(s.jammed);
  ASSERT_TRUE(m.jam_time().has_value());
  EXPECT_NEAR(*m.jam_time(), 5.0, 1e-9);  // the last net flow
  EXPECT_NEAR(m.area_passed(), 500.0, 1e-9);
}

TEST(ChannelMonitor, NoJamBeforeIceReachesTheFunnel) {
  scene::ChannelSpec spec;
  dynamics::WorldSettings ws;
  ws.drift = forcing::DriftSettings::none();
  dynamics::World w(ws);
  w.add_body({.id = 1, .shape = square(10), .position = {500.0, 500.0}, .velocity = {10.0, 0.0}});
  run::ChannelMonitor m(spec, w);
  w.compute_forces(0.0);
  bool jammed = false;
  for (int k = 1; k <= 180; ++k) {
    w.step(0.5);
    if (k % 10 == 0) jammed = jammed || m.sample(w).jammed;
  }
  // At 10 m/s it is in the funnel from t = 60 s to 90 s without any net flow, but moving: not a jam.
  EXPECT_FALSE(jammed);
  EXPECT_FALSE(m.jam_time().has_value());
  EXPECT_NEAR(m.area_passed(), 100.0, 1e-9);
}

}  // namespace
