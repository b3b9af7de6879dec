// POST /api/gcode/run with "machining" (src/server/api_machining.hpp): the stock's grid, heights
// and frames as base64 that decodes to the announced sizes and replays to the finished part, the
// collisions, and bad machining objects refused with 400.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pkm/server/api.hpp"

namespace pkm::server {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;
using Json = nlohmann::json;

/// RFC 4648 base64 decoding, written here independently of the server's encoder.
std::vector<unsigned char> unbase64(const std::string& text) {
  std::vector<unsigned char> out;
  std::uint32_t acc = 0;
  int bits = 0;
  for (const char c : text) {
    int v = -1;
    if (c >= 'A' && c <= 'Z') v = c - 'A';
    if (c >= 'a' && c <= 'z') v = c - 'a' + 26;
    if (c >= '0' && c <= '9') v = c - '0' + 52;
    if (c == '+') v = 62;
    if (c == '/') v = 63;
    if (v < 0) continue;  // '=' padding
    acc = (acc << 6) | static_cast<std::uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<unsigned char>((acc >> bits) & 0xff));
    }
  }
  return out;
}

template <class T>
std::vector<T> values(const Json& text) {
  const std::vector<unsigned char> bytes = unbase64(text.get<std::string>());
  std::vector<T> v(bytes.size() / sizeof(T));
  std::memcpy(v.data(), bytes.data(), v.size() * sizeof(T));
  return v;
}

class ApiMachining : public ::testing::Test {
 protected:
  ApiMachining() : api_(ServerOptions{}) {}
  Response run(const std::string& machining) {
    const std::string body =
        R"({"machine": "hexapod-default", "name": "m.ngc", "program": "G21 G90\nG0 X0 Y0 Z210\nG1 Z200 F300\nG1 X40\nG1 Z199\nG1 X0\nG0 X20 Y5\nM2\n", "machining": )" +
        machining + "}";
    return api_.handle({"POST", "/api/gcode/run", body, "localhost:8787", "", "", ""});
  }
  Api api_;
};

TEST_F(ApiMachining, TheStockAndItsFramesDecodeAndReplay) {
  const Response r = run(R"({"stock": "box", "box": [-10, -10, 190, 50, 10, 200], "cell": 0.5,
                             "frames": 20})");
  ASSERT_EQ(r.status, 200) << r.body;
  const Json m = Json::parse(r.body)["machining"];
  const std::size_t cells = m["nx"].get<std::size_t>() * m["ny"].get<std::size_t>();
  EXPECT_EQ(cells, 120u * 40u);
  const std::vector<float> initial = values<float>(m["initial"]),
                           heights = values<float>(m["heights"]);
  ASSERT_EQ(initial.size(), cells);
  ASSERT_EQ(heights.size(), cells);
  EXPECT_FLOAT_EQ(initial[0], 200.0f);
  std::vector<float> replay = initial;
  for (const Json& f : m["frames"]) {
    const auto c = values<std::uint32_t>(f["cells"]);
    const auto h = values<float>(f["heights"]);
    ASSERT_EQ(c.size(), h.size());
    for (std::size_t k = 0; k < c.size(); ++k) replay.at(c[k]) = h[k];
  }
  EXPECT_EQ(replay, heights);
  ASSERT_EQ(m["events"].size(), 1u);
  EXPECT_EQ(m["events"][0]["kind"], "rapid");
  EXPECT_EQ(m["events"][0]["line"], 7);
  EXPECT_EQ(m["tools"][0]["number"], 0);  // no tool table: the default tool
  EXPECT_EQ(m["path_tools"]["tip"].size(), Json::parse(r.body)["path"]["t"].size());
  EXPECT_GT(m["initial_volume_mm3"].get<double>(), m["final_volume_mm3"].get<double>());
}

TEST_F(ApiMachining, BadMachiningObjectsAre400) {
  EXPECT_EQ(run(R"("box")").status, 400);
  const Response three = run(R"({"stock": "box", "box": [1, 2, 3]})");
  EXPECT_EQ(three.status, 400);
  EXPECT_THAT(three.body, HasSubstr("machining.box"));
  EXPECT_EQ(run(R"({"stock": "cone"})").status, 400);
  EXPECT_EQ(run(R"({"frames": 1e9})").status, 400);
  EXPECT_EQ(run(R"({"stock": "box", "box": [0, 0, 0, 1000, 1000, 10], "cell": 0.001})").status,
            400);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::server
