#include "field_args.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>
#include <sstream>

namespace polyfloe::coupling::app {

namespace {

namespace fs = std::filesystem;

std::vector<double> numbers(const std::string& opt, const std::string& text) {
  std::vector<double> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    const double x = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0' || !std::isfinite(x))
      throw UsageError(opt + ": expected numbers separated by commas, got '" + text + "'");
    v.push_back(x);
  }
  if (v.empty()) throw UsageError(opt + ": expected numbers separated by commas, got '" + text + "'");
  return v;
}

// --times W: auto, all, latest, A:B (either end open) or a list of times [s].
TimeSelection parse_times(const std::string& o, const std::string& w) {
  using K = TimeSelection::Kind;
  TimeSelection t;
  if (w == "auto") {
    t.kind = K::automatic;
  } else if (w == "all") {
    t.kind = K::all;
  } else if (w == "latest") {
    t.kind = K::latest;
  } else if (const std::size_t colon = w.find(':'); colon != std::string::npos) {  // A:B, either end open
    t.kind = K::range;
    const std::string lo = w.substr(0, colon), hi = w.substr(colon + 1);
    t.times = {lo.empty() ? -std::numeric_limits<double>::infinity() : numbers(o, lo).at(0),
               hi.empty() ? std::numeric_limits<double>::infinity() : numbers(o, hi).at(0)};
    if (!(t.times[1] >= t.times[0]) || hi.find(',') != std::string::npos)
      throw UsageError("--times: a range is A:B with A <= B [s] (either end may be left out), got '" + w + "'");
  } else {
    t.kind = K::listed;
    t.times = numbers(o, w);
  }
  return t;
}

// The grid's options (--cell, --bounds, --z, --max-nodes, --surface) into g; false for any other option.
bool grid_option(const std::string& o, const std::function<std::string()>& value, GridSpec& g) {
  if (o == "--cell") {
    const std::string w = value();
    if (w == "auto") {
      g.cell = 0.0;
      return true;
    }
    const std::vector<double> c = numbers(o, w);
    if (c.size() != 1 || !(c[0] > 0.0)) throw UsageError("--cell: expected one spacing > 0 m");
    g.cell = c[0];
  } else if (o == "--bounds") {
    const std::vector<double> b = numbers(o, value());
    if (b.size() != 4 || !(b[2] > b[0]) || !(b[3] > b[1]))
      throw UsageError("--bounds: expected X0,Y0,X1,Y1 [m] with X1 > X0 and Y1 > Y0");
    g.bounds = Eigen::Vector4d(b[0], b[1], b[2], b[3]);
  } else if (o == "--z") {
    g.z = numbers(o, value());
  } else if (o == "--max-nodes") {
    const std::vector<double> n = numbers(o, value());
    if (n.size() != 1 || !(n[0] >= 1.0) || n[0] > 1e10) throw UsageError("--max-nodes: expected a count in [1, 1e10]");
    g.max_nodes = n[0];
  } else if (o == "--surface") {
    const std::vector<double> z = numbers(o, value());
    if (z.size() != 1) throw UsageError("--surface: expected one height [m]");
    g.surface = z[0];
  } else {
    return false;
  }
  return true;
}

// The case's transform (--scale, --rotate, --translate, --velocity-scale) into t; false for any other option.
bool transform_option(const std::string& o, const std::function<std::string()>& value, CaseTransform& t) {
  if (o == "--scale") {
    const std::vector<double> k = numbers(o, value());
    if ((k.size() != 1 && k.size() != 3) ||
        std::any_of(k.begin(), k.end(), [](double x) { return !(x > 0.0) || x > 1e9; }))
      throw UsageError("--scale: expected one factor S or three SX,SY,SZ, each in (0, 1e9]");
    t.scale = k.size() == 1 ? Eigen::Vector3d::Constant(k[0]) : Eigen::Vector3d(k[0], k[1], k[2]);
  } else if (o == "--rotate") {
    const std::vector<double> d = numbers(o, value());
    if (d.size() != 1 || std::abs(d[0]) > 360.0)
      throw UsageError("--rotate: expected one angle in [-360, 360] degrees");
    t.rotate = d[0];
  } else if (o == "--translate") {
    const std::vector<double> d = numbers(o, value());
    if (d.size() != 3 || std::any_of(d.begin(), d.end(), [](double x) { return std::abs(x) > 1e9; }))
      throw UsageError("--translate: expected X,Y,Z [m], each within 1e9 m");
    t.translate = Eigen::Vector3d(d[0], d[1], d[2]);
  } else if (o == "--velocity-scale") {
    const std::vector<double> k = numbers(o, value());
    if (k.size() != 1 || !(k[0] > 0.0) || k[0] > 1e6)
      throw UsageError("--velocity-scale: expected one factor in (0, 1e6]");
    t.velocity_scale = k[0];
  } else {
    return false;
  }
  return true;
}

// The arguments a command takes, and import's output file, checked before any (long) work; the case given as its
// folder.
void check_arguments(Args& a) {
  const std::size_t want = a.command == "compare" ? 2 : 1;
  if (a.positional.size() != want)
    throw UsageError(a.command + " takes " +
                     (want == 2             ? "CASE FILE"
                      : a.command == "info" ? "FILE"
                                            : "CASE") +
                     ", got " + std::to_string(a.positional.size()) + " argument(s)");
  if (a.command == "import" && a.output.empty()) throw UsageError("import needs -o FILE");
  if (a.command == "import") {
    // Checked before the (long) import: the file is HDF5 (.h5), its .pvd and .vtr frames go beside it.
    const std::string ext = a.output.extension().string();
    if (ext != ".h5" && ext != ".hdf5")
      throw UsageError("-o " + a.output.string() +
                       ": a field file is HDF5, named FILE.h5 (its ParaView series "
                       "FILE.pvd and FILE/ go beside it), got the extension '" +
                       ext + "'");
    std::error_code ec;
    const fs::path parent = fs::absolute(a.output, ec).parent_path();
    if (!fs::is_directory(parent, ec))
      throw UsageError("-o " + a.output.string() + ": the folder " + parent.string() + " does not exist");
    if (fs::is_directory(a.output, ec)) throw UsageError("-o " + a.output.string() + ": a folder, not a file name");
  }
  // The case may be given as its folder, or as a file in it that names it for ParaView (CASE/case.foam, any
  // *.foam) or its system/controlDict.
  if (a.command != "info" && !a.positional.empty()) {
    fs::path c = a.positional[0];
    std::error_code ec;
    if (c.extension() == ".foam" && !fs::is_directory(c, ec))
      c = c.parent_path();
    else if (c.filename() == "controlDict" && c.parent_path().filename() == "system")
      c = c.parent_path().parent_path();
    a.positional[0] = c.empty() ? "." : c.string();
  }
}

}  // namespace

// The command line on CLI11: each option's value goes through this file's checks (their messages name the option and
// what it takes); a later option of the same name replaces an earlier one; every command takes every option.
Args parse(int argc, char** argv) {
  Args a;
  if (argc < 2) throw UsageError("no command given");
  a.command = argv[1];
  if (a.command != "import" && a.command != "info" && a.command != "compare")
    throw UsageError("unknown command '" + a.command + "' (import, info, compare)");
  CLI::App app("polyfloe field", "polyfloe field");
  app.set_help_flag();  // --help is answered before the parse (kUsage)
  app.require_subcommand(1, 1);
  CLI::App* cmd = app.add_subcommand(a.command);
  cmd->set_help_flag();
  cmd->add_option("arguments", a.positional, "CASE and/or FILE");
  auto option = [&](const char* names, std::function<void(const std::string& name, const std::string& value)> take) {
    const std::string name = std::string(names).substr(std::string(names).rfind(',') + 1);
    cmd->add_option_function<std::string>(names, [take, name](const std::string& v) { take(name, v); })
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  };
  for (const char* name : {"--cell", "--bounds", "--z", "--max-nodes", "--surface"})
    option(name, [&a](const std::string& o, const std::string& v) {
      grid_option(
          o, [&v] { return v; }, a.grid);
    });
  for (const char* name : {"--scale", "--rotate", "--translate", "--velocity-scale"})
    option(name, [&a](const std::string& o, const std::string& v) {
      transform_option(
          o, [&v] { return v; }, a.transform);
    });
  option("-o,--output", [&a](const std::string&, const std::string& v) { a.output = v; });
  option("--times", [&a](const std::string& o, const std::string& v) { a.times = parse_times(o, v); });
  option("--points", [&a](const std::string& o, const std::string& v) {
    const std::vector<double> n = numbers(o, v);
    if (n.size() != 1 || !(n[0] >= 1.0) || n[0] > 1e8 || n[0] != std::floor(n[0]))
      throw UsageError("--points: expected a whole number in [1, 1e8]");
    a.points = static_cast<long>(n[0]);
  });
  option("--seed", [&a](const std::string& o, const std::string& v) {
    const std::vector<double> n = numbers(o, v);
    if (n.size() != 1 || n[0] < 0 || n[0] > 4e9 || n[0] != std::floor(n[0]))
      throw UsageError("--seed: expected a whole number in [0, 4e9]");
    a.seed = static_cast<unsigned>(n[0]);
  });
  cmd->add_flag_callback("--no-vtk", [&a] { a.vtk = false; });
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    throw UsageError(e.what());
  }
  check_arguments(a);
  return a;
}

}  // namespace polyfloe::coupling::app
