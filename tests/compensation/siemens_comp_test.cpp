// SINUMERIK 840D EEC ($AA_ENC_COMP) and CEC ($AN_CEC) part programs: exact text, the K3 example
// parsed, round trips, interpolation and end values, limits and FILE:LINE errors.
#include "pkm/compensation/siemens_comp.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

namespace comp = pkm::compensation;
using pkm::test::kTolExact;
using ::testing::HasSubstr;

/// Resolution of the fixed-point text (9 decimals), mm.
constexpr double kTolText = 5e-10;

comp::AxisErrorTable evenTable() {
  return {"X1", {-200.0, 0.0, 200.0}, {0.004, 0.0, -0.012}, {0.002, 0.0, -0.008}};
}

std::string eecError(const std::string& text) {
  try {
    (void)comp::parseSiemensEec(text, "eec.mpf");
  } catch (const pkm::IoError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no IoError for:\n" << text;
  return {};
}

TEST(SiemensComp, EecExactText) {
  const comp::SiemensEecTable t = comp::siemensEecFromTable(evenTable());
  EXPECT_EQ(comp::writeSiemensEec(t),
            "%_N_AX_EEC_INI\n"
            "CHANDATA(1)\n"
            "; pkm compensate: value = error (actual - commanded), mm; a positive value moves the "
            "axis in - (K3)\n"
            "$AA_ENC_COMP[0,0,X1]=0.003\n"
            "$AA_ENC_COMP[0,1,X1]=0\n"
            "$AA_ENC_COMP[0,2,X1]=-0.01\n"
            "$AA_ENC_COMP_STEP[0,X1]=200\n"
            "$AA_ENC_COMP_MIN[0,X1]=-200\n"
            "$AA_ENC_COMP_MAX[0,X1]=200\n"
            "$AA_ENC_COMP_IS_MODULO[0,X1]=0\n"
            "M17\n");
}

TEST(SiemensComp, ParsesTheK3Example) {
  // The structure of the example in the SINUMERIK 840D sl Function Manual K3 (§4.4), shortened to
  // points 0..2.
  const comp::SiemensEecTable t = comp::parseSiemensEec(
      "%_N_AX_EEC_INI\nCHANDATA(1)\n"
      "$AA_ENC_COMP[0,0,X1]=0.003      ; 1st compensation value: +3 um\n"
      "$AA_ENC_COMP[0,1,X1]=0.01\n"
      "$AA_ENC_COMP[0,2,X1]=0.012\n"
      "$AA_ENC_COMP_STEP[0,X1]=1.0\n"
      "$AA_ENC_COMP_MIN[0,X1]=-200.0\n"
      "$AA_ENC_COMP_MAX[0,X1]=-198.0\n"
      "$AA_ENC_COMP_IS_MODULO[0,X1]=0\nM17\n",
      "k3.mpf");
  EXPECT_EQ(t.axis, "X1");
  EXPECT_EQ(t.values, (std::vector<double>{0.003, 0.01, 0.012}));
  EXPECT_NEAR(t.valueAt(-199.5), 0.0065, kTolExact);
  EXPECT_EQ(t.valueAt(-500.0), 0.003);  // below MIN: the first value
  EXPECT_EQ(t.valueAt(100.0), 0.012);   // above MAX: the last value
  // A positive value moves the axis in −.
  EXPECT_NEAR(t.axisCommand(-199.0), -199.0 - 0.01, kTolExact);
}

TEST(SiemensComp, EecRoundTripAndModulo) {
  comp::AxisErrorTable t{"AX1", {}, {}, {}};
  for (int i = 0; i <= 40; ++i) {
    t.nominal.push_back(-50.0 + 2.5 * i);
    t.error_up.push_back(1e-3 * std::cos(0.3 * i));
    t.error_down.push_back(1e-3 * std::cos(0.3 * i) - 4e-3);
  }
  comp::SiemensEecTable s = comp::siemensEecFromTable(t, 1);
  s.modulo = true;
  const comp::SiemensEecTable p = comp::parseSiemensEec(comp::writeSiemensEec(s), "rt.mpf");
  EXPECT_EQ(p.encoder, 1);
  EXPECT_EQ(p.axis, "AX1");
  EXPECT_TRUE(p.modulo);
  ASSERT_EQ(p.values.size(), s.values.size());
  for (std::size_t i = 0; i < p.values.size(); ++i) {
    EXPECT_NEAR(p.values[i], t.meanError(i), kTolText);
  }
  // Modulo: the table repeats with period MAX − MIN.
  EXPECT_NEAR(p.valueAt(-50.0 + 3.3 + 100.0), p.valueAt(-50.0 + 3.3), kTolExact);
}

TEST(SiemensComp, EecLimits) {
  comp::AxisErrorTable uneven = evenTable();
  uneven.nominal[1] = 10.0;
  EXPECT_THROW((void)comp::siemensEecFromTable(uneven), pkm::InvalidArgument);
  comp::AxisErrorTable bad = evenTable();
  bad.error_up[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((void)comp::siemensEecFromTable(bad), pkm::InvalidArgument);
  bad = evenTable();
  bad.axis = "X 1";
  EXPECT_THROW((void)comp::siemensEecFromTable(bad), pkm::InvalidArgument);
  EXPECT_THROW((void)comp::siemensEecFromTable(evenTable(), 2), pkm::InvalidArgument);
}

TEST(SiemensComp, EecReaderErrorsNameFileAndLine) {
  const std::string tail =
      "$AA_ENC_COMP_STEP[0,X1]=1\n$AA_ENC_COMP_MIN[0,X1]=0\n$AA_ENC_COMP_MAX[0,X1]=1\n";
  EXPECT_THAT(eecError("$AA_ENC_COMP[0,0,X1]=0\n$AA_ENC_COMP[0,0,X1]=1\n" + tail),
              HasSubstr("eec.mpf:2: $AA_ENC_COMP: point 0 given twice"));
  EXPECT_THAT(eecError("$AA_ENC_COMP[0,0,X1]=0\n$AA_ENC_COMP[0,2,X1]=1\n" + tail),
              HasSubstr("eec.mpf:2: point 1 is missing"));
  EXPECT_THAT(eecError("$AA_ENC_COMP[0,0,X1]=0\n$AA_ENC_COMP[0,1,Y1]=1\n" + tail),
              HasSubstr("eec.mpf:2:"));
  EXPECT_THAT(eecError("$AA_ENC_COMP[0,0,X1]=0\n$AA_ENC_COMP[0,1,X1]=abc\n" + tail),
              HasSubstr("eec.mpf:2: $AA_ENC_COMP: 'abc' is not a finite number"));
  EXPECT_THAT(eecError("$AA_ENC_COMP[0,0,X1]=0\n$AA_ENC_COMP[0,1,X1]=0\n$AA_FOO[0,X1]=1\n"),
              HasSubstr("eec.mpf:3: $AA_FOO: unknown"));
  EXPECT_THAT(eecError("G01 X10\n"), HasSubstr("eec.mpf:1: expected $NAME[...]=value"));
  EXPECT_THAT(eecError("$AA_ENC_COMP[0,0,X1]=0\n$AA_ENC_COMP[0,1,X1]=0\n"
                       "$AA_ENC_COMP_STEP[0,X1]=1\n$AA_ENC_COMP_MIN[0,X1]=0\n"
                       "$AA_ENC_COMP_MAX[0,X1]=5\n"),
              HasSubstr("eec.mpf:5: MIN + STEP"));
  EXPECT_THAT(eecError("$AA_ENC_COMP[0,0,X1]=0\n$AA_ENC_COMP[0,1,X1]=0\n"),
              HasSubstr("_STEP, _MIN and _MAX are all required"));
}

TEST(SiemensComp, CecExactTextAndRoundTrip) {
  const comp::CrossAxisTable sag{"Y1", "Z1", {0.0, 100.0, 200.0}, {0.0, -0.004, -0.0105}};
  comp::SiemensCecTable t = comp::siemensCecFromTable(sag, 2);
  const std::string text = comp::writeSiemensCec(t);
  EXPECT_EQ(text,
            "%_N_NC_CEC_INI\n"
            "CHANDATA(1)\n"
            "; pkm compensate: value = error of Z1 (actual - nominal) over Y1, mm (sign: pkm "
            "docs/compensation.md)\n"
            "$AN_CEC[2,0]=0\n"
            "$AN_CEC[2,1]=-0.004\n"
            "$AN_CEC[2,2]=-0.0105\n"
            "$AN_CEC_INPUT_AXIS[2]=(Y1)\n"
            "$AN_CEC_OUTPUT_AXIS[2]=(Z1)\n"
            "$AN_CEC_STEP[2]=100\n"
            "$AN_CEC_MIN[2]=0\n"
            "$AN_CEC_MAX[2]=200\n"
            "$AN_CEC_DIRECTION[2]=0\n"
            "$AN_CEC_MULT_BY_TABLE[2]=0\n"
            "$AN_CEC_IS_MODULO[2]=0\n"
            "M17\n");
  const comp::SiemensCecTable p = comp::parseSiemensCec(text, "cec.mpf");
  EXPECT_EQ(p.index, 2);
  EXPECT_EQ(p.input_axis, "Y1");
  EXPECT_EQ(p.output_axis, "Z1");
  EXPECT_EQ(p.values, t.values);
  EXPECT_NEAR(p.valueAt(150.0), -0.00725, kTolExact);
  EXPECT_EQ(p.valueAt(-1.0), 0.0);
  comp::CrossAxisTable uneven = sag;
  uneven.position[1] = 90.0;
  EXPECT_THROW((void)comp::siemensCecFromTable(uneven), pkm::InvalidArgument);
  t.direction = 2;
  EXPECT_THROW((void)comp::writeSiemensCec(t), pkm::InvalidArgument);
  try {
    (void)comp::parseSiemensCec("$AN_CEC[0,0]=0\n$AN_CEC[1,1]=0\n", "cec.mpf");
    ADD_FAILURE() << "mixed tables accepted";
  } catch (const pkm::IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("cec.mpf:2:"));
  }
}

}  // namespace PKM_TEST_NS
