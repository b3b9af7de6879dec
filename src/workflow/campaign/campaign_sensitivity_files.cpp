// The files of a sensitivity study (campaign_sensitivity_detail.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <utility>

#include "campaign_sensitivity_detail.hpp"
#include "pkm/io/number_format.hpp"

namespace pkm::workflow::detail {
namespace {

using Json = nlohmann::ordered_json;

/// A number, null when not finite.
Json number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

/// A CSV field: quoted (quotes doubled) when it holds a comma, a quote or a line break.
std::string csvText(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string q = "\"";
  for (const char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string csvNumber(double v) { return std::isfinite(v) ? io::formatNumber(v) : std::string(); }

/// The summary quantities in order of first appearance: (step, quantity).
std::vector<std::pair<std::string, std::string>> quantities(const SensitivityResult& r) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const SensitivityRow& row : r.rows) {
    const std::pair<std::string, std::string> key{row.step, row.row.quantity};
    if (std::find(out.begin(), out.end(), key) == out.end()) out.push_back(key);
  }
  return out;
}

/// The plot of one summary quantity: after (or, without any, before) against the value, with the
/// ±U band when every plotted point has a U; null when nothing is plotted.
Json quantityPlot(const SensitivityResult& r,
                  const std::pair<std::string, std::string>& key,
                  const std::string& id) {
  std::vector<const SensitivityRow*> rows;
  for (const SensitivityRow& row : r.rows)
    if (row.step == key.first && row.row.quantity == key.second) rows.push_back(&row);
  std::sort(rows.begin(), rows.end(), [](const SensitivityRow* a, const SensitivityRow* b) {
    return a->value < b->value;
  });
  const bool after = std::any_of(rows.begin(), rows.end(), [](const SensitivityRow* x) {
    return std::isfinite(x->row.after);
  });
  Json x = Json::array(), y = Json::array(), lower = Json::array(), upper = Json::array();
  bool band = true;
  std::string unit;
  for (const SensitivityRow* row : rows) {
    const double v = after ? row->row.after : row->row.before;
    const double u = after ? row->row.after_U : row->row.before_U;
    if (!std::isfinite(v)) continue;
    unit = row->row.unit;
    x.push_back(row->value);
    y.push_back(v);
    band = band && std::isfinite(u);
    lower.push_back(v - u);
    upper.push_back(v + u);
  }
  if (x.empty()) return nullptr;
  Json series{{"label", after ? "after" : "before"}, {"x", x}, {"y", y}};
  if (band) {
    series["lower"] = lower;
    series["upper"] = upper;
  }
  return Json{{"id", id},
              {"title",
               fmt::format("{} {}: {} ± U (k = 2) against {}",
                           key.first,
                           key.second,
                           after ? "after" : "before",
                           r.source)},
              {"kind", "line"},
              {"x_label", fmt::format("{} ({})", r.source, r.unit)},
              {"y_label", fmt::format("{} ({})", after ? "after" : "before", unit)},
              {"series", Json::array({series})}};
}

/// The report's summary table: every row with its U.
Json summaryTable(const SensitivityResult& r) {
  Json t{
      {"title", fmt::format("Every summary row for each value of {} ({})", r.source, r.unit)},
      {"columns", {"value", "step", "quantity", "unit", "before", "U before", "after", "U after"}},
      {"rows", Json::array()}};
  const auto cell = [](double v) {
    return std::isfinite(v) ? Json(std::stod(fmt::format("{:.4g}", v))) : Json(nullptr);
  };
  for (const SensitivityRow& row : r.rows)
    t["rows"].push_back({row.value,
                         row.step,
                         row.row.quantity,
                         row.row.unit,
                         cell(row.row.before),
                         cell(row.row.before_U),
                         cell(row.row.after),
                         cell(row.row.after_U)});
  return t;
}

/// The report's first section: the coefficients of every quantity.
Json coefficientSection(const SensitivityResult& r) {
  Json t{{"title",
          fmt::format("Sensitivity coefficients: least-squares slope against {} (row unit per {})",
                      r.source,
                      r.unit)},
         {"columns", {"step", "quantity", "unit", "d(before)/d(source)", "d(after)/d(source)"}},
         {"rows", Json::array()}};
  const auto cell = [](double v) {
    return std::isfinite(v) ? Json(std::stod(fmt::format("{:.4g}", v))) : Json(nullptr);
  };
  for (const SensitivityCoefficient& c : r.coefficients)
    t["rows"].push_back({c.step, c.quantity, c.unit, cell(c.before), cell(c.after)});
  return Json{{"id", "coefficients"},
              {"title", "Sensitivity coefficients"},
              {"paragraphs",
               Json::array({"How much each summary figure moves per unit of the swept source, "
                            "before and after compensation: a source the compensation cannot see "
                            "(it acts alike on the measurement it was made from and on the "
                            "re-measurement) moves the before-value but not the after-value."})},
              {"tables", Json::array({t})}};
}

}  // namespace

std::string sensitivityJson(const SensitivityResult& r, const SensitivityOptions& o) {
  Json j{{"schema", "pkm.sensitivity/1"},
         {"campaign", r.campaign},
         {"source", r.source},
         {"unit", r.unit},
         {"base_environment", o.base_source},
         {"uncertainty", o.uncertainty_source.empty() ? Json(nullptr) : Json(o.uncertainty_source)},
         {"seed", o.seed ? Json(*o.seed) : Json(nullptr)},
         {"values", r.values},
         {"rows", Json::array()}};
  for (const SensitivityRow& row : r.rows)
    j["rows"].push_back({{"value", row.value},
                         {"step", row.step},
                         {"quantity", row.row.quantity},
                         {"unit", row.row.unit},
                         {"before", number(row.row.before)},
                         {"after", number(row.row.after)},
                         {"before_U", number(row.row.before_U)},
                         {"after_U", number(row.row.after_U)},
                         {"target", row.row.target ? Json(*row.row.target) : Json(nullptr)},
                         {"pass", row.row.pass()}});
  j["coefficients"] = Json::array();
  for (const SensitivityCoefficient& c : r.coefficients)
    j["coefficients"].push_back({{"step", c.step},
                                 {"quantity", c.quantity},
                                 {"unit", c.unit},
                                 {"before", number(c.before)},
                                 {"after", number(c.after)}});
  return j.dump(2) + "\n";
}

std::string sensitivityCsv(const SensitivityResult& r) {
  std::string csv = "value,step,quantity,unit,before,after,before_U,after_U\n";
  for (const SensitivityRow& row : r.rows)
    csv += fmt::format("{},{},{},{},{},{},{},{}\n",
                       io::formatNumber(row.value),
                       csvText(row.step),
                       csvText(row.row.quantity),
                       csvText(row.row.unit),
                       csvNumber(row.row.before),
                       csvNumber(row.row.after),
                       csvNumber(row.row.before_U),
                       csvNumber(row.row.after_U));
  return csv;
}

std::string sensitivityReportData(const SensitivityResult& r, const SensitivityOptions& o) {
  std::vector<std::string> notes = {
      fmt::format("Swept error source: {} ({}), values {}",
                  r.source,
                  r.unit,
                  [&] {
                    std::string v;
                    for (const double x : r.values)
                      v += (v.empty() ? "" : ", ") + fmt::format("{:g}", x);
                    return v;
                  }()),
      fmt::format("Base environment: {} (the source's group switched on, its other values kept)",
                  o.base_source)};
  if (!o.uncertainty_source.empty())
    notes.push_back(fmt::format("Instruments and environment of the uncertainty budgets: {}",
                                o.uncertainty_source));
  if (o.seed) notes.push_back(fmt::format("Seed of every simulated step: {}", *o.seed));
  Json doc{{"schema", "pkm.report/1"},
           {"title", fmt::format("pkm campaign '{}': sensitivity to {}", r.campaign, r.source)},
           {"subtitle",
            "How each summary figure after compensation and its expanded uncertainty U (k = 2) "
            "respond to one error source of the simulated environment"},
           {"notes", notes},
           {"summary", summaryTable(r)},
           {"sections", Json::array()}};
  std::map<std::string, std::size_t> count;
  std::map<std::string, Json> sections;
  std::vector<std::string> order;
  for (const auto& key : quantities(r)) {
    const std::string& step = key.first;
    if (!sections.count(step)) {
      order.push_back(step);
      sections[step] =
          Json{{"id", "step-" + step},
               {"title", fmt::format("Step {}", step)},
               {"paragraphs",
                Json::array({fmt::format("Each plot: the summary figure of step {} against {} "
                                         "({}); the shaded band is the figure ± its U (k = 2).",
                                         step,
                                         r.source,
                                         r.unit)})},
               {"plots", Json::array()}};
    }
    const std::string id = fmt::format("sens-{}-{}", step, ++count[step]);
    Json plot = quantityPlot(r, key, id);
    if (!plot.is_null()) sections[step]["plots"].push_back(std::move(plot));
  }
  doc["sections"].push_back(coefficientSection(r));
  for (const std::string& step : order) doc["sections"].push_back(sections[step]);
  return doc.dump(1) + "\n";
}

}  // namespace pkm::workflow::detail
