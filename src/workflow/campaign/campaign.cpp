// The campaign runner (workflow/campaign.hpp): loads and checks a pkm.campaign/1 file, runs each
// step kind (campaign_steps.hpp), then writes summary.json, report-data.json, report.html and the
// result store.
#include "pkm/workflow/campaign.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <map>
#include <regex>
#include <tuple>

#include "campaign_steps.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/io/html_report.hpp"

namespace pkm::io::detail {
/// The built-in campaigns, data/campaigns/*.json (cmake/PkmEmbed.cmake).
const std::vector<std::pair<std::string_view, std::string_view>>& embeddedCampaigns();
}  // namespace pkm::io::detail

namespace pkm::workflow {
namespace {

namespace fs = std::filesystem;
using campaign::Json;
using Clock = std::chrono::steady_clock;

const std::map<std::string, campaign::StepRunner>& stepKinds() {
  static const std::map<std::string, campaign::StepRunner> kinds = {
      {"hybrid-squareness", &campaign::runHybridSquarenessStep},
      {"cartesian-diagonals", &campaign::runCartesianDiagonalsStep},
      {"probe-offset", &campaign::runProbeOffsetStep},
      {"hexapod-calibration", &campaign::runHexapodCalibrationStep},
  };
  return kinds;
}

/// The campaign text and its source name ("FILE" or "builtin:NAME").
std::pair<std::string, std::string> loadText(const std::string& spec) {
  std::error_code ec;
  if (fs::is_regular_file(spec, ec)) return {io::readFileText(spec), spec};
  for (const auto& [stem, text] : io::detail::embeddedCampaigns())
    if (stem == spec) return {std::string(text), "builtin:" + spec};
  throw IoError(fmt::format("{}: no such file, and not a built-in campaign (built-in: {})",
                            spec,
                            fmt::join(builtinCampaignNames(), ", ")));
}

/// The string at `key` of object `j` ("" when absent); throws pkm::IoError "WHERE: \"KEY\" must
/// be a string" for another type.
std::string stringKey(const Json& j, const char* key, const std::string& where) {
  if (!j.contains(key)) return {};
  if (!j[key].is_string()) throw IoError(fmt::format("{}: \"{}\" must be a string", where, key));
  return j[key].get<std::string>();
}

/// Checks one step's id (unique, lower case) and kind.
void checkStep(const Json& s, const std::string& where, std::map<std::string, int>& ids) {
  static const std::regex id_re("[a-z0-9][a-z0-9-]*");
  if (!s.is_object()) throw IoError(where + ": a step must be an object");
  const std::string id = stringKey(s, "id", where);
  if (!std::regex_match(id, id_re))
    throw IoError(where + ": \"id\" must be lower-case letters, digits and '-'");
  if (ids[id]++) throw IoError(fmt::format("{}: id '{}' is used twice", where, id));
  const std::string kind = stringKey(s, "kind", where);
  if (!stepKinds().count(kind)) {
    std::vector<std::string> known;
    for (const auto& [name, run] : stepKinds()) known.push_back(name);
    throw IoError(
        fmt::format("{}: unknown \"kind\" '{}' (known: {})", where, kind, fmt::join(known, ", ")));
  }
}

Json parseCampaign(const std::string& text, const std::string& source) {
  Json j;
  try {
    j = Json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // nlohmann reports a byte offset; turn it into a line number.
    const std::size_t at = std::min<std::size_t>(e.byte, text.size());
    const long line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(at), '\n');
    throw IoError(fmt::format("{}:{}: invalid JSON ({})", source, line, e.what()));
  } catch (const nlohmann::json::out_of_range& e) {
    // A number beyond a double's range ("1e999"): nlohmann gives no position.
    throw IoError(fmt::format("{}: invalid JSON ({})", source, e.what()));
  }
  if (!j.is_object() || !j.contains("schema") || j["schema"] != "pkm.campaign/1")
    throw IoError(
        fmt::format("{}: not a campaign (\"schema\": \"pkm.campaign/1\" expected)", source));
  // Read with defaults later (json::value), so a wrong type must be refused here.
  (void)stringKey(j, "name", source);
  (void)stringKey(j, "description", source);
  if (!j.contains("steps") || !j["steps"].is_array() || j["steps"].empty())
    throw IoError(fmt::format("{}: \"steps\" must be a non-empty array", source));
  std::map<std::string, int> ids;
  for (std::size_t k = 0; k < j["steps"].size(); ++k)
    checkStep(j["steps"][k], fmt::format("{}: steps[{}]", source, k), ids);
  return j;
}

/// Runs step `k` of `n`.
campaign::StepOutcome runStep(const Json& step,
                              std::size_t k,
                              std::size_t n,
                              const std::string& source,
                              const CampaignOptions& o,
                              const fs::path& base_dir,
                              const RunControl& control,
                              Clock::time_point t0) {
  const std::string id = step["id"].get<std::string>();
  campaign::StepContext ctx;
  ctx.spec = step;
  ctx.source = fmt::format("{}: steps[{}] ({})", source, k, id);
  ctx.out = o.out;
  ctx.dir = o.out / id;
  ctx.base_dir = base_dir;
  ctx.environment = o.environment;
  ctx.seed = o.seed;
  ctx.sources = o.uncertainty.value_or(metrology::UncertaintySources{});
  const auto ts = Clock::now();
  ctx.progress = [&, k, id](const std::string& what) {
    control.checkCancelled();
    control.report({id, k + 1, n, std::chrono::duration<double>(Clock::now() - t0).count(), what});
  };
  campaign::StepOutcome outcome;
  try {
    outcome = stepKinds().at(step["kind"].get<std::string>())(ctx);
  } catch (const nlohmann::json::exception& e) {
    // A step's keys are read by its runner; one of the wrong type is the campaign file's error.
    throw IoError(fmt::format("{}: {}", ctx.source, e.what()));
  }
  outcome.id = id;
  // Every summary row goes into the result store (before and after, where measured, with U).
  for (const campaign::SummaryRow& r : outcome.rows)
    for (const auto& [stage, value, u] :
         {std::tuple{"before", r.before, r.before_U}, std::tuple{"after", r.after, r.after_U}})
      if (std::isfinite(value))
        outcome.record.results.push_back(
            {r.quantity, stage, value, r.unit, std::isfinite(u) ? u : std::nan("")});
  ctx.progress(
      fmt::format("done in {:.2f} s", std::chrono::duration<double>(Clock::now() - ts).count()));
  return outcome;
}

/// summary.json's rows.
Json summaryRows(const std::vector<campaign::StepOutcome>& steps) {
  Json rows = Json::array();
  for (const campaign::StepOutcome& s : steps)
    for (const campaign::SummaryRow& r : s.rows)
      rows.push_back({{"step", s.id},
                      {"quantity", r.quantity},
                      {"unit", r.unit},
                      {"before", campaign::cell(r.before, 6)},
                      {"after", campaign::cell(r.after, 6)},
                      {"target", r.target ? Json(*r.target) : Json(nullptr)},
                      {"paper", r.paper},
                      {"noise", r.noise},
                      {"pass", r.pass()},
                      {"before_U", campaign::cell(r.before_U, 2)},
                      {"after_U", campaign::cell(r.after_U, 2)},
                      {"significant", campaign::significantJson(r)}});
  return rows;
}

/// The campaign-level settings given (environment, uncertainty sources, seed) as report header
/// notes; empty when none was given.
std::vector<std::string> settingNotes(const CampaignResult& r) {
  std::vector<std::string> notes;
  if (!r.environment_source.empty())
    notes.push_back(fmt::format(
        "Environment of every simulated step: {} ({})", r.environment_source, r.environment_name));
  if (!r.uncertainty_source.empty())
    notes.push_back(fmt::format("Instruments and environment of the uncertainty budgets: {}",
                                r.uncertainty_source));
  if (r.seed) notes.push_back(fmt::format("Seed of every simulated step: {}", *r.seed));
  return notes;
}

/// report-data.json (pkm.report/1): the summary table, then each step's section.
Json reportData(const CampaignResult& result,
                const Json& spec,
                const std::vector<campaign::StepOutcome>& outcomes) {
  Json report{{"schema", "pkm.report/1"},
              {"title", fmt::format("pkm campaign '{}'", result.name)},
              {"subtitle", spec.value("description", std::string())}};
  if (const std::vector<std::string> notes = settingNotes(result); !notes.empty())
    report["notes"] = notes;
  Json summary = campaign::table("Before and after compensation, beside the papers' results",
                                 {"step",
                                  "quantity",
                                  "unit",
                                  "before",
                                  "after",
                                  "target",
                                  "paper (before -> after)",
                                  "instrument noise",
                                  "result"});
  for (const campaign::StepOutcome& s : outcomes)
    for (const campaign::SummaryRow& r : s.rows)
      summary["rows"].push_back({s.id,
                                 r.quantity,
                                 r.unit,
                                 campaign::cell(r.before),
                                 campaign::cell(r.after),
                                 r.target ? Json(fmt::format("<= {:g}", *r.target)) : Json(nullptr),
                                 r.paper.empty() ? Json(nullptr) : Json(r.paper),
                                 r.noise,
                                 r.target ? Json(r.pass() ? "PASS" : "FAIL") : Json(nullptr)});
  report["summary"] = summary;
  report["sections"] = Json::array();
  for (const campaign::StepOutcome& s : outcomes) report["sections"].push_back(s.section);
  report["sections"].push_back(campaign::uncertaintySection(outcomes, result.uncertainty_source));
  return report;
}

/// summary.json, report-data.json, report.html; returns summary.json's text. The campaign-level
/// settings appear only when given, so a campaign run without them writes what it always wrote.
std::string writeCampaignFiles(const fs::path& out,
                               const CampaignResult& result,
                               const Json& spec,
                               const std::vector<campaign::StepOutcome>& outcomes) {
  const std::string report_text = reportData(result, spec, outcomes).dump(1) + "\n";
  io::writeFileAtomic(out / "report-data.json", report_text, io::Overwrite::kAllow);
  io::writeFileAtomic(out / "report.html",
                      io::renderHtmlReport(report_text, (out / "report-data.json").string()),
                      io::Overwrite::kAllow);
  Json sj{
      {"schema", "pkm.campaign-summary/1"}, {"campaign", result.name}, {"source", result.source}};
  if (!result.environment_source.empty())
    sj["environment"] = {{"source", result.environment_source}, {"name", result.environment_name}};
  if (!result.uncertainty_source.empty())
    sj["uncertainty"] = {{"source", result.uncertainty_source}};
  if (result.seed) sj["seed"] = *result.seed;
  sj["rows"] = summaryRows(outcomes);
  sj["steps"] = Json::array();
  for (const campaign::StepOutcome& s : outcomes)
    sj["steps"].push_back({{"id", s.id}, {"title", s.title}, {"files", s.files}});
  std::string summary = sj.dump(2) + "\n";
  io::writeFileAtomic(out / "summary.json", summary, io::Overwrite::kAllow);
  return summary;
}

/// Adds every step to the result store `db`.
void storeResults(const std::string& db,
                  const fs::path& out,
                  const std::string& name,
                  std::vector<campaign::StepOutcome>& outcomes) {
  store::ResultStore results(db);
  for (campaign::StepOutcome& s : outcomes) {
    s.record.name = fmt::format("campaign {} / {}", name, s.id);
    for (const std::string& f : s.files) {
      if (f.find("/measured-before/") == std::string::npos) continue;
      s.record.measurements.push_back(
          {fs::path(f).stem().string(), "measurement", (out / f).string(), 0});
    }
    results.store(s.record);
  }
}

}  // namespace

bool CampaignRow::pass() const {
  return !target || (std::isfinite(after) && std::abs(after) <= *target);
}

void CampaignOptions::validate() const {
  if (out.empty()) throw IoError("give --out DIR");
  std::string why;
  if (environment && !environment->isValid(&why))
    throw InvalidArgument(fmt::format("campaign environment {}: {}", environment_source, why));
  if (uncertainty && !uncertainty->isValid(&why))
    throw InvalidArgument(
        fmt::format("campaign uncertainty sources {}: {}", uncertainty_source, why));
}

std::vector<std::string> builtinCampaignNames() {
  std::vector<std::string> names;
  for (const auto& [stem, text] : io::detail::embeddedCampaigns()) names.emplace_back(stem);
  std::sort(names.begin(), names.end());
  return names;
}

CampaignInfo describeCampaign(const std::string& spec) {
  const auto [text, source] = loadText(spec);
  const Json j = parseCampaign(text, source);
  return {j.value("name", std::string("campaign")),
          j["steps"].size(),
          j.value("description", std::string())};
}

CampaignResult runCampaign(const CampaignOptions& options, const RunControl& control) {
  options.validate();
  const bool given = !options.campaign_text.empty();
  const auto [text, source] =
      given ? std::pair{options.campaign_text, options.campaign} : loadText(options.campaign);
  const Json spec = parseCampaign(text, source);
  io::prepareOutputDirectory(options.out, options.force);
  const fs::path base_dir = given || source.rfind("builtin:", 0) == 0
                                ? fs::current_path()
                                : fs::path(source).parent_path();
  CampaignResult result;
  result.name = spec.value("name", std::string("campaign"));
  result.source = source;
  result.description = spec.value("description", std::string());
  if (options.environment) {
    result.environment_source =
        options.environment_source.empty() ? options.environment->name : options.environment_source;
    result.environment_name = options.environment->name;
  }
  if (options.uncertainty)
    result.uncertainty_source =
        options.uncertainty_source.empty() ? "given" : options.uncertainty_source;
  result.seed = options.seed;
  const std::size_t n = spec["steps"].size();
  const auto t0 = Clock::now();
  control.report({"", 0, n, 0.0, result.name});
  std::vector<campaign::StepOutcome> outcomes;
  for (std::size_t k = 0; k < n; ++k) {
    outcomes.push_back(runStep(spec["steps"][k], k, n, source, options, base_dir, control, t0));
    const campaign::StepOutcome& s = outcomes.back();
    if (options.on_step) options.on_step({s.id, s.title, s.rows, s.files});
  }
  control.checkCancelled();
  result.summary_json = writeCampaignFiles(options.out, result, spec, outcomes);
  if (!options.db.empty()) storeResults(options.db, options.out, result.name, outcomes);
  for (const campaign::StepOutcome& s : outcomes) {
    result.steps.push_back({s.id, s.title, s.rows, s.files});
    for (const campaign::SummaryRow& r : s.rows) {
      result.all_pass = result.all_pass && r.pass();
      if (r.target) ++result.targets;
    }
  }
  result.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  result.report = (fs::absolute(options.out) / "report.html").lexically_normal();
  return result;
}

}  // namespace pkm::workflow
