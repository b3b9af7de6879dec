// Atomic output files (atomic_file.hpp).
#include "pkm/io/atomic_file.hpp"

#include <fmt/format.h>

#include <fstream>
#include <iterator>
#include <system_error>
#include <utility>

#include "pkm/core/error.hpp"

namespace pkm::io {

namespace fs = std::filesystem;

void prepareOutputDirectory(const fs::path& dir, bool force) {
  const std::string out = dir.string();
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw IoError(fmt::format("{}: exists and is not a directory", out));
  if (!force && fs::exists(dir, ec) && !fs::is_empty(dir, ec))
    throw IoError(
        fmt::format("{}: exists and is not empty; refusing to overwrite (use --force)", out));
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir, ec))
    throw IoError(fmt::format("{}: cannot create the directory", out));
}

void checkOverwrite(const fs::path& path, Overwrite overwrite) {
  std::error_code ec;
  if (overwrite == Overwrite::kRefuse && fs::exists(path, ec))
    throw IoError(fmt::format("{} exists; pass --force to overwrite it", path.string()));
}

AtomicFile::AtomicFile(fs::path path, Overwrite overwrite)
    : path_(std::move(path)), tmp_(path_.string() + ".tmp") {
  checkOverwrite(path_, overwrite);
  file_ = std::fopen(tmp_.c_str(), "wb");
  if (file_ == nullptr) throw IoError(fmt::format("{}: cannot write the file", path_.string()));
}

AtomicFile::~AtomicFile() { discard(); }

void AtomicFile::discard() noexcept {
  if (file_ == nullptr) return;
  std::fclose(file_);
  file_ = nullptr;
  std::error_code ec;
  fs::remove(tmp_, ec);
}

void AtomicFile::write(std::string_view text) {
  if (file_ == nullptr) throw IoError(fmt::format("{}: write failed", path_.string()));
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size()) {
    discard();
    throw IoError(fmt::format("{}: write failed", path_.string()));
  }
}

void AtomicFile::commit() {
  if (file_ == nullptr) throw IoError(fmt::format("{}: write failed", path_.string()));
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  std::error_code ec;
  if (!closed) {
    fs::remove(tmp_, ec);
    throw IoError(fmt::format("{}: write failed", path_.string()));
  }
  fs::rename(tmp_, path_, ec);
  if (ec) {
    fs::remove(tmp_, ec);
    throw IoError(fmt::format("{}: cannot write the file", path_.string()));
  }
}

void writeFileAtomic(const fs::path& path, std::string_view text, Overwrite overwrite) {
  AtomicFile f(path, overwrite);
  f.write(text);
  f.commit();
}

std::string readFileText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(fmt::format("{}: cannot read the file", path.string()));
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw IoError(fmt::format("{}: cannot read the file", path.string()));
  return text;
}

}  // namespace pkm::io
