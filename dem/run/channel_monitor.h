// Channel diagnostics, sampled at every output frame: the ice area that has passed the strait's entrance (the gate
// x = basin_x_max + funnel_length) and its rate, the floes in the strait and their mean speed, and jam detection.
//
// Crossings are counted from each floe's side of the gate at consecutive samples (centroid x >= gate: through), so
// the area passed is the net area through the gate between samples (a floe that crosses and comes back within one
// output interval is not counted). The channel is jammed once no net ice area has passed for `jam_window` seconds
// while the ice in the funnel (centroids between basin_x_max and the gate) has stalled: its mean speed below
// `jam_speed`. The jam time is when that spell began (the later of the last net flow and the stall).
#pragma once

#include <optional>
#include <vector>

#include "dynamics/world.h"
#include "scene/scene.h"

namespace polyfloe::run {

struct ChannelSample {
  double time = 0.0;               // [s]
  double area_flux = 0.0;          // net ice area through the gate since the last sample / elapsed time [m^2/s]
  double area_passed = 0.0;        // net ice area through the gate since the start [m^2]
  double upstream_area = 0.0;      // ice area with centroids before the gate [m^2]
  double funnel_area = 0.0;        // of which in the funnel (x >= basin_x_max) [m^2]
  double funnel_mean_speed = 0.0;  // mean speed of the floes in the funnel [m/s] (0 when none)
  int strait_floes = 0;            // floes with centroids in the strait
  double strait_mean_speed = 0.0;  // their mean speed [m/s] (0 when none)
  bool jammed = false;
};

class ChannelMonitor {
 public:
  // `world` at the start of the run: the state every later sample is compared with.
  ChannelMonitor(const scene::ChannelSpec& spec, const dynamics::World& world);
  ChannelSample sample(const dynamics::World& world);
  double gate_x() const { return gate_; }                       // [m]
  std::optional<double> jam_time() const { return jam_time_; }  // [s]
  double area_passed() const { return passed_; }                // [m^2]

  // What carries from one sample to the next (checkpoints).
  struct State {
    std::vector<std::uint8_t> through;                           // per body in id order
    double last_time = 0.0, last_flow_time = 0.0, passed = 0.0;  // [s], [s], [m^2]
    std::optional<double> stalled_since, jam_time;               // [s]
  };
  State state() const { return {through_, last_time_, last_flow_time_, passed_, stalled_since_, jam_time_}; }
  // Throws std::invalid_argument if the body count differs.
  void restore(const State& s);

 private:
  double funnel_start_, gate_, strait_end_, y_lo_, y_hi_, jam_window_, jam_speed_;
  std::vector<std::uint8_t> through_;  // per body in id order: centroid at or past the gate at the last sample
  double last_time_, last_flow_time_, passed_ = 0.0;
  std::optional<double> stalled_since_;  // first sample of the current stall of the funnel's ice [s]
  std::optional<double> jam_time_;
};

}  // namespace polyfloe::run
