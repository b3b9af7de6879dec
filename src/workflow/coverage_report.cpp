// The outputs of `pkm validate coverage` (workflow/coverage.hpp): the table, coverage.json and the
// report.
#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <system_error>

#include "pkm/core/error.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/io/html_report.hpp"
#include "pkm/workflow/coverage.hpp"

namespace pkm::workflow {
namespace {

using Json = nlohmann::ordered_json;

/// A finite number, or null.
Json number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

/// The flags of a quantity: "LOW" (coverage below the acceptable), "BIAS" (the same for a
/// quantity pkm does not claim: the method's bias), "WIDE" (U > 3 RMS error).
std::string flags(const CoverageQuantity& q) {
  std::string f;
  if (!q.holds()) f += q.claimed() ? "LOW" : "BIAS";
  if (q.wide()) f += f.empty() ? "WIDE" : " WIDE";
  return f;
}

/// A value in the quantity's unit, shown in µm / µrad where that reads better (mm from 1 mm: a
/// calibration's parameters and TCP errors reach tens of millimetres).
std::string scaled(double v, const std::string& unit) {
  if (unit == "mm" && std::abs(v) >= 1.0) return fmt::format("{:.3g} mm", v);
  if (unit == "mm") return fmt::format("{:.3g} µm", v * 1e3);
  if (unit == "rad") return fmt::format("{:.3g} µrad", v * 1e6);
  return fmt::format("{:.3g} {}", v, unit);
}

}  // namespace

std::string coverageText(const CoverageResult& r) {
  std::string out = fmt::format(
      "coverage of the stated U over {} seeds ({} to {}); truth: the same test with a perfect "
      "instrument in perfect conditions{}\n",
      r.seeds,
      r.first_seed,
      r.first_seed + static_cast<std::uint64_t>(r.seeds) - 1,
      r.environment.empty() ? "" : fmt::format("; environment {}", r.environment));
  out += "scenario\tgroup\tquantity\tN\tcoverage\tmean U\tbias\tRMS error\tmean z\tsd z\tflags\n";
  for (const CoverageQuantity& q : r.quantities)
    out += fmt::format("{}\t{}\t{}\t{}\t{:.1f} %\t{}\t{}\t{}\t{:.2f}\t{:.2f}\t{}\n",
                       q.scenario,
                       q.group,
                       q.quantity,
                       q.trials.size(),
                       100.0 * q.coverage(),
                       scaled(q.meanU(), q.unit),
                       scaled(q.bias(), q.unit),
                       scaled(q.errorRms(), q.unit),
                       q.meanZ(),
                       q.spreadZ(),
                       flags(q));
  const double need = r.quantities.empty() ? 0.0 : r.quantities.front().acceptableCoverage();
  out += fmt::format(
      "{} of {} quantities reach the acceptable coverage ({:.1f} % at N = {}: 95 % less two "
      "binomial standard deviations); {:.1f} s\n",
      r.holding(),
      r.claims(),
      100.0 * need,
      r.seeds,
      r.seconds);
  if (r.claims() < r.quantities.size())
    out += fmt::format(
        "{} rows compare a squareness with the injected one: not a claim of U (diagonal methods "
        "do not separate squareness from the other geometric errors, ISO 230-6), their bias is "
        "the method's on this machine (BIAS when outside U)\n",
        r.quantities.size() - r.claims());
  return out;
}

std::string coverageJson(const CoverageResult& r) {
  Json j;
  j["schema"] = "pkm.coverage/1";
  j["seeds"] = r.seeds;
  j["first_seed"] = r.first_seed;
  j["scenarios"] = r.scenarios;
  j["environment"] = r.environment;
  j["uncertainty"] = r.uncertainty;
  j["claimed_coverage"] = 0.95;
  j["holding"] = r.holding();
  j["claims"] = r.claims();
  j["seconds"] = r.seconds;
  Json qs = Json::array();
  for (const CoverageQuantity& q : r.quantities) {
    Json trials = Json::array();
    for (const CoverageTrial& t : q.trials)
      trials.push_back(Json{{"seed", t.seed},
                            {"value", t.value},
                            {"truth", t.truth},
                            {"U", t.U},
                            {"u_c", t.u_c},
                            {"k", t.k}});
    qs.push_back(Json{{"scenario", q.scenario},
                      {"group", q.group},
                      {"quantity", q.quantity},
                      {"unit", q.unit},
                      {"truth", q.truth_kind},
                      {"n", q.trials.size()},
                      {"coverage", number(q.coverage())},
                      {"acceptable", q.acceptableCoverage()},
                      {"holds", q.holds()},
                      {"claimed", q.claimed()},
                      {"wide", q.wide()},
                      {"mean_U", number(q.meanU())},
                      {"bias", number(q.bias())},
                      {"error_rms", number(q.errorRms())},
                      {"mean_z", number(q.meanZ())},
                      {"sd_z", number(q.spreadZ())},
                      {"trials", std::move(trials)}});
  }
  j["quantities"] = std::move(qs);
  return j.dump(2) + "\n";
}

std::string coverageReportData(const CoverageResult& r) {
  Json doc;
  doc["schema"] = "pkm.report/1";
  doc["title"] = fmt::format("Coverage of pkm's uncertainty statements ({} seeds)", r.seeds);
  Json summary{
      {"title", "Per quantity: the fraction of seeds whose |value − truth| <= U"},
      {"columns", {"scenario", "group", "quantity", "coverage %", "mean U", "bias", "flags"}},
      {"rows", Json::array()}};
  Json categories = Json::array(), coverage = Json::array(), acceptable = Json::array();
  for (const CoverageQuantity& q : r.quantities) {
    summary["rows"].push_back({q.scenario,
                               q.group,
                               q.quantity,
                               number(100.0 * q.coverage()),
                               scaled(q.meanU(), q.unit),
                               scaled(q.bias(), q.unit),
                               flags(q)});
    categories.push_back(fmt::format("{} {}", q.group, q.quantity));
    coverage.push_back(number(100.0 * q.coverage()));
    acceptable.push_back(100.0 * q.acceptableCoverage());
  }
  doc["summary"] = std::move(summary);
  Json plot{{"id", "coverage"},
            {"title", "Coverage per quantity and the acceptable coverage"},
            {"kind", "bar"},
            {"x_label", "quantity"},
            {"y_label", "coverage (%)"},
            {"categories", std::move(categories)},
            {"series",
             Json::array({Json{{"label", "coverage"}, {"y", std::move(coverage)}},
                          Json{{"label", "acceptable"}, {"y", std::move(acceptable)}}})}};
  doc["sections"] = Json::array(
      {Json{{"id", "coverage"},
            {"title", "Coverage"},
            {"paragraphs",
             {"Truth: the value the same test gives on the same virtual machine with a perfect "
              "instrument in perfect conditions (docs/coverage.md); a squareness is also "
              "compared with the injected one (\"vs injected\").",
              fmt::format("{} of {} claimed quantities hold.", r.holding(), r.claims())}},
            {"plots", Json::array({std::move(plot)})}}});
  return doc.dump(2) + "\n";
}

void writeCoverage(const CoverageResult& result, const std::filesystem::path& dir, bool force) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw IoError(fmt::format("{}: cannot create the directory", dir.string()));
  const std::string data = coverageReportData(result);
  const std::pair<const char*, std::string> files[] = {
      {"coverage.json", coverageJson(result)},
      {"report-data.json", data},
      {"report.html", io::renderHtmlReport(data, "coverage report data")}};
  if (!force)
    for (const auto& [name, text] : files)
      if (std::filesystem::exists(dir / name, ec))
        throw IoError(
            fmt::format("{}: exists; refusing to overwrite (use --force)", (dir / name).string()));
  for (const auto& [name, text] : files)
    io::writeFileAtomic(dir / name, text, io::Overwrite::kAllow);
}

}  // namespace pkm::workflow
