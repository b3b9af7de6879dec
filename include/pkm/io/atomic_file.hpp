/// @file
/// @brief The one way pkm writes an output file: into a temporary file beside the destination,
/// renamed into place once complete, so that a failed or interrupted write never leaves a partial
/// file and never destroys the file that was there.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>

namespace pkm::io {

/// What a writer does when the destination already exists.
enum class Overwrite {
  kRefuse,  ///< throw pkm::IoError "PATH exists; pass --force to overwrite it"
  kAllow,   ///< replace it (atomically)
};

/// Throws pkm::IoError "PATH exists; pass --force to overwrite it" when `path` exists and
/// `overwrite` is kRefuse. For commands that check every output before they start working.
void checkOverwrite(const std::filesystem::path& path, Overwrite overwrite);

/// Creates the output directory `dir` of a command that writes a folder of files. Throws
/// pkm::IoError "DIR: exists and is not a directory", "DIR: exists and is not empty; refusing to
/// overwrite (use --force)" (unless `force`) or "DIR: cannot create the directory".
void prepareOutputDirectory(const std::filesystem::path& dir, bool force);

/// A file written in pieces and published atomically. The text goes to `PATH.tmp` beside the
/// destination; commit() renames it into place. Destroyed without commit() (an exception on the
/// way), the temporary file is removed and the destination is untouched.
class AtomicFile {
 public:
  /// Opens `path`.tmp for writing. Throws pkm::IoError "PATH: cannot write the file" when it
  /// cannot be created, and as checkOverwrite().
  AtomicFile(std::filesystem::path path, Overwrite overwrite);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// Appends `text`. Throws pkm::IoError "PATH: write failed" (disk full, ...).
  void write(std::string_view text);
  /// Closes the file and renames it into place. Throws pkm::IoError "PATH: write failed" or
  /// "PATH: cannot write the file"; afterwards no temporary file is left either way.
  void commit();
  /// The destination.
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  void discard() noexcept;
  std::filesystem::path path_, tmp_;
  std::FILE* file_ = nullptr;
};

/// Writes `text` to `path` through an AtomicFile. Throws as AtomicFile.
void writeFileAtomic(const std::filesystem::path& path, std::string_view text, Overwrite overwrite);

/// The whole content of the file `path`. Throws pkm::IoError "PATH: cannot read the file".
[[nodiscard]] std::string readFileText(const std::filesystem::path& path);

}  // namespace pkm::io
