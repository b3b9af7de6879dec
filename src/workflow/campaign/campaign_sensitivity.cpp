// A campaign's sensitivity to one error source of its environment
// (workflow/campaign_sensitivity.hpp, docs/campaign.md "Sensitivity study").
#include "pkm/workflow/campaign_sensitivity.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>

#include "campaign_sensitivity_detail.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/io/environment_file.hpp"
#include "pkm/io/html_report.hpp"

namespace pkm::workflow {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// The campaign run of value `k`.
CampaignOptions runOptions(const SensitivityOptions& o, std::size_t k) {
  CampaignOptions c;
  c.campaign = o.campaign;
  c.campaign_text = o.campaign_text;
  c.out = o.out / "runs" / fmt::format("value-{}", k + 1);
  c.force = o.force;
  simulation::Environment e = o.base;
  io::setEnvironmentParameter(e, o.source, o.values[k]);
  c.environment = e;
  c.environment_source = fmt::format("{} with {} = {:g}", o.base_source, o.source, o.values[k]);
  c.uncertainty = o.uncertainty;
  c.uncertainty_source = o.uncertainty_source;
  c.seed = o.seed;
  return c;
}

/// The coefficients of every summary quantity, in the order of first appearance.
std::vector<SensitivityCoefficient> coefficientsOf(const std::vector<SensitivityRow>& rows) {
  std::vector<SensitivityCoefficient> out;
  for (const SensitivityRow& row : rows) {
    const auto same = [&](const auto& x) {
      return x.step == row.step && x.quantity == row.row.quantity;
    };
    if (std::any_of(out.begin(), out.end(), same)) continue;
    std::vector<double> x, before, after;
    for (const SensitivityRow& r : rows)
      if (r.step == row.step && r.row.quantity == row.row.quantity) {
        x.push_back(r.value);
        before.push_back(r.row.before);
        after.push_back(r.row.after);
      }
    out.push_back({row.step,
                   row.row.quantity,
                   row.row.unit,
                   leastSquaresSlope(x, before),
                   leastSquaresSlope(x, after)});
  }
  return out;
}

}  // namespace

double leastSquaresSlope(const std::vector<double>& x, const std::vector<double>& y) {
  PKM_CHECK(x.size() == y.size(), "leastSquaresSlope: {} x but {} y", x.size(), y.size());
  double n = 0.0, mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (std::isfinite(y[i])) {
      n += 1.0;
      mx += x[i];
      my += y[i];
    }
  if (n < 2.0) return std::nan("");
  mx /= n;
  my /= n;
  double sxy = 0.0, sxx = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (std::isfinite(y[i])) {
      sxy += (x[i] - mx) * (y[i] - my);
      sxx += (x[i] - mx) * (x[i] - mx);
    }
  return sxx > 0.0 ? sxy / sxx : std::nan("");
}

void SensitivityOptions::validate() const {
  if (out.empty()) throw IoError("give --out DIR");
  std::string why;
  PKM_CHECK(base.isValid(&why), "sensitivity: base environment {}: {}", base_source, why);
  (void)io::environmentParameter(base, source);  // throws for an unknown path, listing them
  PKM_CHECK(!values.empty(), "sensitivity: give the values of {} (--values V1,V2,...)", source);
  std::set<double> seen;
  for (const double v : values) {
    PKM_CHECK(std::isfinite(v), "sensitivity: value {} of {} is not finite", v, source);
    PKM_CHECK(seen.insert(v).second, "sensitivity: value {:g} of {} is repeated", v, source);
    simulation::Environment e = base;
    io::setEnvironmentParameter(e, source, v);  // throws for a value the environment refuses
  }
  PKM_CHECK(!uncertainty || uncertainty->isValid(&why),
            "sensitivity: uncertainty sources {}: {}",
            uncertainty_source,
            why);
}

SensitivityResult runSensitivity(const SensitivityOptions& options, const RunControl& control) {
  options.validate();
  io::prepareOutputDirectory(options.out, options.force);
  const auto t0 = Clock::now();
  SensitivityResult result;
  result.source = options.source;
  result.values = options.values;
  for (const io::EnvironmentParameter& p : io::environmentParameters())
    if (p.path == options.source) result.unit = p.unit;
  const std::size_t n = options.values.size();
  for (std::size_t k = 0; k < n; ++k) {
    control.checkCancelled();
    const std::string stage = fmt::format("value-{}", k + 1);
    const auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - t0).count(); };
    control.report({stage,
                    k + 1,
                    n,
                    elapsed(),
                    fmt::format("{} = {:g} {}", options.source, options.values[k], result.unit)});
    RunControl inner;
    inner.cancel = control.cancel;
    inner.notice = control.notice;
    inner.progress = [&](const ProgressEvent& e) {
      if (e.index > 0)
        control.report({stage + " " + e.stage, k + 1, n, elapsed(), fmt::format("{}", e.message)});
    };
    const CampaignResult run = runCampaign(runOptions(options, k), inner);
    result.campaign = run.name;
    for (const CampaignStepResult& s : run.steps)
      for (const CampaignRow& r : s.rows) result.rows.push_back({options.values[k], s.id, r});
  }
  result.coefficients = coefficientsOf(result.rows);
  result.json = detail::sensitivityJson(result, options);
  io::writeFileAtomic(options.out / "sensitivity.json", result.json, io::Overwrite::kAllow);
  io::writeFileAtomic(
      options.out / "sensitivity.csv", detail::sensitivityCsv(result), io::Overwrite::kAllow);
  const std::string report = detail::sensitivityReportData(result, options);
  io::writeFileAtomic(options.out / "report-data.json", report, io::Overwrite::kAllow);
  io::writeFileAtomic(options.out / "report.html",
                      io::renderHtmlReport(report, (options.out / "report-data.json").string()),
                      io::Overwrite::kAllow);
  result.report = (fs::absolute(options.out) / "report.html").lexically_normal();
  result.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return result;
}

}  // namespace pkm::workflow
