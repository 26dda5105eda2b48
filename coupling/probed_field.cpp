#include "probed_field.h"

#include <sstream>
#include <stdexcept>

namespace polyfloe::coupling {

ProbedField::ProbedField(std::shared_ptr<const std::vector<MeshSnapshot>> snapshots,
                         forcing::GriddedFieldOptions options)
    : snapshots_(std::move(snapshots)), options_(std::move(options)) {
  if (!snapshots_ || snapshots_->empty()) throw std::invalid_argument(options_.source + ": no snapshot");
  for (const MeshSnapshot& s : *snapshots_) times_.push_back(s.time());
  for (std::size_t i = 1; i < times_.size(); ++i)
    if (!(times_[i] > times_[i - 1])) throw std::invalid_argument(options_.source + ": snapshot times must increase");
}

bool ProbedField::contains(const forcing::Vec3& p) const {
  Eigen::Vector3d u;
  return snapshots_->front().sample(p, u);
}

void ProbedField::sample(double t, std::span<const forcing::Vec3> points, std::span<forcing::Vec2> out) const {
  const forcing::TimeBracket tb = forcing::time_bracket(times_, t, options_.time_outside, options_.source);
  const std::vector<MeshSnapshot>& s = *snapshots_;
  Eigen::Vector3d a, b;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const forcing::Vec3& p = points[k];
    // In water when both snapshots around t hold p (a moving mesh may hold it in one only).
    if (s[tb.i].sample(p, a) && (tb.w == 0.0 || s[tb.i + 1].sample(p, b))) {
      if (tb.w > 0.0) a += tb.w * (b - a);
      out[k] = a.head<2>();
      continue;
    }
    if (options_.no_water == forcing::OutsideWater::velocity) {
      out[k] = options_.no_water_velocity;
      continue;
    }
    std::ostringstream os;
    os << options_.source << ": no water at (" << p.x() << ", " << p.y() << ", " << p.z()
       << ") m: outside the OpenFOAM mesh";
    throw forcing::FieldError(os.str());
  }
}

}  // namespace polyfloe::coupling
