// Progress of a run on stderr.
//
// Interactive (a terminal): one line redrawn in place with '\r' at most ~5 times a second:
//   t = 12.5 / 300 s (4.2 %)  1234 steps/s  ETA 3m52s
// Not interactive (a log file): nothing but a line at every 10 % of the simulated time,
//   t = 30 / 300 s, 1234 steps/s
// and, from finish(), a one-line summary. Rates are measured from the first update() on, so set-up time does
// not count and a restart (steps not starting at 0) reads right.
#pragma once

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>

namespace polyfloe::io {

// "42s", "3m05s", "2h07m", "3d04h"; "?" for a negative or non-finite duration [s].
std::string format_duration(double seconds);
// Simulated time with as many decimals as the end time needs (300 -> "30", 10 -> "1.0", 0.5 -> "0.050") [s].
std::string format_sim_time(double t, double t_end);
// The interactive line; eta_seconds < 0 means not yet known.
std::string format_progress_line(double t, double t_end, double steps_per_second, double eta_seconds);
// The non-interactive line printed at each 10 %.
std::string format_progress_report(double t, double t_end, double steps_per_second);
// The final summary: "done: t = 300 s, 123456 steps in 1m40s (1234 steps/s)".
std::string format_progress_summary(double t, double t_end, std::uint64_t steps, double wall_seconds);

class Progress {
 public:
  // `t_end` [s]; `interactive`: the caller passes isatty(fileno(stderr)). `out` is for tests. `first_step`: the
  // step count the run starts from (a restart: its checkpoint's), so the summary counts this run's steps.
  Progress(double t_end, bool interactive, std::FILE* out = stderr, std::uint64_t first_step = 0);
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  ~Progress();  // ends a half-drawn interactive line, so later messages start on their own line

  // Cheap enough to call every step: it reads the clock and prints only when a line is due.
  void update(double t, std::uint64_t steps);
  // Ends the progress display with the summary line (t, steps: the final values).
  void finish(double t, std::uint64_t steps);

 private:
  using Clock = std::chrono::steady_clock;
  double seconds_since_start(Clock::time_point now) const;
  double steps_per_second(std::uint64_t steps, double wall) const;
  double eta(double t, double wall) const;
  void redraw(const std::string& line);

  double t_end_;
  bool interactive_;
  std::FILE* out_;
  bool started_ = false;
  Clock::time_point start_wall_{}, last_draw_{};
  double start_t_ = 0.0;
  std::uint64_t start_steps_ = 0;  // at the first update (rates)
  std::uint64_t first_step_ = 0;   // at the start of the run (the summary's count)
  int next_decile_ = 1;            // non-interactive: next 10 % mark to report
  std::size_t drawn_width_ = 0;    // interactive: length of the line on screen
  bool finished_ = false;
};

}  // namespace polyfloe::io
