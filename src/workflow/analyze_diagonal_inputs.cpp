// The readers of `pkm analyze diagonals` (analyze_diagonal_inputs.hpp): line files and body and
// step tables.
#include "analyze_diagonal_inputs.hpp"

#include <fmt/format.h>

#include <map>
#include <sstream>
#include <string>
#include <tuple>

namespace pkm::workflow::detail {

using metrology::BodyDiagonal;

std::optional<Eigen::Vector3d> metaVector(const io::TextTable& t, std::string_view key) {
  const auto v = t.meta(key);
  if (!v) return std::nullopt;
  std::string s = *v;
  for (char& c : s)
    if (c == '(' || c == ')' || c == ',') c = ' ';
  std::istringstream in(s);
  Eigen::Vector3d out;
  if (!(in >> out.x() >> out.y() >> out.z()))
    t.failHeader(fmt::format("metadata '{}' is not a 3-vector: '{}'", key, *v));
  return out;
}

bool isLineFile(const io::TextTable& t) {
  return !t.findColumn({"diagonal"}) && t.findColumn({"target_mm", "target"}) &&
         t.findColumn({"reading_mm"});
}

LineFile readLineFile(const io::TextTable& t) {
  LineFile f;
  const auto start = metaVector(t, "line start");
  const auto direction = metaVector(t, "line direction");
  if (!start || !direction)
    t.failHeader("a measurement file needs '# line start' and '# line direction' metadata");
  f.start = *start;
  f.direction = *direction;
  const std::size_t ct = t.column({"target_mm", "target"});
  const std::size_t cr = t.column({"reading_mm"});
  const auto crun = t.findColumn({"run"});
  const auto cdir = t.findColumn({"direction"});
  const auto csub = t.findColumn({"sub_step"});
  for (std::size_t r = 0; r < t.rows(); ++r) {
    f.target.push_back(t.number(r, ct));
    f.deviation.push_back(t.number(r, cr) - f.target.back());
    f.run.push_back(crun ? static_cast<int>(t.integer(r, *crun)) : 1);
    f.dir.push_back(cdir ? t.direction(r, *cdir) : 1);
    f.sub_step.push_back(csub ? static_cast<int>(t.integer(r, *csub)) : 0);
  }
  if (f.target.empty()) t.failHeader("no readings");
  return f;
}

std::optional<BodyDiagonal> diagonalAt(const Eigen::Vector3d& start, const Eigen::Vector3d& size) {
  for (BodyDiagonal d : metrology::kBodyDiagonals)
    if ((metrology::diagonalStart(d, size) - start).norm() < kCornerTolerance) return d;
  return std::nullopt;
}

BodyDiagonal diagonalField(const io::TextTable& t, std::size_t row, std::size_t col) {
  const auto d = metrology::parseBodyDiagonal(t.text(row, col));
  if (!d) t.fail(row, fmt::format("diagonal '{}' is not PPP, NPP, PNP or NNP", t.text(row, col)));
  return *d;
}

namespace {

/// The diagonal of a continuous or step measurement file that runs along a whole body diagonal.
BodyDiagonal identifyDiagonal(const io::TextTable& t,
                              const LineFile& f,
                              const Eigen::Vector3d& size) {
  const auto d = diagonalAt(f.start, size);
  if (!d ||
      (metrology::diagonalTravel(*d, size).normalized() - f.direction).norm() > kDirectionTolerance)
    t.failHeader(
        fmt::format("line start ({}, {}, {}) and direction are not a body diagonal "
                    "PPP/NPP/PNP/NNP of the box {} x {} x {}",
                    f.start.x(),
                    f.start.y(),
                    f.start.z(),
                    size.x(),
                    size.y(),
                    size.z()));
  return *d;
}

/// The rows of a `diagonal,position,deviation[,run,direction]` table; false when it has no runs.
bool readBodyTable(const io::TextTable& t, std::vector<metrology::BodyDiagonalSample>& samples) {
  const std::size_t cd = t.column({"diagonal"});
  const std::size_t cp = t.column({"position", "target", "target_mm"});
  const std::size_t cv = t.column({"deviation", "deviation_mm"});
  const auto crun = t.findColumn({"run"});
  const auto cdir = t.findColumn({"direction"});
  for (std::size_t r = 0; r < t.rows(); ++r) {
    metrology::BodyDiagonalSample s{diagonalField(t, r, cd),
                                    t.number(r, cp),
                                    t.number(r, cv),
                                    crun ? static_cast<int>(t.integer(r, *crun)) : 0,
                                    cdir ? t.direction(r, *cdir) : 1};
    if (crun && s.run < 1) t.fail(r, "run must be >= 1");
    samples.push_back(s);
  }
  return crun.has_value();
}

/// The rows of one step input, as columns.
struct StepRows {
  std::vector<BodyDiagonal> diag;
  std::vector<double> target, deviation;
  std::vector<int> run, dir, sub;
};

StepRows readStepRows(const io::TextTable& t, const Eigen::Vector3d& size) {
  StepRows s;
  if (isLineFile(t)) {
    const LineFile f = readLineFile(t);
    return {std::vector<BodyDiagonal>(f.target.size(), identifyDiagonal(t, f, size)),
            f.target,
            f.deviation,
            f.run,
            f.dir,
            f.sub_step};
  }
  const std::size_t cd = t.column({"diagonal"});
  const std::size_t cp = t.column({"position", "target", "target_mm"});
  const std::size_t cs = t.column({"sub_step"});
  const std::size_t cv = t.column({"deviation", "deviation_mm"});
  const auto crun = t.findColumn({"run"});
  const auto cdir = t.findColumn({"direction"});
  for (std::size_t r = 0; r < t.rows(); ++r) {
    s.diag.push_back(diagonalField(t, r, cd));
    s.target.push_back(t.number(r, cp));
    s.sub.push_back(static_cast<int>(t.integer(r, cs)));
    s.deviation.push_back(t.number(r, cv));
    s.run.push_back(crun ? static_cast<int>(t.integer(r, *crun)) : 1);
    s.dir.push_back(cdir ? t.direction(r, *cdir) : 1);
  }
  return s;
}

}  // namespace

std::vector<metrology::BodyDiagonalSample> readBodySamples(const std::vector<io::NamedText>& data,
                                                           const Eigen::Vector3d& size) {
  std::vector<metrology::BodyDiagonalSample> samples;
  bool runs_given = true;
  for (const io::NamedText& in : data) {
    const io::TextTable t = io::TextTable::parseData(in.text, in.name);
    if (isLineFile(t)) {
      const LineFile f = readLineFile(t);
      const BodyDiagonal d = identifyDiagonal(t, f, size);
      for (std::size_t i = 0; i < f.target.size(); ++i)
        samples.push_back({d, f.target[i], f.deviation[i], f.run[i], f.dir[i]});
      continue;
    }
    if (!readBodyTable(t, samples)) runs_given = false;
  }
  if (!runs_given) {  // each row one reading: number them per (diagonal, position, direction)
    std::map<std::tuple<int, double, int>, int> count;
    for (auto& s : samples)
      s.run = ++count[{static_cast<int>(s.diagonal), s.position, s.direction}];
  }
  return samples;
}

std::vector<metrology::StepDiagonalPass> readStepPasses(const std::vector<io::NamedText>& data,
                                                        const Eigen::Vector3d& size) {
  std::vector<metrology::StepDiagonalPass> passes;
  for (const io::NamedText& in : data) {
    const io::TextTable t = io::TextTable::parseData(in.text, in.name);
    const StepRows s = readStepRows(t, size);
    for (std::size_t r = 0; r < s.target.size(); ++r) {
      if (s.sub[r] < 1 || s.sub[r] > 3)
        t.fail(r, fmt::format("sub_step must be 1, 2 or 3 (X, Y, Z sub-moves), got {}", s.sub[r]));
      const bool new_pass = r == 0 || s.diag[r] != s.diag[r - 1] || s.run[r] != s.run[r - 1] ||
                            s.dir[r] != s.dir[r - 1];
      if (new_pass) passes.push_back({s.diag[r], {}});
      auto& steps = passes.back().steps;
      if (s.sub[r] == 1) steps.emplace_back();
      if (steps.empty() || (s.sub[r] > 1 && s.sub[r - 1] != s.sub[r] - 1))
        t.fail(r, "sub-steps of a step must come in the order 1, 2, 3");
      steps.back().deviation[static_cast<std::size_t>(s.sub[r] - 1)] = s.deviation[r];
      steps.back().target = s.target[r];
    }
  }
  return passes;
}

}  // namespace pkm::workflow::detail
