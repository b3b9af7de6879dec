// POST /api/gcode/run, POST /api/gcode/compensate and POST /api/gcode/shape (docs/web.md):
// workflow::runGcode and workflow::compensateGcode on a program sent as text; cnc::shapeLines for
// the page's composite blocks.
#include <fmt/format.h>

#include "api_machining.hpp"
#include "api_state.hpp"
#include "pkm/cnc/shapes.hpp"
#include "pkm/io/gcode_run_report.hpp"
#include "pkm/workflow/gcode_compensate.hpp"
#include "pkm/workflow/gcode_run.hpp"

namespace pkm::server::detail {
namespace {

/// Default and largest number of path points a run returns.
constexpr std::size_t kDefaultPathPoints = 20'000;
constexpr std::size_t kMaxPathPoints = 1'000'000;
/// Default and largest number of violations listed per check.
constexpr std::size_t kDefaultViolations = 10'000;
constexpr std::size_t kMaxViolations = 1'000'000;
/// Largest number of animation frames (machine drawings) a run returns.
constexpr std::size_t kMaxFrames = 10'000;

io::NamedText program(const Json& body) {
  return {safeName(stringField(body, "name", "program.ngc")), requiredString(body, "program")};
}

/// The tool table a request sends as text ("tool_table", "tool_units").
workflow::GcodeInterpreterSettings interpreter(const Json& body) {
  workflow::GcodeInterpreterSettings settings;
  settings.search_working_folder = false;  // the server's folder is not the user's
  settings.tool_table_text = stringField(body, "tool_table", "");
  settings.tool_units = stringField(body, "tool_units", "mm");
  return settings;
}

/// The fields a run and a compensation share: the program, the machine (and its INI), the
/// tolerance and the tool table.
template <class GcodeRequest>
void readCommon(Api::State& s, const Json& body, GcodeRequest& q) {
  q.program = program(body);
  const MachineSpec m = s.resolveMachine(requiredString(body, "machine"));
  q.machine = m.spec;
  q.ini = m.ini;
  q.tolerance = numberField(body, "tolerance");
  q.interpreter = interpreter(body);
}

Json pathJson(const workflow::GcodeRunPath& p) {
  Json pose = Json::array(), q = Json::array();
  for (const auto& x : p.pose) pose.push_back(x);
  for (const auto& x : p.q) q.push_back(x);
  return {{"joints", p.joints},
          {"joint_units", p.joint_units},
          {"total_points", p.total_points},
          {"index", p.index},
          {"t", p.t},
          {"line", p.line},
          {"pose", pose},
          {"q", q}};
}

Json violationsJson(const std::vector<workflow::GcodeRunViolation>& v) {
  Json a = Json::array();
  for (const workflow::GcodeRunViolation& x : v)
    a.push_back({{"check", x.check},
                 {"line", x.event.line},
                 {"position", x.event.position},
                 {"item", x.event.item},
                 {"value", finiteOrNull(x.event.value)},
                 {"limit", finiteOrNull(x.event.limit)},
                 {"margin", finiteOrNull(x.event.margin)},
                 {"unit", x.event.unit}});
  return a;
}

}  // namespace

Response runGcode(Api::State& s, const Request& r) {
  const Json body = parseObject(r);
  workflow::GcodeRunRequest q;
  readCommon(s, body, q);
  q.strut_diameter = numberField(body, "strut_diameter");
  q.orientation = stringField(body, "orientation", "vector");
  q.path_points = countField(body, "max_points", kMaxPathPoints).value_or(kDefaultPathPoints);
  q.max_violations =
      countField(body, "max_violations", kMaxViolations).value_or(kDefaultViolations);
  q.frames = countField(body, "frames", kMaxFrames).value_or(0);
  q.max_points = s.options.max_run_points;  // a runaway loop is refused long before GBs
  q.machining = machiningRequest(body);
  const NamedJob job(s, stringField(body, "job", ""));
  const JobSlot slot(s, job.name(), &job.token());
  const workflow::GcodeRunResult result = workflow::runGcode(q, job.control());
  Json j = Json::parse(io::gcodeRunJson(result.report));
  j["path"] = pathJson(result.path);
  j["violations"] = violationsJson(result.violations);
  Json rows = Json::array();
  for (const workflow::PoseCheckRow& row : result.frames) rows.push_back(poseRowJson(row));
  j["frames"] = {{"t", result.frame_t}, {"index", result.frame_index}, {"rows", rows}};
  if (result.machining) j["machining"] = machiningJson(*result.machining);
  return json(j);
}

Response compensateGcode(Api::State& s, const Request& r) {
  const Json body = parseObject(r);
  workflow::GcodeCompensateRequest q;
  readCommon(s, body, q);
  const std::string nominal = stringField(body, "nominal", "");
  if (!nominal.empty()) q.nominal = s.resolveMachine(nominal).spec;
  if (body.contains("orientation")) q.orientation = stringField(body, "orientation", "vector");
  const JobSlot slot(s);
  const workflow::GcodeCompensateResult result = workflow::compensateGcode(q);
  const cnc::ProgramCompensation& c = result.compensation;
  return json({{"text", c.text},
               {"note", s.clean(result.note)},
               {"motion_lines", c.motion_lines},
               {"added_lines", c.added_lines},
               {"offset_lines", c.offset_lines},
               {"max_correction_mm", c.max_correction}});
}

Response makeShape(const Request& r) {
  const Json body = parseObject(r);
  cnc::ShapeSpec spec{requiredString(body, "shape"), {}};
  if (body.contains("values")) {
    const Json& v = body["values"];
    if (!v.is_object()) throw HttpError(400, "\"values\" must be an object of numbers");
    for (const auto& [name, value] : v.items()) {
      if (!value.is_number())
        throw HttpError(400, fmt::format("\"values.{}\" must be a number", name));
      spec.values[name] = value.get<double>();
    }
  }
  return json({{"shape", spec.kind}, {"lines", cnc::shapeLines(spec)}});
}

}  // namespace pkm::server::detail
