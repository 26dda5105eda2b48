// The progress display: its line formats, a batch job's line every 10 % and summary, a terminal's closing newline.
#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "io/progress.h"

using namespace polyfloe;

namespace {

// Everything written to `f`, read back from its start; closes it.
std::string read_and_close(std::FILE* f) {
  std::rewind(f);
  std::string text;
  char buf[256];
  while (std::fgets(buf, sizeof buf, f)) text += buf;
  std::fclose(f);
  return text;
}

}  // namespace

TEST(Progress, LinesAreExactDurationsUseTwoUnitsAndUnknownRatesAndEtasPrintAsQuestionMarks) {
  EXPECT_EQ(io::format_progress_line(30.0, 300.0, 1234.0, 272.0), "t = 30 / 300 s (10.0 %)  1234 steps/s  ETA 4m32s");
  EXPECT_EQ(io::format_progress_line(0.0, 300.0, -1.0, -1.0), "t = 0 / 300 s (0.0 %)  ? steps/s  ETA ?");
  EXPECT_EQ(io::format_progress_report(30.0, 300.0, 1234.4), "t = 30 / 300 s, 1234 steps/s");
  EXPECT_EQ(io::format_progress_report(0.05, 0.5, 2.5), "t = 0.050 / 0.5 s, 2.50 steps/s");
  EXPECT_EQ(io::format_sim_time(1.0, 10.0), "1.0");
  EXPECT_EQ(io::format_duration(42.0), "42s");
  EXPECT_EQ(io::format_duration(185.0), "3m05s");
  EXPECT_EQ(io::format_duration(7620.0), "2h07m");
  EXPECT_EQ(io::format_duration(3 * 86400.0 + 4 * 3600.0), "3d04h");
  EXPECT_EQ(io::format_duration(-1.0), "?");
  EXPECT_EQ(io::format_progress_summary(300.0, 300.0, 1000, 10.0), "done: t = 300 s, 1000 steps in 10s (100 steps/s)");
}

TEST(Progress, NonInteractivePrintsEveryTenPercentThenSummary) {
  std::FILE* out = std::tmpfile();
  ASSERT_TRUE(out);
  {
    io::Progress p(300.0, false, out);
    for (int s = 0; s <= 3000; ++s) p.update(0.1 * s, static_cast<std::uint64_t>(s));
    p.finish(300.0, 3000);
  }
  const std::string text = read_and_close(out);
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  ASSERT_EQ(lines.size(), 10u) << text;
  EXPECT_EQ(lines[0].rfind("t = 30 / 300 s, ", 0), 0u) << lines[0];
  EXPECT_EQ(lines[8].rfind("t = 270 / 300 s, ", 0), 0u) << lines[8];
  EXPECT_EQ(lines[9].rfind("done: t = 300 s, 3000 steps in ", 0), 0u) << lines[9];
  EXPECT_EQ(text.find('\r'), std::string::npos);
}

TEST(Progress, InteractiveEndsWithNewline) {
  std::FILE* out = std::tmpfile();
  ASSERT_TRUE(out);
  {
    io::Progress p(1.0, true, out);
    p.update(0.0, 0);
    p.finish(1.0, 10);
  }
  const std::string text = read_and_close(out);
  EXPECT_EQ(text.rfind("\rdone: t = 1.00 s, 10 steps in ", 0), 0u) << text;
  EXPECT_EQ(text.back(), '\n');
}
