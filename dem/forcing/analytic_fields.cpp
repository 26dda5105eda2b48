#include "forcing/analytic_fields.h"

#include "forcing/gridded_field.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace polyfloe::forcing {

std::string_view to_string(FieldKind k) {
  switch (k) {
    case FieldKind::uniform: return "uniform";
    case FieldKind::linear: return "linear";
    case FieldKind::solid_body: return "solid_body";
    case FieldKind::rankine: return "rankine";
    case FieldKind::tidal: return "tidal";
    case FieldKind::time_series: return "time_series";
    case FieldKind::file: return "file";
  }
  return "?";
}

std::string_view to_string(TimeBoundary b) {
  switch (b) {
    case TimeBoundary::clamp: return "clamp";
    case TimeBoundary::cyclic: return "cyclic";
    case TimeBoundary::error: return "error";
  }
  return "?";
}

std::string_view to_string(OutsideWater o) {
  switch (o) {
    case OutsideWater::error: return "error";
    case OutsideWater::velocity: return "velocity";
  }
  return "?";
}

namespace {

bool finite(const Vec2& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }

class UniformField final : public VelocityField {
 public:
  explicit UniformField(const Vec2& v) : v_(v) {}
  void sample(double, std::span<const Vec3>, std::span<Vec2> out) const override {
    std::fill(out.begin(), out.end(), v_);
  }
  bool uniform_in_space() const override { return true; }

 private:
  Vec2 v_;
};

// u = u0 + G (p - origin) + (du/dz) z
class LinearField final : public VelocityField {
 public:
  explicit LinearField(const FieldSpec& s) : u0_(s.velocity), o_(s.origin), g_(s.gradient), dz_(s.depth_gradient) {}
  void sample(double, std::span<const Vec3> p, std::span<Vec2> out) const override {
    for (std::size_t i = 0; i < p.size(); ++i) out[i] = u0_ + g_ * (p[i].head<2>() - o_) + p[i].z() * dz_;
  }

 private:
  Vec2 u0_, o_;
  Eigen::Matrix2d g_;
  Vec2 dz_;
};

// Swirl about a centre plus a uniform background: solid body (speed Omega r everywhere) or Rankine (solid body
// inside the core radius R, irrotational V R / r outside, V at r = R).
class VortexField final : public VelocityField {
 public:
  explicit VortexField(const FieldSpec& s)
      : rankine_(s.kind == FieldKind::rankine),
        c_(s.origin),
        u0_(s.velocity),
        omega_(rankine_ ? s.max_speed / s.core_radius : s.angular_velocity),
        r_core_(s.core_radius),
        v_max_(s.max_speed) {}
  void sample(double, std::span<const Vec3> p, std::span<Vec2> out) const override {
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Vec2 r = p[i].head<2>() - c_;
      const double r2 = r.squaredNorm();
      // Inside the core (or everywhere for solid body): Omega k x r. Outside: (V R / |r|) e_theta = V R k x r / r^2.
      const double rate = (!rankine_ || r2 <= r_core_ * r_core_) ? omega_ : v_max_ * r_core_ / r2;
      out[i] = u0_ + rate * geometry::perp_left(r);
    }
  }

 private:
  bool rankine_;
  Vec2 c_, u0_;
  double omega_, r_core_, v_max_;
};

class TidalField final : public VelocityField {
 public:
  explicit TidalField(const FieldSpec& s) : mean_(s.velocity), amp_(s.amplitude), period_(s.period), phase_(s.phase) {}
  void sample(double t, std::span<const Vec3>, std::span<Vec2> out) const override {
    const Vec2 v = mean_ + std::cos(2.0 * std::numbers::pi * t / period_ + phase_) * amp_;
    std::fill(out.begin(), out.end(), v);
  }
  bool uniform_in_space() const override { return true; }

 private:
  Vec2 mean_, amp_;
  double period_, phase_;
};

class TimeSeriesField final : public VelocityField {
 public:
  explicit TimeSeriesField(const FieldSpec& s) : t_(s.times), v_(s.values), outside_(s.outside) {}
  void sample(double t, std::span<const Vec3>, std::span<Vec2> out) const override {
    const Vec2 v = at_time(t);
    std::fill(out.begin(), out.end(), v);
  }
  bool uniform_in_space() const override { return true; }

 private:
  Vec2 at_time(double t) const {
    const double t0 = t_.front(), t1 = t_.back();
    if (t < t0 || t > t1) {
      switch (outside_) {
        case TimeBoundary::clamp: return t < t0 ? v_.front() : v_.back();
        case TimeBoundary::cyclic: {
          const double span = t1 - t0;
          t = t0 + (t - t0 - span * std::floor((t - t0) / span));
          t = std::clamp(t, t0, t1);  // rounding of the wrap
          break;
        }
        case TimeBoundary::error: {
          std::ostringstream m;
          m.precision(12);
          m << "time " << t << " s is outside the velocity time series [" << t0 << ", " << t1
            << "] s (outside: error); extend the series or choose outside: clamp or cyclic";
          throw FieldError(m.str());
        }
      }
    }
    const auto hi = std::upper_bound(t_.begin(), t_.end(), t);
    if (hi == t_.end()) return v_.back();
    const std::size_t k = static_cast<std::size_t>(hi - t_.begin());  // t_[k-1] <= t < t_[k]
    const double w = (t - t_[k - 1]) / (t_[k] - t_[k - 1]);
    return (1.0 - w) * v_[k - 1] + w * v_[k];
  }

  std::vector<double> t_;
  std::vector<Vec2> v_;
  TimeBoundary outside_;
};

}  // namespace

std::string field_spec_error(const FieldSpec& s) {
  if (!finite(s.velocity) || !finite(s.origin) || !finite(s.depth_gradient) || !finite(s.amplitude) ||
      !s.gradient.allFinite() || !std::isfinite(s.angular_velocity) || !std::isfinite(s.max_speed) ||
      !std::isfinite(s.phase))
    return "every value must be finite";
  switch (s.kind) {
    case FieldKind::uniform:
    case FieldKind::linear:
    case FieldKind::solid_body: return {};
    case FieldKind::rankine:
      if (!(s.core_radius > 0.0) || !std::isfinite(s.core_radius)) return "core_radius must be > 0 m";
      return {};
    case FieldKind::tidal:
      if (!(s.period > 0.0) || !std::isfinite(s.period)) return "period must be > 0 s";
      return {};
    case FieldKind::time_series: {
      if (s.times.size() < 2) return "times needs at least 2 entries";
      if (s.values.size() != s.times.size())
        return "values has " + std::to_string(s.values.size()) + " entries but times has " +
               std::to_string(s.times.size());
      for (std::size_t i = 0; i < s.times.size(); ++i) {
        if (!std::isfinite(s.times[i]) || !finite(s.values[i])) return "every value must be finite";
        if (i > 0 && !(s.times[i] > s.times[i - 1]))
          return "times must increase strictly (entry " + std::to_string(i) + " is not after entry " +
                 std::to_string(i - 1) + ")";
      }
      return {};
    }
    case FieldKind::file: {
      if (!s.grid) return "the field file '" + s.path + "' is not loaded";
      if (std::string e = grid_data_error(*s.grid); !e.empty()) return s.path + ": " + e;
      if (!finite(s.no_water_velocity)) return "no_water_velocity must be finite";
      if (!finite(s.offset) || !std::isfinite(s.time_offset)) return "offset and time_offset must be finite";
      return {};
    }
  }
  return "unknown field kind";
}

std::shared_ptr<const VelocityField> make_field(const FieldSpec& s) {
  if (const std::string err = field_spec_error(s); !err.empty())
    throw std::invalid_argument(std::string(to_string(s.kind)) + " field: " + err);
  switch (s.kind) {
    case FieldKind::uniform: return std::make_shared<UniformField>(s.velocity);
    case FieldKind::linear: return std::make_shared<LinearField>(s);
    case FieldKind::solid_body:
    case FieldKind::rankine: return std::make_shared<VortexField>(s);
    case FieldKind::tidal: return std::make_shared<TidalField>(s);
    case FieldKind::time_series: return std::make_shared<TimeSeriesField>(s);
    case FieldKind::file:
      return std::make_shared<GriddedField>(
          s.grid, GriddedFieldOptions{s.outside, s.no_water, s.no_water_velocity, s.path, s.offset, s.time_offset});
  }
  throw std::invalid_argument("unknown field kind");
}

}  // namespace polyfloe::forcing
