// Test helpers: a per-process scratch folder under the system temporary directory, and a file's
// whole content.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace pkm::test {

/// `name` inside the folder TMP/pkm_<prefix>_<pid> (created).
inline std::filesystem::path scratchPath(const std::string& prefix, const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("pkm_" + prefix + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir / name;
}

/// The whole content of the file `p` ("" when it cannot be read).
inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace pkm::test
