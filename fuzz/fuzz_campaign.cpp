// libFuzzer harness for the campaign reader (workflow::describeCampaign, docs/campaign.md, schema
// pkm.campaign/1): any input loads or throws pkm::IoError. describeCampaign reads a file, so the
// input is written to a temporary file first. Running a campaign (simulation, calibration) is far
// too slow for fuzzing and not exercised here.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "fuzz_support.hpp"
#include "pkm/workflow/campaign.hpp"

namespace {

const std::string& tempPath() {
  static const std::string path = (std::filesystem::temp_directory_path() /
                                   ("pkm-fuzz-campaign-" + std::to_string(getpid()) + ".json"))
                                      .string();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  {
    std::ofstream out(tempPath(), std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  pkm::fuzz::accepts([&] {
    const pkm::workflow::CampaignInfo info = pkm::workflow::describeCampaign(tempPath());
    pkm::fuzz::check(info.steps > 0, "a campaign has steps");
  });
  std::remove(tempPath().c_str());
  return 0;
}
