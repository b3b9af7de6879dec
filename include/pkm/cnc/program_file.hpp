/// @file
/// @brief The text of a G-code file without a copy: a regular file is mapped into memory
/// read-only (one system call, no page-by-page copy of a program of millions of lines), anything
/// else (a pipe, a terminal) is read whole as Program::readFile does.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace pkm::cnc {

/// A G-code file held in memory for as long as the object lives. Movable, not copyable. As with
/// any mapping, a file cut short by another program while it is mapped ends the process
/// (SIGBUS); pkm's own writers replace files atomically (io::AtomicFile), which is safe.
class ProgramFile {
 public:
  /// Maps or reads `path`. Throws pkm::IoError "PATH: cannot open G-code file" (the message of
  /// Program::readFile).
  explicit ProgramFile(const std::string& path);
  ~ProgramFile();
  ProgramFile(ProgramFile&& other) noexcept;
  ProgramFile& operator=(ProgramFile&& other) noexcept;
  ProgramFile(const ProgramFile&) = delete;
  ProgramFile& operator=(const ProgramFile&) = delete;

  /// The whole text of the file. Valid while this object lives and is not moved from.
  [[nodiscard]] std::string_view text() const { return text_; }

 private:
  void release() noexcept;
  void* map_ = nullptr;    ///< the mapping, null when the text was read into `owned_`
  std::size_t size_ = 0;   ///< length of the mapping
  std::string owned_;      ///< the text of a file that is not mapped
  std::string_view text_;  ///< into the mapping or `owned_`
};

}  // namespace pkm::cnc
