#include "io/progress.h"

#include <algorithm>
#include <cmath>

namespace polyfloe::io {
namespace {

constexpr double kRedrawInterval = 0.2;  // [s] of wall time between interactive redraws

std::string printf_string(const char* fmt, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, x);
  return buf;
}

std::string format_rate(double steps_per_second) {
  if (!std::isfinite(steps_per_second) || steps_per_second < 0.0) return "? steps/s";
  if (steps_per_second < 10.0) return printf_string("%.2f steps/s", steps_per_second);
  return printf_string("%.0f steps/s", steps_per_second);
}

}  // namespace

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0) return "?";
  const auto s = static_cast<long long>(std::llround(seconds));
  char buf[48];
  if (s < 60) {
    std::snprintf(buf, sizeof buf, "%llds", s);
  } else if (s < 3600) {
    std::snprintf(buf, sizeof buf, "%lldm%02llds", s / 60, s % 60);
  } else if (s < 86400) {
    std::snprintf(buf, sizeof buf, "%lldh%02lldm", s / 3600, (s % 3600) / 60);
  } else {
    std::snprintf(buf, sizeof buf, "%lldd%02lldh", s / 86400, (s % 86400) / 3600);
  }
  return buf;
}

std::string format_sim_time(double t, double t_end) {
  if (!(t_end > 0.0) || !std::isfinite(t_end)) return printf_string("%g", t);
  const int decimals = std::clamp(2 - static_cast<int>(std::floor(std::log10(t_end))), 0, 6);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, t);
  return buf;
}

std::string format_progress_line(double t, double t_end, double steps_per_second, double eta_seconds) {
  const double percent = t_end > 0.0 ? 100.0 * t / t_end : 100.0;
  std::string line = "t = " + format_sim_time(t, t_end) + " / " + printf_string("%g", t_end) + " s (" +
                     printf_string("%.1f", percent) + " %)  " + format_rate(steps_per_second);
  line += "  ETA " + (eta_seconds < 0.0 ? std::string("?") : format_duration(eta_seconds));
  return line;
}

std::string format_progress_report(double t, double t_end, double steps_per_second) {
  return "t = " + format_sim_time(t, t_end) + " / " + printf_string("%g", t_end) + " s, " +
         format_rate(steps_per_second);
}

std::string format_progress_summary(double t, double t_end, std::uint64_t steps, double wall_seconds) {
  const double rate = wall_seconds > 0.0 ? static_cast<double>(steps) / wall_seconds : -1.0;
  return "done: t = " + format_sim_time(t, t_end) + " s, " + std::to_string(steps) + " steps in " +
         format_duration(wall_seconds) + " (" + format_rate(rate) + ")";
}

Progress::Progress(double t_end, bool interactive, std::FILE* out, std::uint64_t first_step)
    : t_end_(t_end),
      interactive_(interactive),
      out_(out),
      start_wall_(Clock::now()),
      last_draw_(start_wall_),
      first_step_(first_step) {}

Progress::~Progress() {
  if (interactive_ && drawn_width_ > 0 && !finished_) {
    std::fputc('\n', out_);
    std::fflush(out_);
  }
}

double Progress::seconds_since_start(Clock::time_point now) const {
  return std::chrono::duration<double>(now - start_wall_).count();
}

double Progress::steps_per_second(std::uint64_t steps, double wall) const {
  return wall > 0.0 ? static_cast<double>(steps - start_steps_) / wall : -1.0;
}

double Progress::eta(double t, double wall) const {
  const double done = t - start_t_;
  if (!(done > 0.0) || !(wall > 0.0)) return -1.0;
  return std::max(0.0, t_end_ - t) * wall / done;
}

void Progress::redraw(const std::string& line) {
  // Pad with blanks over the remains of a longer previous line.
  std::string text = "\r" + line;
  if (line.size() < drawn_width_) text.append(drawn_width_ - line.size(), ' ');
  drawn_width_ = line.size();
  std::fputs(text.c_str(), out_);
  std::fflush(out_);
}

void Progress::update(double t, std::uint64_t steps) {
  const auto now = Clock::now();
  if (!started_) {  // measure from here: set-up time is not simulation time
    started_ = true;
    start_wall_ = last_draw_ = now;
    start_t_ = t;
    start_steps_ = steps;
    if (t_end_ > 0.0) next_decile_ = static_cast<int>(std::floor(10.0 * t / t_end_ + 1e-9)) + 1;
    return;
  }
  const double wall = seconds_since_start(now);
  if (interactive_) {
    if (std::chrono::duration<double>(now - last_draw_).count() < kRedrawInterval) return;
    last_draw_ = now;
    redraw(format_progress_line(t, t_end_, steps_per_second(steps, wall), eta(t, wall)));
    return;
  }
  if (next_decile_ > 9 || !(t_end_ > 0.0)) return;
  if (10.0 * t < next_decile_ * t_end_ * (1.0 - 1e-12)) return;
  next_decile_ = static_cast<int>(std::floor(10.0 * t / t_end_ + 1e-9)) + 1;
  std::fprintf(out_, "%s\n", format_progress_report(t, t_end_, steps_per_second(steps, wall)).c_str());
  std::fflush(out_);
}

void Progress::finish(double t, std::uint64_t steps) {
  if (finished_) return;
  finished_ = true;
  // Never updated: the run had nothing left to do (a restart from its final checkpoint), no rate to report.
  // The steps of the whole run; the wall time from the first update (set-up excluded), as the rates.
  const std::string summary =
      started_ ? format_progress_summary(t, t_end_, steps - first_step_, seconds_since_start(Clock::now()))
               : "done: t = " + format_sim_time(t, t_end_) + " s, no step left to take";
  if (interactive_) {
    redraw(summary);
    std::fputc('\n', out_);
  } else {
    std::fprintf(out_, "%s\n", summary.c_str());
  }
  std::fflush(out_);
}

}  // namespace polyfloe::io
