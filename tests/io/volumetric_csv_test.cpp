// io::volumetricCsvHeader / appendVolumetricCsvRow: the three statuses.
#include "pkm/io/volumetric_csv.hpp"

#include <gtest/gtest.h>

namespace pkm::io {
namespace PKM_TEST_NS {

TEST(VolumetricCsv, RowsOfEachStatus) {
  EXPECT_EQ(volumetricCsvHeader(),
            "x,y,z,x2,y2,xp,yp,zp,dx,dy,dz,dp,dx_lin,dy_lin,dz_lin,status\n");
  VolumetricRow r;
  r.tool = {1.0, 2.0, 3.0};
  r.command.x2 = 10.0;
  r.command.y2 = 20.0;
  r.command.pkm = {0.5, 0.25, -1.0};
  r.dp = {0.375, 0.5, 0.0};
  r.dp_linear = {0.375, 0.5, 0.001};
  std::string o;
  appendVolumetricCsvRow(o, r);
  EXPECT_EQ(o, "1,2,3,10,20,0.5,0.25,-1,0.375,0.5,0,0.625,0.375,0.5,0.001,ok\n");
  o.clear();
  r.status = VolumetricRow::Status::kAxisLimit;
  appendVolumetricCsvRow(o, r);
  EXPECT_EQ(o.substr(o.rfind(',') + 1), "axis_limit\n");
  o.clear();
  r.status = VolumetricRow::Status::kOutsideTable;
  appendVolumetricCsvRow(o, r);
  EXPECT_EQ(o, "1,2,3,10,20,0.5,0.25,-1,,,,,,,,outside_table\n");
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
