// Tests of the geometric-errors JSON reader (pkm/io/geometric_errors.hpp) on a hand-written file:
// every error is "FILE:LINE: /pointer: message". The shipped file, round trips and defaults are in
// geometric_errors_test.cpp.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "io/geometric_errors_sample.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/geometric_errors.hpp"

namespace PKM_TEST_NS {

namespace kin = pkm::kinematics;
using pkm::IoError;
using pkm::io::parseGeometricErrorsJson;
using pkm::io::readGeometricErrorsJson;
using pkm::test::errors_json::at;
using pkm::test::errors_json::errorOf;
using pkm::test::errors_json::kSource;
using pkm::test::errors_json::text;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// ---------------------------------------------------------------------------------------------
// Errors: "FILE:LINE: /pointer: message"

TEST(GeometricErrorsJsonErrors, ColumnOfWrongLength) {
  EXPECT_THAT(errorOf(text({{8, "         \"dx\": [0, 0.01],"}})),
              StartsWith(at(8, "/x2/dx") + "expected 3 values, found 2"));
  EXPECT_THAT(errorOf(text({{11, "         \"dy\": [0, 0.002, 0.004]},"}})),
              StartsWith(at(11, "/y2/dy") + "expected 2 values, found 3"));
}

TEST(GeometricErrorsJsonErrors, GridValueCountIsNotNxNyNz) {
  EXPECT_THAT(errorOf(text({{14, "          \"dz\": [0, 0.1, 0.2]}"}})),
              StartsWith(at(14, "/pkm/dz") + "expected 4 values, found 3"));
  // One more node on y makes 8 nodes, and the 4 values no longer fit.
  EXPECT_THAT(errorOf(text({{13, "          \"x\": [-100, 100], \"y\": [0, 1], \"z\": [0, 10],"}})),
              StartsWith(at(14, "/pkm/dz") + "expected 8 values, found 4"));
}

// A grid's values are allocated for every node: a few kilobytes of node coordinates must not ask
// for gigabytes (found by fuzzing: 3 × 600 nodes in 5 kB allocated 10 GB).
TEST(GeometricErrorsJsonErrors, GridOfMoreThanAMillionNodesIsRefused) {
  const auto grid = [](int nx, int ny, int nz) {
    const auto axis = [](int n) {
      std::string a = "[0";
      for (int i = 1; i < n; ++i) a += ", " + std::to_string(i);
      return a + "]";
    };
    return R"({"type": "hybrid_geometric_errors", "pkm": {"x": )" + axis(nx) +
           ",\n\"y\": " + axis(ny) + ",\n\"z\": " + axis(nz) + "}}";
  };
  EXPECT_THAT(errorOf(grid(600, 600, 600)),
              HasSubstr(":3: /pkm/z: the grid has more than 1000000 nodes (nx·ny·nz)"));
  EXPECT_THAT(errorOf(grid(100, 100, 101)), HasSubstr("/pkm/z: the grid has more than"));
  EXPECT_THAT(errorOf(grid(1000001, 1, 1)), HasSubstr("/pkm/x: the grid has more than"));
  const kin::GeometricErrors e = parseGeometricErrorsJson(grid(100, 100, 100), kSource);
  ASSERT_TRUE(e.pkm.has_value());
  EXPECT_EQ(e.pkm->values().rows(), 1'000'000);
}

TEST(GeometricErrorsJsonErrors, PositionsNotIncreasing) {
  const std::string msg = errorOf(text({{7, "         \"positions\": [0, 200, 100],"}}));
  EXPECT_THAT(msg, StartsWith(at(7, "/x2/positions")));
  EXPECT_THAT(msg, HasSubstr("strictly increasing"));
  EXPECT_THAT(errorOf(text({{7, "         \"positions\": [0, 100, 100],"}})),
              StartsWith(at(7, "/x2/positions")));
  const std::string grid =
      errorOf(text({{13, "          \"x\": [100, -100], \"y\": [0], \"z\": [0, 10],"}}));
  EXPECT_THAT(grid, StartsWith(std::string(kSource) + ":12: /pkm"));
  EXPECT_THAT(grid, HasSubstr("strictly increasing"));
}

TEST(GeometricErrorsJsonErrors, EmptyOrMissingPositions) {
  EXPECT_THAT(errorOf(text({{10, "  \"y2\": {\"positions\": [],"}})),
              StartsWith(at(10, "/y2/positions") + "expected a non-empty array"));
  EXPECT_THAT(errorOf(text({{10, "  \"y2\": {"}})),
              StartsWith(at(10, "/y2") + "missing key 'positions'"));
}

TEST(GeometricErrorsJsonErrors, NonFiniteValue) {
  // JSON has no NaN or infinity; a number beyond the range of a double is the way to write one.
  const std::string msg = errorOf(text({{9, "         \"ey_urad\": [0, -5, -1e999]},"}}));
  EXPECT_THAT(msg, StartsWith(std::string(kSource) + ":9: "));
  EXPECT_THAT(msg, HasSubstr("not finite"));
  EXPECT_THAT(errorOf(text({{9, "         \"ey_urad\": [0, -5, NaN]},"}})),
              StartsWith(std::string(kSource) + ":9: invalid JSON"));
}

TEST(GeometricErrorsJsonErrors, NonNumberValue) {
  EXPECT_THAT(errorOf(text({{8, "         \"dx\": [0, \"0.01\", 0.03],"}})),
              StartsWith(at(8, "/x2/dx/1") + "expected a number"));
  EXPECT_THAT(errorOf(text({{8, "         \"dx\": [0, null, 0.03],"}})),
              StartsWith(at(8, "/x2/dx/1") + "expected a number"));
}

TEST(GeometricErrorsJsonErrors, UnknownKey) {
  EXPECT_THAT(errorOf(text({{4, "  \"units\": \"mm\", \"z2\": {},"}})),
              StartsWith(at(4, "/z2") + "unknown key 'z2'"));
  EXPECT_THAT(errorOf(text({{9, "         \"eb_urad\": [0, -5, -10]},"}})),
              StartsWith(at(9, "/x2/eb_urad") + "unknown key 'eb_urad'"));
  EXPECT_THAT(errorOf(text({{5, "  \"squareness_urad\": {\"szX2\": -34, \"sxp\": 10},"}})),
              StartsWith(at(5, "/squareness_urad/sxp") + "unknown key 'sxp'"));
  // Rotation keys need their unit suffix.
  EXPECT_THAT(errorOf(text({{14, "          \"dz\": [0, 0.1, 0.2, 0.4], \"ez\": [0, 0, 0, 0]}"}})),
              StartsWith(at(14, "/pkm/ez") + "unknown key 'ez'"));
}

TEST(GeometricErrorsJsonErrors, BadOutOfRangePolicy) {
  EXPECT_THAT(errorOf(text({{6, "  \"x2\": {\"out_of_range\": \"extrapolate\","}})),
              StartsWith(at(6, "/x2/out_of_range") + "must be \"clamp\" or \"error\""));
  EXPECT_THAT(errorOf(text({{12, "  \"pkm\": {\"out_of_range\": 1,"}})),
              StartsWith(at(12, "/pkm/out_of_range") + "expected a string"));
}

TEST(GeometricErrorsJsonErrors, WrongType) {
  EXPECT_THAT(errorOf(text({{3, "  \"type\": \"exechon\","}})), StartsWith(at(3, "/type")));
  EXPECT_THAT(errorOf(text({{3, ""}})), StartsWith(at(1, "/type")));
}

TEST(GeometricErrorsJsonErrors, BadSchemaAndUnits) {
  EXPECT_THAT(errorOf(text({{2, "  \"schema\": \"pkm.machine/1\","}})),
              StartsWith(at(2, "/schema") + "unsupported schema"));
  EXPECT_THAT(errorOf(text({{4, "  \"units\": \"um\","}})), StartsWith(at(4, "/units")));
}

TEST(GeometricErrorsJsonErrors, InvalidJsonSyntax) {
  EXPECT_THAT(errorOf(text({{11, "         \"dy\": [0, 0.002]}"}})),  // missing comma before "pkm"
              StartsWith(std::string(kSource) + ":12: invalid JSON"));
}

TEST(GeometricErrorsJsonErrors, ReadingAFileNamesIt) {
  const std::string path = testing::TempDir() + "geometric_errors_test_bad.json";
  {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    const std::string t = text({{8, "         \"dx\": [0, 0.01],"}});
    std::fwrite(t.data(), 1, t.size(), f);
    std::fclose(f);
  }
  try {
    (void)readGeometricErrorsJson(path);
    ADD_FAILURE() << "no error";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), StartsWith(path + ":8: /x2/dx: "));
  }
  std::remove(path.c_str());
  EXPECT_THROW((void)readGeometricErrorsJson(path), IoError);  // no such file
}

}  // namespace PKM_TEST_NS
