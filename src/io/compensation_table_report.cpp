// The summary of a compensation table (compensation_table_report.hpp).
#include "pkm/io/compensation_table_report.hpp"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

namespace pkm::io {

std::string compensationTableText(const CompensationTableSummary& s) {
  std::string t = fmt::format("compensation table ({}, axis {}{})\n",
                              s.format,
                              s.axis,
                              s.input_axis ? fmt::format(" over {}", *s.input_axis) : "");
  t += fmt::format("rows\t{}\nrange\t{:.6g}\t{:.6g} {}\nmax_correction\t{:.6g} {}\n",
                   s.rows,
                   s.first,
                   s.last,
                   s.unit,
                   s.max_correction,
                   s.unit);
  if (s.iso && std::isfinite(s.iso->E))
    t += fmt::format("measured E\t{:.6g} {}\n", s.iso->E, s.unit);
  t += fmt::format("wrote\t{}\n", s.out);
  return t;
}

std::string compensationTableJson(const CompensationTableSummary& s) {
  nlohmann::ordered_json j{{"format", s.format},
                           {"out", s.out},
                           {"axis", s.axis},
                           {"rows", s.rows},
                           {"input_rows", s.input_rows},
                           {"unit", s.unit},
                           {"first", s.first},
                           {"last", s.last},
                           {"max_correction", s.max_correction}};
  if (s.input_axis) j["input_axis"] = *s.input_axis;
  if (s.iso) {
    j["E"] = s.iso->E;
    j["B"] = s.iso->B;
    j["M"] = s.iso->M;
  }
  return j.dump(2) + "\n";
}

}  // namespace pkm::io
