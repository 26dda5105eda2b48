// The direct mode: a VelocityField that samples the OpenFOAM mesh itself at every call (cell location plus the
// cell's interpolation), linear between snapshots. It is the reference a gridded field file is measured against
// (`polyfloe field compare`, tests/bench/bench_field_sampling.cpp); it costs a cell search per sample.
#pragma once

#include <memory>
#include <vector>

#include "forcing/gridded_field.h"
#include "openfoam_case.h"

namespace polyfloe::coupling {

class ProbedField final : public forcing::VelocityField {
 public:
  // `options` as for a gridded field: the time boundary, what a point outside the mesh gets, the name in errors.
  ProbedField(std::shared_ptr<const std::vector<MeshSnapshot>> snapshots, forcing::GriddedFieldOptions options);
  void sample(double t, std::span<const forcing::Vec3> points, std::span<forcing::Vec2> out) const override;
  // Whether p is in the mesh (in water) [m].
  bool contains(const forcing::Vec3& p) const;

 private:
  std::shared_ptr<const std::vector<MeshSnapshot>> snapshots_;
  std::vector<double> times_;
  forcing::GriddedFieldOptions options_;
};

}  // namespace polyfloe::coupling
