#include "run/channel_monitor.h"

#include <algorithm>
#include <span>
#include <stdexcept>
#include <string>

namespace polyfloe::run {

ChannelMonitor::ChannelMonitor(const scene::ChannelSpec& spec, const dynamics::World& world)
    : funnel_start_(spec.basin_x_max),
      gate_(spec.basin_x_max + spec.funnel_length),
      strait_end_(spec.basin_x_max + spec.funnel_length + spec.strait_length),
      y_lo_(0.5 * (spec.basin_y_min + spec.basin_y_max) - 0.5 * spec.opening),
      y_hi_(0.5 * (spec.basin_y_min + spec.basin_y_max) + 0.5 * spec.opening),
      jam_window_(spec.jam_window),
      jam_speed_(spec.jam_speed),
      last_time_(world.time()),
      last_flow_time_(world.time()) {
  // (by body in id order, as the checkpoint keeps it)
  const std::span<const int> order = world.id_order();
  through_.resize(order.size());
  for (std::size_t k = 0; k < order.size(); ++k)
    through_[k] = world.positions()[static_cast<std::size_t>(order[k])].x() >= gate_ ? 1 : 0;
}

void ChannelMonitor::restore(const State& s) {
  if (s.through.size() != through_.size())
    throw std::invalid_argument("channel monitor state for " + std::to_string(s.through.size()) +
                                " bodies, the run has " + std::to_string(through_.size()));
  through_ = s.through;
  last_time_ = s.last_time;
  last_flow_time_ = s.last_flow_time;
  passed_ = s.passed;
  stalled_since_ = s.stalled_since;
  jam_time_ = s.jam_time;
}

ChannelSample ChannelMonitor::sample(const dynamics::World& world) {
  ChannelSample s;
  s.time = world.time();
  double crossed = 0.0, speed = 0.0, funnel_speed = 0.0;  // [m^2], [m/s], [m/s]
  int funnel_floes = 0;
  const auto pos = world.positions();
  const auto vel = world.velocities();
  const std::span<const int> order = world.id_order();
  for (std::size_t k = 0; k < order.size(); ++k) {
    const int b = order[k];
    const auto i = static_cast<std::size_t>(b);
    if (world.motion(b) != dynamics::Motion::dynamic) continue;
    const double area = world.shape(b).area();
    const std::uint8_t now = pos[i].x() >= gate_ ? 1 : 0;
    crossed += (static_cast<int>(now) - static_cast<int>(through_[k])) * area;
    through_[k] = now;
    if (!now) s.upstream_area += area;
    if (!now && pos[i].x() >= funnel_start_) {
      s.funnel_area += area;
      funnel_speed += vel[i].norm();
      ++funnel_floes;
    }
    if (pos[i].x() >= gate_ && pos[i].x() <= strait_end_ && pos[i].y() >= y_lo_ && pos[i].y() <= y_hi_) {
      ++s.strait_floes;
      speed += vel[i].norm();
    }
  }
  passed_ += crossed;
  s.area_passed = passed_;
  const double elapsed = s.time - last_time_;
  s.area_flux = elapsed > 0.0 ? crossed / elapsed : 0.0;
  s.strait_mean_speed = s.strait_floes > 0 ? speed / s.strait_floes : 0.0;
  if (crossed > 0.0) last_flow_time_ = s.time;
  s.funnel_mean_speed = funnel_floes > 0 ? funnel_speed / funnel_floes : 0.0;
  const bool stalled = funnel_floes > 0 && s.funnel_mean_speed < jam_speed_;
  if (!stalled)
    stalled_since_.reset();
  else if (!stalled_since_)
    stalled_since_ = s.time;
  if (stalled) {
    const double spell_start = std::max(last_flow_time_, *stalled_since_);  // no flow since, ice stalled [s]
    s.jammed = s.time - spell_start >= jam_window_;
    if (s.jammed && !jam_time_) jam_time_ = spell_start;
  }
  last_time_ = s.time;
  return s;
}

}  // namespace polyfloe::run
