// The rows of `pkm volumetric` as CSV (volumetric_csv.hpp).
#include "pkm/io/volumetric_csv.hpp"

#include "pkm/io/number_format.hpp"

namespace pkm::io {

std::string volumetricCsvHeader() {
  return "x,y,z,x2,y2,xp,yp,zp,dx,dy,dz,dp,dx_lin,dy_lin,dz_lin,status\n";
}

void appendVolumetricCsvRow(std::string& o, const VolumetricRow& row) {
  for (int i = 0; i < 3; ++i) o += formatNumber(row.tool[i]) + ',';
  o += formatNumber(row.command.x2) + ',' + formatNumber(row.command.y2) + ',';
  for (int i = 0; i < 3; ++i) o += formatNumber(row.command.pkm[i]) + ',';
  if (row.status == VolumetricRow::Status::kOutsideTable) {
    o += ",,,,,,,outside_table\n";
    return;
  }
  for (int i = 0; i < 3; ++i) o += formatNumber(row.dp[i]) + ',';
  o += formatNumber(row.dp.norm()) + ',';
  for (int i = 0; i < 3; ++i) o += formatNumber(row.dp_linear[i]) + ',';
  o += row.status == VolumetricRow::Status::kOk ? "ok\n" : "axis_limit\n";
}

}  // namespace pkm::io
