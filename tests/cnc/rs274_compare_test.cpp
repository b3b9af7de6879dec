// Differential test against LinuxCNC's own interpreter: every program of examples/gcode and
// tests/cnc/corpus is run through the standalone `rs274` of the unpacked Debian linuxcnc-uspace
// package (scripts/fetch-linuxcnc.sh; run as an external program, never linked) and through
// pkm::cnc::Interpreter; every motion's kind, end point, arc centre, turns and feed must agree.
// rs274 prints canonical calls in program units with the offsets reported separately
// (SET_G5X_OFFSET, SET_G92_OFFSET, USE_TOOL_LENGTH_OFFSET, USE_LENGTH_UNITS, all in the units
// active when printed), so the machine position is rebuilt here as
// printed + G5x + G92 + tool offset, converted to mm. rs274 prints 4 decimals: the tolerance is
// half a unit of the last digit per printed term (1e-4 mm class in mm programs, 25.4 times that
// in inch programs). Programs named err_*.ngc must fail in both, on the same line; err_any_*.ngc
// in both, where rs274 reports another line than the one at fault (it searches on for a missing
// M98 subprogram and reports where the search ends; pkm names the M98 line).
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "pkm/cnc/interpreter.hpp"
#include "pkm/core/error.hpp"

namespace pkm::cnc {
namespace PKM_TEST_NS {

namespace fs = std::filesystem;

const fs::path kRoot = PKM_SOURCE_DIR;
const fs::path kLinuxcnc = kRoot / ".cache/linuxcnc/usr";
const fs::path kToolTable =
    kLinuxcnc / "share/doc/linuxcnc/examples/sample-configs/common/tool.tbl";
constexpr double kPrintHalfUnit = 0.5e-4;  // rs274 prints %.4f
constexpr double kTolSlack = 1e-9;

/// One motion as rs274 reports it, rebuilt in machine coordinates (mm, deg).
struct RefMove {
  MoveKind kind = MoveKind::kRapid;
  std::array<double, 6> end{};
  std::array<double, 3> centre{NAN, NAN, NAN};
  int turns = 0;
  double feed = NAN;
  double tol = 0.0;  ///< rounding bound of the printed terms (mm)
};

struct RefRun {
  bool ok = false;
  std::vector<RefMove> moves;
  std::string error_line;         ///< the offending line rs274 echoes after its message
  std::size_t error_line_no = 0;  ///< line named by an "... from line: N" message, else 0
};

std::string shellQuote(const std::string& s) { return "'" + s + "'"; }

std::string runCapture(const std::string& cmd, int& status) {
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  if (p == nullptr) {
    status = -1;
    return out;
  }
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) out.append(buf.data(), n);
  status = pclose(p);
  return out;
}

/// A HOME of this process's own for rs274: LinuxCNC keeps its tool data in $HOME/.tool.mmap, so
/// two rs274 runs with one HOME (ctest -j, the cutter-compensation check) clobber each other's.
const fs::path& rs274Home() {
  struct Home {
    fs::path path = fs::temp_directory_path() / ("pkm_rs274_home_" + std::to_string(::getpid()));
    Home() { fs::create_directories(path); }
    ~Home() {
      std::error_code ec;
      fs::remove_all(path, ec);
    }
  };
  static const Home home;
  return home.path;
}

/// What rs274 prints (standard output and error) for `program` with the parameter file `var`.
std::string runRs274Command(const fs::path& program, const fs::path& var, int& status) {
  return runCapture("HOME=" + shellQuote(rs274Home().string()) +
                        " LD_LIBRARY_PATH=" + shellQuote((kLinuxcnc / "lib").string()) + " " +
                        shellQuote((kLinuxcnc / "bin/rs274").string()) + " -t " +
                        shellQuote(kToolTable.string()) + " -v " + shellQuote(var.string()) +
                        " -g " + shellQuote(program.string()) + " 2>&1",
                    status);
}

bool rs274Available() {
  if (!fs::exists(kLinuxcnc / "bin/rs274") || !fs::exists(kToolTable)) return false;
  const fs::path prog = fs::temp_directory_path() / "pkm_rs274_probe.ngc";
  std::ofstream(prog) << "G0 X1\nM2\n";
  int status = 0;
  const std::string var = (fs::temp_directory_path() / "pkm_rs274_probe.var").string();
  std::ofstream(var).close();
  const std::string out = runRs274Command(prog, var, status);
  return status == 0 && out.find("STRAIGHT_TRAVERSE(1.0000") != std::string::npos;
}

std::vector<double> numbers(const std::string& args) {
  std::vector<double> v;
  std::string s;
  std::string cleaned = args;
  for (char& c : cleaned)
    if (c == ',') c = ' ';
  std::istringstream cin(cleaned);
  while (cin >> s) {
    try {
      std::size_t used = 0;
      const double d = std::stod(s, &used);
      if (used == s.size()) v.push_back(d);
    } catch (...) {
    }
  }
  return v;
}

/// What rs274 has reported before a motion: units, plane, offsets (mm, deg) and feed.
struct Rs274State {
  double scale = 1.0;  ///< mm per program unit
  int plane = 0;       ///< 0 XY, 1 XZ, 2 YZ
  std::array<double, 6> g5x{}, g92{}, tlo{};
  std::array<int, 6> t5{}, t9{}, tt{};  ///< non-zero printed offset terms per axis
  double feed = 0.0;
  double rotation = 0.0;  ///< SET_XY_ROTATION, rad
  bool per_rev = false;   ///< SET_FEED_MODE(0, 1): F per spindle revolution (G95)
  double spindle = 0.0;   ///< SET_SPINDLE_SPEED, rev/min
  double sync = 0.0;      ///< START_SPEED_FEED_SYNC's advance per revolution (mm), 0 when off
  /// A feed move's rate in mm/min, as pkm reports it: F, F·S under G95, K·S under G33.
  [[nodiscard]] double feedRate() const {
    return sync != 0.0 ? sync * spindle : per_rev ? feed * spindle : feed;
  }
};

/// machine = Rz(rotation)·(program + G92) + G5x + tool offset (LinuxCNC's canon), mm.
std::array<double, 6> toMachine(const Rs274State& st, const std::array<double, 6>& program) {
  std::array<double, 6> m{};
  for (std::size_t i = 0; i < 6; ++i) m[i] = program[i] * (i < 3 ? st.scale : 1.0) + st.g92[i];
  const double c = std::cos(st.rotation), s = std::sin(st.rotation);
  const double x = m[0], y = m[1];
  m[0] = c * x - s * y;
  m[1] = s * x + c * y;
  for (std::size_t i = 0; i < 6; ++i) m[i] += st.g5x[i] + st.tlo[i];
  return m;
}

/// Applies the call `name(args)` when it sets units, the plane, an offset or the feed.
void applyRs274Setting(Rs274State& st, const std::string& name, const std::string& args) {
  if (name == "USE_LENGTH_UNITS") {
    st.scale = args.find("INCHES") != std::string::npos ? 25.4 : 1.0;
    return;
  }
  if (name == "SET_XY_ROTATION") {
    st.rotation = numbers(args).at(0) * M_PI / 180.0;
    return;
  }
  if (name == "SELECT_PLANE") {
    st.plane = args.find("XZ") != std::string::npos   ? 1
               : args.find("YZ") != std::string::npos ? 2
                                                      : 0;
    return;
  }
  const std::vector<double> v = numbers(args);
  auto store = [&](std::array<double, 6>& dst, std::array<int, 6>& nz, std::size_t first) {
    for (std::size_t i = 0; i < 6; ++i) {
      dst[i] = v[first + i] * (i < 3 ? st.scale : 1.0);
      nz[i] = v[first + i] != 0.0 ? 1 : 0;
    }
  };
  if (name == "SET_G5X_OFFSET" && v.size() >= 7) {
    store(st.g5x, st.t5, 1);
  } else if (name == "SET_G92_OFFSET" && v.size() >= 6) {
    store(st.g92, st.t9, 0);
  } else if (name == "USE_TOOL_LENGTH_OFFSET" && v.size() >= 6) {
    store(st.tlo, st.tt, 0);
  } else if (name == "SET_FEED_RATE" && !v.empty()) {
    st.feed = v[0] * st.scale;
  } else if (name == "SET_FEED_MODE" && v.size() >= 2) {
    st.per_rev = v[1] == 1.0;
  } else if (name == "SET_SPINDLE_SPEED" && v.size() >= 2) {
    st.spindle = v[1];
  } else if (name == "START_SPEED_FEED_SYNC" && !v.empty()) {
    st.sync = std::abs(v[0]) * st.scale;
  } else if (name == "STOP_SPEED_FEED_SYNCH") {
    st.sync = 0.0;
  }
}

/// The motion call `name(v)` (STRAIGHT_TRAVERSE, STRAIGHT_FEED or ARC_FEED) in machine
/// coordinates, with the rounding bound of its printed terms.
RefMove rs274Motion(const Rs274State& st, const std::string& name, const std::vector<double>& v) {
  std::array<int, 6> terms{};
  for (std::size_t i = 0; i < 6; ++i) terms[i] = 1 + st.t5[i] + st.t9[i] + st.tt[i];
  RefMove m;
  std::array<double, 6> prog{};
  std::array<double, 3> centre{NAN, NAN, NAN};
  if (name == "ARC_FEED") {
    // ARC_FEED(first_end, second_end, first_centre, second_centre, rotation, axis_end, a, b, c)
    // first/second axes: XY -> X,Y; XZ -> Z,X; YZ -> Y,Z.
    static constexpr std::array<std::array<std::size_t, 3>, 3> kAxes{
        {{0, 1, 2}, {2, 0, 1}, {1, 2, 0}}};
    const auto& ax = kAxes[static_cast<std::size_t>(st.plane)];
    prog[ax[0]] = v[0];
    prog[ax[1]] = v[1];
    centre[ax[0]] = v[2];
    centre[ax[1]] = v[3];
    m.turns = static_cast<int>(v[4]);
    prog[ax[2]] = v[5];
    prog[3] = v[6];
    prog[4] = v[7];
    prog[5] = v[8];
    m.kind = MoveKind::kArc;
  } else {
    for (std::size_t i = 0; i < 6; ++i) prog[i] = v[i];
    m.kind = name == "STRAIGHT_TRAVERSE" ? MoveKind::kRapid : MoveKind::kLinear;  // probes feed
  }
  int max_terms = 1;
  m.end = toMachine(st, prog);
  for (std::size_t i = 0; i < 6; ++i) max_terms = std::max(max_terms, terms[i]);
  std::array<double, 6> c6{};
  for (std::size_t i = 0; i < 3; ++i) c6[i] = std::isnan(centre[i]) ? 0.0 : centre[i];
  const std::array<double, 6> centre_machine = toMachine(st, c6);
  for (std::size_t i = 0; i < 3; ++i)
    if (!std::isnan(centre[i])) m.centre[i] = centre_machine[i];
  m.tol = kPrintHalfUnit * 25.4 * (max_terms + 1) + kTolSlack;
  if (st.scale == 1.0) m.tol = kPrintHalfUnit * (max_terms + 1) + kTolSlack;
  if (m.kind != MoveKind::kRapid) m.feed = st.feedRate();
  return m;
}

RefRun runRs274(const fs::path& program) {
  const fs::path var =
      fs::temp_directory_path() / ("pkm_rs274_" + program.stem().string() + ".var");
  std::ofstream(var).close();  // a fresh, empty parameter file every run (rs274 writes it back)
  int status = 0;
  const std::string out = runRs274Command(program, var, status);
  fs::remove(var);
  RefRun r;
  r.ok = status == 0;
  Rs274State state;
  static const std::regex kCall(R"(^\s*\d+ N\S*\s+(\w+)\((.*)\)\s*$)");
  std::istringstream in(out);
  std::string line, prev;
  while (std::getline(in, line)) {
    std::smatch match;
    if (!std::regex_match(line, match, kCall)) {
      if (!r.ok && !line.empty() && line != "executing") prev = line;  // offending block last
      continue;
    }
    const std::string name = match[1].str();
    const std::string args = match[2].str();
    if (name == "STRAIGHT_TRAVERSE" || name == "STRAIGHT_FEED" || name == "ARC_FEED" ||
        name == "STRAIGHT_PROBE") {
      r.moves.push_back(rs274Motion(state, name, numbers(args)));
    } else if (name == "RIGID_TAP") {
      // RIGID_TAP(x, y, z): in to the point and back out to where the tap started (G33.1).
      const RefMove before = r.moves.empty() ? RefMove{} : r.moves.back();
      std::vector<double> v = numbers(args);
      v.resize(3);
      RefMove tap_in = rs274Motion(state, "STRAIGHT_FEED", {v[0], v[1], v[2], 0, 0, 0});
      for (std::size_t i = 3; i < 6; ++i) tap_in.end[i] = before.end[i];
      RefMove tap_out = tap_in;
      tap_out.end = before.end;
      r.moves.push_back(tap_in);
      r.moves.push_back(tap_out);
    } else {
      applyRs274Setting(state, name, args);
    }
  }
  r.error_line = prev;
  static const std::regex kFromLine(R"(from line: (\d+))");
  std::smatch m;
  if (std::regex_search(out, m, kFromLine)) r.error_line_no = std::stoul(m[1].str());
  return r;
}

std::vector<fs::path> corpus() {
  std::vector<fs::path> files;
  for (const fs::path& dir : {kRoot / "examples/gcode", kRoot / "tests/cnc/corpus"}) {
    if (!fs::exists(dir)) continue;
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().extension() == ".ngc") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string trim(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t\r");
  const std::size_t b = s.find_last_not_of(" \t\r");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

TEST(Rs274Compare, CorpusHasEnoughPrograms) { EXPECT_GE(corpus().size(), 15u); }

TEST(Rs274Compare, EveryMotionMatchesLinuxcnc) {
  if (!rs274Available())
    GTEST_SKIP() << "LinuxCNC rs274 not found or not runnable under " << kLinuxcnc
                 << " (run scripts/fetch-linuxcnc.sh)";
  const ToolTable tools = ToolTable::load(kToolTable.string(), kMmPerInch);  // rs274: inch table
  std::size_t compared = 0;
  double worst = 0.0;
  for (const fs::path& file : corpus()) {
    SCOPED_TRACE(file.filename().string());
    const RefRun ref = runRs274(file);
    const bool expect_error = file.filename().string().rfind("err_", 0) == 0;
    InterpreterOptions options;
    options.tools = tools;
    options.require_program_end = true;  // as `pkm gcode moves` runs a file
    Interpreter interp(options);
    MoveCollector got;
    std::string error;
    std::size_t error_line_no = 0;
    std::string source_lines;
    try {
      interp.run(Program::load(file.string()), got);
    } catch (const IoError& e) {
      error = e.what();
      const std::string prefix = file.string() + ":";
      if (error.rfind(prefix, 0) == 0) error_line_no = std::stoul(error.substr(prefix.size()));
    }
    if (expect_error) {
      EXPECT_FALSE(ref.ok) << "rs274 accepted an err_ program";
      ASSERT_FALSE(error.empty()) << "pkm accepted an err_ program";
      std::ifstream in(file);
      std::string l;
      for (std::size_t k = 0; k < error_line_no && std::getline(in, l);) ++k;
      if (file.filename().string().rfind("err_any_", 0) == 0) continue;
      if (ref.error_line_no != 0) {
        EXPECT_EQ(error_line_no, ref.error_line_no) << error;
      } else {
        EXPECT_EQ(trim(l), trim(ref.error_line)) << error;
      }
      continue;
    }
    ASSERT_TRUE(ref.ok) << "rs274 rejected the program";
    ASSERT_TRUE(error.empty()) << error;
    EXPECT_EQ(got.moves.size(), ref.moves.size());
    for (std::size_t k = 0; k < std::min(ref.moves.size(), got.moves.size()); ++k) {
      const Move& g = got.moves[k];
      const RefMove& r = ref.moves[k];
      SCOPED_TRACE("motion " + std::to_string(k) + " (line " + std::to_string(g.line) + ")");
      ASSERT_EQ(g.kind, r.kind);  // stop at the first divergence
      for (std::size_t i = 0; i < 6; ++i) {
        EXPECT_NEAR(g.end[i], r.end[i], r.tol) << "axis " << i;
        worst = std::max(worst, std::abs(g.end[i] - r.end[i]));
      }
      if (r.kind == MoveKind::kArc) {
        EXPECT_EQ(g.turns, r.turns);
        for (std::size_t i = 0; i < 3; ++i) {
          EXPECT_EQ(std::isnan(g.centre[i]), std::isnan(r.centre[i])) << "centre axis " << i;
          if (!std::isnan(r.centre[i])) {
            EXPECT_NEAR(g.centre[i], r.centre[i], r.tol) << "centre axis " << i;
            worst = std::max(worst, std::abs(g.centre[i] - r.centre[i]));
          }
        }
      }
      if (r.kind != MoveKind::kRapid) {
        EXPECT_NEAR(g.feed, r.feed, 25.4 * kPrintHalfUnit);
      }
      ++compared;
    }
  }
  std::printf("[ rs274    ] %zu motions compared, worst |difference| %.3g mm\n", compared, worst);
  EXPECT_GT(compared, 200u);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::cnc
