#include "forcing/gridded_field.h"

#include <algorithm>
#include <map>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace polyfloe::forcing {

namespace {

std::string axis_error(const std::vector<double>& a, const char* name, std::size_t min_size) {
  std::ostringstream os;
  if (a.size() < min_size) {
    os << "axis " << name << " has " << a.size() << " values, needs at least " << min_size;
    return os.str();
  }
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!std::isfinite(a[i])) {
      os << "axis " << name << " is not finite at index " << i;
      return os.str();
    }
    if (i > 0 && !(a[i] > a[i - 1])) {
      os << "axis " << name << " is not strictly increasing at index " << i << " (" << a[i - 1] << ", " << a[i] << ")";
      return os.str();
    }
  }
  return {};
}

// Where p falls on an axis: the lower node and the weight of the upper one (0 for a single-node axis).
struct AxisHit {
  std::size_t i = 0;
  double w = 0.0;
};

// Where p falls on axis `a`: a direct index for uniform spacing (what the importer writes), else a binary search.
inline AxisHit locate(const std::vector<double>& a, const GriddedField::AxisScale& scale, double p) {
  if (a.size() < 2) return {};
  p = std::clamp(p, a.front(), a.back());
  if (scale.uniform) {  // one multiplication, no division
    const double s = (p - a.front()) * scale.inv_h;
    const std::size_t i = std::min(static_cast<std::size_t>(s), a.size() - 2);
    return {i, std::clamp(s - static_cast<double>(i), 0.0, 1.0)};
  }
  std::size_t i = static_cast<std::size_t>(std::upper_bound(a.begin(), a.end(), p) - a.begin());
  i = std::clamp<std::size_t>(i, 1, a.size() - 1) - 1;
  return {i, std::clamp((p - a[i]) / (a[i + 1] - a[i]), 0.0, 1.0)};
}

bool contains(const std::vector<double>& a, double p) { return p >= a.front() && p <= a.back(); }

}  // namespace

std::string grid_data_error(const GridData& g) {
  for (auto [a, name, min] : {std::tuple{&g.x, "x", 2}, {&g.y, "y", 2}, {&g.z, "z", 1}, {&g.t, "t", 1}})
    if (std::string e = axis_error(*a, name, static_cast<std::size_t>(min)); !e.empty()) return e;
  const std::size_t n = g.nodes_per_snapshot(), total = n * g.t.size();
  std::ostringstream os;
  for (auto [c, name] : {std::pair{&g.u, "u"}, {&g.v, "v"}}) {
    if (c->size() != total) {
      os << name << " has " << c->size() << " values, expected " << total << " (t x z x y x x = " << g.t.size() << " x "
         << g.z.size() << " x " << g.y.size() << " x " << g.x.size() << ")";
      return os.str();
    }
    for (std::size_t k = 0; k < total; ++k)
      if (!(std::abs((*c)[k]) <= kMaxFieldSpeed)) {
        const std::size_t ix = k % g.x.size(), iy = k / g.x.size() % g.y.size(),
                          iz = k / (g.x.size() * g.y.size()) % g.z.size(), it = k / n;
        os << name;
        if (std::isfinite((*c)[k]))
          os << " = " << (*c)[k] << " m/s is beyond the " << kMaxFieldSpeed << " m/s any current may have";
        else
          os << " is not finite";
        os << " at node (t " << it << ", z " << iz << ", y " << iy << ", x " << ix << ")";
        if (std::isfinite((*c)[k])) os << " (are the velocities in other units?)";
        return os.str();
      }
  }
  if (g.wet.size() != n) {
    os << "wet has " << g.wet.size() << " values, expected " << n << " (z x y x x)";
    return os.str();
  }
  for (std::size_t k = 0; k < n; ++k)
    if (g.wet[k] > 1) {
      os << "wet must be 0 or 1, found " << int(g.wet[k]) << " at index " << k;
      return os.str();
    }
  if (std::find(g.wet.begin(), g.wet.end(), std::uint8_t{1}) == g.wet.end()) return "no node is wet";
  return {};
}

std::vector<LandRectangle> land_rectangles(const GridData& g) {
  const std::size_t nx = g.x.size(), ny = g.y.size();
  std::size_t iz = 0;
  for (std::size_t k = 1; k < g.z.size(); ++k)
    if (std::abs(g.z[k]) < std::abs(g.z[iz])) iz = k;
  // A node's square: from half-way to its neighbours (half a spacing beyond the grid's first and last nodes).
  auto edge = [](const std::vector<double>& a,
                 std::size_t i) {  // the boundary below node i (i = a.size(): above the last)
    if (i == 0) return a[0] - 0.5 * (a[1] - a[0]);
    if (i == a.size()) return a.back() + 0.5 * (a.back() - a[a.size() - 2]);
    return 0.5 * (a[i - 1] + a[i]);
  };
  struct Open {
    std::size_t y0;
    bool seen;
  };
  std::map<std::pair<std::size_t, std::size_t>, Open> open;  // run [x0, x1) -> the row it started in
  std::vector<LandRectangle> out;
  auto close = [&](std::pair<std::size_t, std::size_t> run, std::size_t y0, std::size_t y1) {
    out.push_back({Vec2(edge(g.x, run.first), edge(g.y, y0)), Vec2(edge(g.x, run.second), edge(g.y, y1))});
  };
  for (std::size_t iy = 0; iy <= ny; ++iy) {
    for (auto& [run, o] : open) o.seen = false;
    if (iy < ny)
      for (std::size_t ix = 0; ix < nx;) {
        if (g.wet[g.index(0, iz, iy, ix)]) {
          ++ix;
          continue;
        }
        std::size_t end = ix;
        while (end < nx && !g.wet[g.index(0, iz, iy, end)]) ++end;
        const auto [it, fresh] = open.try_emplace({ix, end}, Open{iy, true});
        it->second.seen = true;
        ix = end;
      }
    for (auto it = open.begin(); it != open.end();) {
      if (it->second.seen) {
        ++it;
        continue;
      }
      close(it->first, it->second.y0, iy);
      it = open.erase(it);
    }
  }
  return out;
}

TimeBracket time_bracket(std::span<const double> times, double t, TimeBoundary outside, const std::string& source) {
  if (times.size() < 2) return {};
  const double first = times.front(), last = times.back();
  if (t < first || t > last) {
    switch (outside) {
      case TimeBoundary::clamp: t = std::clamp(t, first, last); break;
      case TimeBoundary::cyclic: {
        const double period = last - first;
        t = std::clamp(first + (t - first - period * std::floor((t - first) / period)), first, last);
        break;
      }
      case TimeBoundary::error: {
        std::ostringstream os;
        os << source << ": time " << t << " s is outside the field's snapshots [" << first << ", " << last
           << "] s (the field says outside: error)";
        throw FieldError(os.str());
      }
    }
  }
  std::size_t i = static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin());
  i = std::clamp<std::size_t>(i, 1, times.size() - 1) - 1;
  return {i, std::clamp((t - times[i]) / (times[i + 1] - times[i]), 0.0, 1.0)};
}

GriddedField::AxisScale GriddedField::scale_of(const std::vector<double>& a) {
  if (a.size() < 2) return {};
  const double h = (a.back() - a.front()) / static_cast<double>(a.size() - 1);
  for (std::size_t i = 1; i < a.size(); ++i)
    if (std::abs(a[i] - (a.front() + h * static_cast<double>(i))) > 1e-9 * std::max(h, std::abs(a[i]))) return {};
  return {true, 1.0 / h};
}

GriddedField::GriddedField(std::shared_ptr<const GridData> grid, GriddedFieldOptions options)
    : grid_(std::move(grid)), options_(std::move(options)) {
  if (!grid_) throw std::invalid_argument("gridded field: no grid");
  if (std::string e = grid_data_error(*grid_); !e.empty())
    throw std::invalid_argument((options_.source.empty() ? "" : options_.source + ": ") + e);
  sx_ = scale_of(grid_->x);
  sy_ = scale_of(grid_->y);
  sz_ = scale_of(grid_->z);
  const GridData& g = *grid_;
  const std::size_t nx = g.x.size(), ny = g.y.size(), nz = g.z.size(), nxy = nx * ny;
  const std::size_t dz = nz > 1 ? nxy : 0;
  if (nz == 1 && g.t.size() == 1 && nxy <= 10'000'000) {
    uv_.resize(2 * nxy);
    for (std::size_t n = 0; n < nxy; ++n) {
      uv_[2 * n] = g.u[n];
      uv_[2 * n + 1] = g.v[n];
    }
  }
  all_wet_.assign(g.wet.size(), 0);
  for (std::size_t iz = 0; iz < (nz > 1 ? nz - 1 : 1); ++iz)
    for (std::size_t iy = 0; iy + 1 < ny; ++iy)
      for (std::size_t ix = 0; ix + 1 < nx; ++ix) {
        const std::size_t n = iz * nxy + iy * nx + ix;
        all_wet_[n] = g.wet[n] && g.wet[n + 1] && g.wet[n + nx] && g.wet[n + nx + 1] && g.wet[n + dz] &&
                      g.wet[n + dz + 1] && g.wet[n + dz + nx] && g.wet[n + dz + nx + 1];
      }
  if (!std::isfinite(options_.no_water_velocity.x()) || !std::isfinite(options_.no_water_velocity.y()))
    throw std::invalid_argument("gridded field: the no-water velocity is not finite");
}

void GriddedField::sample(double t, std::span<const Vec3> points, std::span<Vec2> out) const {
  const GridData& g = *grid_;
  const TimeBracket tb = time_bracket(g.t, t + options_.time_offset, options_.time_outside, options_.source);
  const std::size_t t0 = tb.i;
  const double wt = tb.w;
  const bool two_times = wt > 0.0;
  const std::size_t nx = g.x.size(), nxy = nx * g.y.size(), per_t = g.nodes_per_snapshot();
  const std::size_t dz = g.z.size() > 1 ? nxy : 0;
  // The common case, a steady depth-averaged field on a uniform grid (a 2-D OpenFOAM case): bilinear in the water,
  // the general loop below for the rest (land nearby, off the grid).
  const bool plain = dz == 0 && !two_times && sx_.uniform && sy_.uniform && !uv_.empty();
  const double* uv = uv_.data();
  const double x0 = g.x.front(), y0 = g.y.front();
  const double sx_max = static_cast<double>(nx - 1), sy_max = static_cast<double>(g.y.size() - 1);

  for (std::size_t k = 0; k < points.size(); ++k) {
    const Vec3 p(points[k].x() - options_.offset.x(), points[k].y() - options_.offset.y(), points[k].z());
    if (plain) {
      const double sx = (p.x() - x0) * sx_.inv_h, sy = (p.y() - y0) * sy_.inv_h;
      if (sx >= 0.0 && sy >= 0.0 && sx <= sx_max && sy <= sy_max) {
        const std::size_t ix = std::min(static_cast<std::size_t>(sx), nx - 2);
        const std::size_t iy = std::min(static_cast<std::size_t>(sy), g.y.size() - 2);
        const std::size_t n = iy * nx + ix;
        if (all_wet_[n]) {
          const double wx = sx - static_cast<double>(ix), wy = sy - static_cast<double>(iy);
          const double a = (1.0 - wx) * (1.0 - wy), b = wx * (1.0 - wy), c = (1.0 - wx) * wy, d = wx * wy;
          const double* q = uv + 2 * n;
          const double* r = q + 2 * nx;
          out[k] = Vec2{a * q[0] + b * q[2] + c * r[0] + d * r[2], a * q[1] + b * q[3] + c * r[1] + d * r[3]};
          continue;
        }
      }
    }
    const bool inside = contains(g.x, p.x()) && contains(g.y, p.y());
    double u = 0.0, v = 0.0, wet = 0.0;
    if (inside) {
      const AxisHit hx = locate(g.x, sx_, p.x()), hy = locate(g.y, sy_, p.y()), hz = locate(g.z, sz_, p.z());
      const std::size_t base = hz.i * nxy + hy.i * nx + hx.i;
      // The 8 corners (4 when the field is the same at every depth: dz = 0 and the z weight is 0).
      const std::size_t offset[8] = {0, 1, nx, nx + 1, dz, dz + 1, dz + nx, dz + nx + 1};
      const double wx[2] = {1.0 - hx.w, hx.w}, wy[2] = {1.0 - hy.w, hy.w}, wz[2] = {1.0 - hz.w, hz.w};
      // Where every corner is water (most cells) the land tests are skipped: the same sums in the same order.
      const bool all_wet = all_wet_[base];
      for (int c = 0; c < (dz ? 8 : 4); ++c) {
        const double w = wx[c & 1] * wy[(c >> 1) & 1] * wz[c >> 2];
        const std::size_t n = base + offset[c];
        if (!all_wet && (w == 0.0 || !g.wet[n])) continue;  // land: zero velocity, and it does not count as water
        wet += w;
        const std::size_t i0 = t0 * per_t + n;
        double cu = g.u[i0], cv = g.v[i0];
        if (two_times) {
          cu += wt * (g.u[i0 + per_t] - cu);
          cv += wt * (g.v[i0 + per_t] - cv);
        }
        u += w * cu;
        v += w * cv;
      }
    }
    if (wet > 1e-9) {
      out[k] = Vec2{u, v};
      continue;
    }
    if (options_.no_water == OutsideWater::velocity) {
      out[k] = options_.no_water_velocity;
      continue;
    }
    std::ostringstream os;
    os << options_.source << ": no water at (" << points[k].x() << ", " << points[k].y() << ", " << p.z() << ") m";
    if (options_.offset != Vec2::Zero()) os << " (the file's (" << p.x() << ", " << p.y() << ") m, offset applied)";
    os << ": ";
    if (!inside)
      os << "outside the field's grid x [" << g.x.front() << ", " << g.x.back() << "], y [" << g.y.front() << ", "
         << g.y.back() << "] m";
    else
      os << "on land (every grid node around it is dry)";
    os << "; to give floes there a fixed current set no_water: velocity and no_water_velocity: [u, v] in the field";
    throw FieldError(os.str());
  }
}

}  // namespace polyfloe::forcing
