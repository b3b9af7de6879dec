// truth.json read back into a true hexapod (pkm/io/truth_file.hpp).
#include "pkm/io/truth_file.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "pkm/core/error.hpp"
#include "pkm/io/json_locator.hpp"
#include "pkm/io/machine_loader.hpp"

namespace pkm::io {
namespace {

using TruthJson = nlohmann::json;

/// Reads values of one truth text, naming the file, line and JSON pointer of a bad one.
class TruthReader {
 public:
  TruthReader(const std::string& text, std::string source)
      : locator_(text), source_(std::move(source)) {}

  [[noreturn]] void fail(const std::string& pointer, const std::string& message) const {
    throw IoError(locate(source_, locator_.line(pointer), fmt::format("{}: {}", pointer, message)));
  }
  const TruthJson& at(const TruthJson& j, const std::string& pointer, const char* key) const {
    if (!j.is_object() || !j.contains(key)) fail(pointer, fmt::format("no \"{}\"", key));
    return j[key];
  }
  double number(const TruthJson& j, const std::string& pointer) const {
    if (!j.is_number()) fail(pointer, "not a number");
    const double v = j.get<double>();
    if (!std::isfinite(v)) fail(pointer, "not finite");
    return v;
  }
  kinematics::StrutVector six(const TruthJson& j, const std::string& pointer) const {
    if (!j.is_array() || j.size() != 6) fail(pointer, "not an array of six numbers");
    kinematics::StrutVector v;
    for (std::size_t i = 0; i < 6; ++i)
      v[static_cast<Eigen::Index>(i)] = number(j[i], fmt::format("{}/{}", pointer, i));
    return v;
  }
  std::array<Eigen::Vector3d, 6> points(const TruthJson& j, const std::string& pointer) const {
    if (!j.is_array() || j.size() != 6) fail(pointer, "not an array of six [x, y, z]");
    std::array<Eigen::Vector3d, 6> out;
    for (std::size_t i = 0; i < 6; ++i) {
      const std::string p = fmt::format("{}/{}", pointer, i);
      if (!j[i].is_array() || j[i].size() != 3) fail(p, "not [x, y, z]");
      for (std::size_t k = 0; k < 3; ++k)
        out[i][static_cast<Eigen::Index>(k)] = number(j[i][k], fmt::format("{}/{}", p, k));
    }
    return out;
  }

 private:
  JsonLocator locator_;
  std::string source_;
};

}  // namespace

HexapodTruth parseHexapodTruth(const std::string& text, const std::string& source) {
  const TruthJson j = TruthJson::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object())
    throw IoError(locate(source, 0, "not a JSON object (a truth.json of `pkm simulate`)"));
  const TruthReader r(text, source);
  const TruthJson& kind = r.at(j, "", "machine_kind");
  if (kind != "hexapod")
    r.fail("/machine_kind", fmt::format("{}: only a hexapod truth is read here", kind.dump()));
  HexapodTruth t;
  t.source = source;
  const TruthJson& machine = r.at(j, "", "machine");
  if (!machine.is_string() || machine.get<std::string>().empty()) r.fail("/machine", "not a name");
  t.machine = machine.get<std::string>();
  std::string spec = t.machine;
  const std::filesystem::path beside = std::filesystem::path(source).parent_path() / spec;
  if (std::filesystem::path(spec).is_relative() && std::filesystem::is_regular_file(beside))
    spec = beside.string();
  try {
    t.nominal = loadHexapodMachine(spec);
  } catch (const IoError& e) {
    r.fail("/machine", e.what());
  }
  if (t.nominal.model.unit != LengthUnit::kMillimetre)
    r.fail("/machine", "the truth's machine must be in mm");
  const TruthJson& errors = r.at(j, "", "errors");
  t.errors.base_joint = r.points(r.at(errors, "/errors", "base_joint"), "/errors/base_joint");
  t.errors.platform_joint =
      r.points(r.at(errors, "/errors", "platform_joint"), "/errors/platform_joint");
  t.errors.length_offset = r.six(r.at(errors, "/errors", "length_offset"), "/errors/length_offset");
  const TruthJson& act = r.at(j, "", "actuation");
  t.actuation.encoder_resolution =
      r.number(r.at(act, "/actuation", "encoder_resolution"), "/actuation/encoder_resolution");
  t.actuation.backlash = r.six(r.at(act, "/actuation", "backlash"), "/actuation/backlash");
  t.actuation.repeatability_sigma =
      r.number(r.at(act, "/actuation", "repeatability_sigma"), "/actuation/repeatability_sigma");
  try {
    t.actuation.validate();
  } catch (const InvalidArgument& e) {
    r.fail("/actuation", e.what());
  }
  return t;
}

HexapodTruth readHexapodTruth(const std::string& path) {
  return parseHexapodTruth(readTextFile(path), path);
}

simulation::HexapodVirtualMachine trueMachine(const HexapodTruth& truth, std::uint64_t noise_seed) {
  simulation::HexapodVirtualMachine m(truth.nominal.model, truth.errors, truth.actuation);
  m.reset(noise_seed);
  return m;
}

}  // namespace pkm::io
