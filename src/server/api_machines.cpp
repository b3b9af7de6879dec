// GET /api/machines, GET /api/machines/NAME and POST /api/machines (docs/web.md).
#include <fmt/format.h>

#include <fstream>

#include "api_state.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/exechon_machine.hpp"
#include "pkm/io/linuxcnc_samples.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/workflow/pose_checks.hpp"

namespace pkm::server::detail {
namespace {

Json numbers(const std::vector<double>& v) {
  Json a = Json::array();
  for (double x : v) a.push_back(finiteOrNull(x));
  return a;
}

Json points(const std::vector<workflow::WorldPoint>& v) {
  Json a = Json::array();
  for (const auto& p : v) a.push_back({p[0], p[1], p[2]});
  return a;
}

/// The machine's type, unit and document (`describe --json`), and any reader notices.
struct Loaded {
  std::string type, units, name;
  Json document;
  std::vector<std::string> notices;
};

Loaded load(const MachineSpec& m) {
  Loaded l;
  l.type = io::machineTypeOf(m.spec);
  if (l.type == "exechon") {
    const io::ExechonMachine e = io::loadExechonMachine(m.spec);
    l.units = std::string(toString(e.model.unit));
    l.name = e.model.name;
    l.document = Json::parse(io::writeExechonJson(e));
    l.notices = e.notices;
    return l;
  }
  io::HalReadOptions hal;
  if (!m.ini.empty()) hal.ini_path = m.ini;
  const io::HexapodMachine h = io::loadHexapodMachine(m.spec, hal);
  l.units = std::string(toString(h.model.unit));
  l.name = h.model.name;
  l.document = Json::parse(io::writeHexapodJson(h));
  l.notices = h.notices;
  return l;
}

void writeFile(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw IoError(fmt::format("{}: cannot write", path.string()));
}

}  // namespace

Json poseRowJson(const workflow::PoseCheckRow& row) {
  Json j{{"status", row.status},
         {"joints", numbers(row.joints)},
         {"stroke_margin", numbers(row.stroke_margin)},
         {"angle_margin", numbers(row.angle_margin)},
         {"clearance", finiteOrNull(row.clearance)},
         {"closest_pair", {row.closest_pair[0], row.closest_pair[1]}},
         {"condition_number", finiteOrNull(row.condition_number)},
         {"condition_margin", finiteOrNull(row.condition_margin)},
         {"violations", row.violations},
         {"base_points", points(row.base_points)},
         {"moving_points", points(row.moving_points)},
         {"tool_point", {row.tool_point[0], row.tool_point[1], row.tool_point[2]}},
         {"tool_direction", {row.tool_direction[0], row.tool_direction[1], row.tool_direction[2]}},
         {"wrist_points", points(row.wrist_points)},
         {"carriage", row.carriage}};
  return j;
}

Response listMachines(Api::State& s) {
  Json list = Json::array();
  for (const char* type : {"hexapod", "exechon"})
    for (const std::string& name : io::builtinMachineNames(type))
      list.push_back(
          {{"name", name}, {"type", type}, {"units", load({name, ""}).units}, {"uploaded", false}});
  // LinuxCNC's own samples, where LinuxCNC is installed (a sample that does not load is left out).
  for (const io::LinuxcncSample& sample : io::installedLinuxcncSamples(s.options.sample_root)) {
    try {
      list.push_back({{"name", sample.name},
                      {"type", "hexapod"},
                      {"units", load({sample.hal.string(), sample.ini.string()}).units},
                      {"uploaded", false},
                      {"sample", sample.description}});
    } catch (const std::exception&) {
    }
  }
  std::vector<Upload> uploads;
  {
    const std::lock_guard lock(s.mutex);
    uploads = s.uploads;
  }
  for (const Upload& u : uploads)
    list.push_back({{"name", u.name},
                    {"type", u.type},
                    {"units", load({u.path.string(), u.ini.string()}).units},
                    {"uploaded", true}});
  std::shared_ptr<const live::LiveMachine> followed;
  {
    const std::lock_guard lock(s.live_mutex);
    followed = s.live_machine;
  }
  if (followed)
    list.push_back({{"name", kLiveMachine},
                    {"type", "hexapod"},
                    {"units", followed->units()},
                    {"uploaded", false},
                    {"live", true}});
  return json(list);
}

Response getMachine(Api::State& s, const std::string& name) {
  const MachineSpec m = s.resolveMachine(name);
  const Loaded l = load(m);
  workflow::PoseCheckRequest q;
  q.machine = m.spec;
  q.ini = m.ini;
  q.poses = {workflow::homePose(m.spec, m.ini)};
  const workflow::PoseCheckResult home = workflow::checkPoses(q);
  return json({{"name", name},
               {"type", l.type},
               {"units", l.units},
               {"joints", home.joint_names},
               {"home", q.poses[0]},
               {"machine", l.document},
               {"drawing", poseRowJson(home.rows[0])}});
}

Response uploadMachine(Api::State& s, const Request& r) {
  const Json body = parseObject(r);
  const std::string filename = safeName(requiredString(body, "filename"));
  const std::string text = requiredString(body, "text");
  const std::string ini_text = stringField(body, "ini", "");
  const bool hal = filename.ends_with(".hal");
  if (!hal && !filename.ends_with(".json"))
    throw HttpError(400,
                    fmt::format("\"filename\" '{}' must end in .json (a pkm machine file) or "
                                ".hal (a LinuxCNC configuration)",
                                filename));
  if (!ini_text.empty() && !hal) throw HttpError(400, "\"ini\" goes with a .hal machine only");
  int n = 0;
  {
    const std::lock_guard lock(s.mutex);
    n = s.next_upload++;
  }
  // Each upload in its own folder: a .hal file finds no INI but its own.
  const std::filesystem::path folder = s.dir / fmt::format("upload-{}", n);
  std::filesystem::create_directories(folder);
  Upload u;
  u.path = folder / filename;
  writeFile(u.path, text);
  if (!ini_text.empty()) {
    u.ini = folder / (filename.substr(0, filename.size() - 4) + ".ini");
    writeFile(u.ini, ini_text);
  }
  Loaded l;
  try {
    l = load({u.path.string(), u.ini.string()});
  } catch (const std::exception& e) {
    // The errors name the upload as the client did: its file name, without the server's folder.
    std::error_code ec;
    std::filesystem::remove_all(folder, ec);
    std::string message = e.what();
    const std::string prefix = folder.string() + "/";
    for (std::size_t at = message.find(prefix); at != std::string::npos; at = message.find(prefix))
      message.erase(at, prefix.size());
    if (dynamic_cast<const InvalidArgument*>(&e) != nullptr) throw InvalidArgument(message);
    throw IoError(message);
  }
  u.type = l.type;
  u.name = fmt::format("upload-{}-{}", n, filename.substr(0, filename.find_last_of('.')));
  {
    const std::lock_guard lock(s.mutex);
    s.uploads.push_back(u);
    if (s.uploads.size() > s.options.max_uploads) {
      std::error_code ec;
      std::filesystem::remove_all(s.uploads.front().path.parent_path(), ec);
      s.uploads.erase(s.uploads.begin());
    }
  }
  Json notices = Json::array();
  for (std::string note : l.notices) {
    // The reader's advice is the command line's; the page attaches the INI with the .hal.
    if (const std::size_t at = note.find("pass --ini"); at != std::string::npos && hal)
      note.replace(at, 10, "choose the .hal together with its .ini");
    notices.push_back(s.clean(note));
  }
  return json({{"name", u.name},
               {"type", u.type},
               {"units", l.units},
               {"machine", l.name},
               {"notices", notices}});
}

}  // namespace pkm::server::detail
