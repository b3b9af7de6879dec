// `pkm campaign run CAMPAIGN --out DIR [--db FILE | --no-db] [--force]` and `pkm campaign list`:
// the end-to-end campaign (docs/campaign.md): every step measures, analyses, calibrates,
// compensates and re-measures on the virtual machine; then a summary table, summary.json,
// report-data.json, the self-contained report.html and the result store.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "campaign.hpp"
#include "cli_common.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/html_report.hpp"

namespace pkm::io::detail {
const std::vector<std::pair<std::string_view, std::string_view>>& embeddedCampaigns();
}  // namespace pkm::io::detail

namespace pkm::cli {
namespace {

namespace fs = std::filesystem;
using campaign::Json;
using Clock = std::chrono::steady_clock;

struct RunArgs {
  std::string campaign = "default";
  std::string out;
  std::string db = "pkm.db";
  bool no_db = false;
  bool force = false;
};

const std::map<std::string, campaign::StepRunner>& stepKinds() {
  static const std::map<std::string, campaign::StepRunner> kinds = {
      {"hybrid-squareness", &campaign::runHybridSquarenessStep},
      {"cartesian-diagonals", &campaign::runCartesianDiagonalsStep},
      {"probe-offset", &campaign::runProbeOffsetStep},
      {"hexapod-calibration", &campaign::runHexapodCalibrationStep},
  };
  return kinds;
}

std::vector<std::string> builtinNames() {
  std::vector<std::string> names;
  for (const auto& [stem, text] : io::detail::embeddedCampaigns()) names.emplace_back(stem);
  std::sort(names.begin(), names.end());
  return names;
}

/// The campaign text and its source name ("FILE" or "builtin:NAME").
std::pair<std::string, std::string> loadText(const std::string& spec) {
  std::error_code ec;
  if (fs::is_regular_file(spec, ec)) {
    std::ifstream in(spec, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    if (!in) throw IoError(fmt::format("{}: cannot read the file", spec));
    return {text.str(), spec};
  }
  for (const auto& [stem, text] : io::detail::embeddedCampaigns())
    if (stem == spec) return {std::string(text), "builtin:" + spec};
  throw IoError(fmt::format("{}: no such file, and not a built-in campaign (built-in: {})",
                            spec,
                            fmt::join(builtinNames(), ", ")));
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
  }
  if (!j.is_object() || j.value("schema", std::string()) != "pkm.campaign/1")
    throw IoError(
        fmt::format("{}: not a campaign (\"schema\": \"pkm.campaign/1\" expected)", source));
  if (!j.contains("steps") || !j["steps"].is_array() || j["steps"].empty())
    throw IoError(fmt::format("{}: \"steps\" must be a non-empty array", source));
  static const std::regex id_re("[a-z0-9][a-z0-9-]*");
  std::map<std::string, int> ids;
  for (std::size_t k = 0; k < j["steps"].size(); ++k) {
    const Json& s = j["steps"][k];
    const std::string where = fmt::format("{}: steps[{}]", source, k);
    if (!s.is_object()) throw IoError(where + ": a step must be an object");
    const std::string id = s.value("id", std::string());
    if (!std::regex_match(id, id_re))
      throw IoError(where + ": \"id\" must be lower-case letters, digits and '-'");
    if (ids[id]++) throw IoError(fmt::format("{}: id '{}' is used twice", where, id));
    const std::string kind = s.value("kind", std::string());
    if (!stepKinds().count(kind)) {
      std::vector<std::string> known;
      for (const auto& [name, run] : stepKinds()) known.push_back(name);
      throw IoError(fmt::format(
          "{}: unknown \"kind\" '{}' (known: {})", where, kind, fmt::join(known, ", ")));
    }
  }
  return j;
}

std::string numText(double v) {
  if (!std::isfinite(v)) return "-";
  return fmt::format("{:.4g}", v);
}

std::string targetText(const campaign::SummaryRow& r) {
  return r.target ? fmt::format("<= {:g}", *r.target) : "";
}

Json summaryJson(const std::vector<campaign::StepOutcome>& steps) {
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
                      {"pass", r.pass()}});
  return rows;
}

void runCampaign(const RunArgs& a) {
  if (a.out.empty()) throw IoError("give --out DIR");
  const auto [text, source] = loadText(a.campaign);
  const Json spec = parseCampaign(text, source);
  const fs::path out(a.out);
  std::error_code ec;
  if (fs::exists(out, ec) && !fs::is_directory(out, ec))
    throw IoError(fmt::format("{}: exists and is not a directory", a.out));
  if (!a.force && fs::exists(out, ec) && !fs::is_empty(out, ec))
    throw IoError(
        fmt::format("{}: exists and is not empty; refusing to overwrite (use --force)", a.out));
  fs::create_directories(out, ec);
  if (!fs::is_directory(out, ec))
    throw IoError(fmt::format("{}: cannot create the directory", a.out));

  const fs::path base_dir =
      source.rfind("builtin:", 0) == 0 ? fs::current_path() : fs::path(source).parent_path();
  const std::string name = spec.value("name", std::string("campaign"));
  fmt::print("pkm campaign '{}': {} steps -> {}\n", name, spec["steps"].size(), a.out);
  std::fflush(stdout);
  const auto t0 = Clock::now();
  std::vector<campaign::StepOutcome> outcomes;
  const std::size_t n = spec["steps"].size();
  for (std::size_t k = 0; k < n; ++k) {
    const Json& step = spec["steps"][k];
    const std::string id = step["id"].get<std::string>();
    campaign::StepContext ctx;
    ctx.spec = step;
    ctx.source = fmt::format("{}: steps[{}] ({})", source, k, id);
    ctx.out = out;
    ctx.dir = out / id;
    ctx.base_dir = base_dir;
    const auto ts = Clock::now();
    ctx.progress = [&, k, id](const std::string& what) {
      fmt::print("  [{}/{} {} {:5.1f} s] {}\n",
                 k + 1,
                 n,
                 id,
                 std::chrono::duration<double>(Clock::now() - t0).count(),
                 what);
      std::fflush(stdout);
    };
    campaign::StepOutcome o = stepKinds().at(step["kind"].get<std::string>())(ctx);
    o.id = id;
    // Every summary row goes into the result store (before and after, where measured).
    for (const campaign::SummaryRow& r : o.rows)
      for (const auto& [stage, value] :
           {std::pair{"before", r.before}, std::pair{"after", r.after}})
        if (std::isfinite(value)) o.record.results.push_back({r.quantity, stage, value, r.unit});
    ctx.progress(
        fmt::format("done in {:.2f} s", std::chrono::duration<double>(Clock::now() - ts).count()));
    outcomes.push_back(std::move(o));
  }

  // Summary table.
  std::string table = fmt::format("\n{:<10} {:<52} {:>10} {:>10} {:>9} {:<6} {}\n",
                                  "step",
                                  "quantity",
                                  "before",
                                  "after",
                                  "target",
                                  "unit",
                                  "result");
  bool all_pass = true;
  int targets = 0;
  for (const campaign::StepOutcome& s : outcomes)
    for (const campaign::SummaryRow& r : s.rows) {
      all_pass = all_pass && r.pass();
      if (r.target) ++targets;
      table += fmt::format("{:<10} {:<52} {:>10} {:>10} {:>9} {:<6} {}\n",
                           s.id,
                           r.quantity,
                           numText(r.before),
                           numText(r.after),
                           targetText(r),
                           r.unit,
                           r.target ? (r.pass() ? "PASS" : "FAIL") : "");
    }
  fmt::print("{}", table);

  // Report data, report and summary.
  Json report{{"schema", "pkm.report/1"},
              {"title", fmt::format("pkm campaign '{}'", name)},
              {"subtitle", spec.value("description", std::string())}};
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
  const std::string report_text = report.dump(1) + "\n";
  auto write = [&](const std::string& file, const std::string& content) {
    std::ofstream f(out / file, std::ios::binary);
    f << content;
    f.close();
    if (!f) throw IoError(fmt::format("{}: cannot write the file", (out / file).string()));
  };
  write("report-data.json", report_text);
  write("report.html", io::renderHtmlReport(report_text, (out / "report-data.json").string()));
  Json sj{{"schema", "pkm.campaign-summary/1"},
          {"campaign", name},
          {"source", source},
          {"rows", summaryJson(outcomes)}};
  sj["steps"] = Json::array();
  for (const campaign::StepOutcome& s : outcomes)
    sj["steps"].push_back({{"id", s.id}, {"title", s.title}, {"files", s.files}});
  write("summary.json", sj.dump(2) + "\n");

  if (!a.no_db) {
    io::ResultStore store(a.db);
    for (campaign::StepOutcome& s : outcomes) {
      s.record.name = fmt::format("campaign {} / {}", name, s.id);
      for (const std::string& f : s.files) {
        if (f.find("/measured-before/") == std::string::npos) continue;
        s.record.measurements.push_back(
            {fs::path(f).stem().string(), "measurement", (out / f).string(), 0});
      }
      store.store(s.record);
    }
  }
  fmt::print("\n{} in {:.2f} s; report: {}\n",
             targets == 0 ? "no targets (nothing measured after compensation)"
             : all_pass   ? fmt::format("all targets met ({})", targets)
                          : std::string("SOME TARGETS MISSED"),
             std::chrono::duration<double>(Clock::now() - t0).count(),
             (fs::absolute(out) / "report.html").lexically_normal().string());
  if (!a.no_db)
    fmt::print("results stored in {} (pkm history --machine NAME --db {})\n", a.db, a.db);
  if (!all_pass) {
    std::fflush(stdout);
    fmt::print(stderr, "pkm: a campaign target was missed (see the summary)\n");
    std::exit(1);
  }
}

void addCampaign(CLI::App& app) {
  CLI::App* group = app.add_subcommand("campaign",
                                       "end-to-end campaign: measure, analyse, calibrate, "
                                       "compensate, re-measure, report (docs/campaign.md)");
  group->require_subcommand(1);
  auto a = std::make_shared<RunArgs>();
  CLI::App* run =
      group->add_subcommand("run", "run a campaign (a pkm.campaign/1 file or a built-in name)");
  run->add_option("campaign", a->campaign, "campaign file or built-in name (default: default)");
  run->add_option("--out,-o", a->out, "output directory (report.html, summary.json, step folders)")
      ->required();
  run->add_option("--db", a->db, "result store (SQLite), default pkm.db");
  run->add_flag("--no-db", a->no_db, "do not store the results");
  run->add_flag("--force", a->force, "write into a non-empty output directory");
  run->callback([a] { runCampaign(*a); });
  CLI::App* list = group->add_subcommand("list", "list the built-in campaigns");
  list->callback([] {
    for (const std::string& name : builtinNames()) {
      const auto [text, source] = loadText(name);
      const Json j = parseCampaign(text, source);
      fmt::print(
          "{}\t{} steps\t{}\n", name, j["steps"].size(), j.value("description", std::string()));
    }
  });
}

const CommandRegistration kRegisterCampaign{110, &addCampaign};

}  // namespace
}  // namespace pkm::cli
