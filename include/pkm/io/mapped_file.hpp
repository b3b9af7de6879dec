/// @file
/// @brief The bytes of a file as they are in the page cache: a regular file is mapped read-only
/// (no copy, no buffer zeroed first), standard input and pipes are read into memory. The input
/// of the bulk table reader (io/number_table.hpp).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace pkm::io {

/// A whole input file held for reading. Move-only; the bytes stay valid while it lives.
/// Precondition: a mapped file is not truncated by another program while it lives (its pages
/// past the new end could no longer be read).
class MappedFile {
 public:
  /// Largest file accepted, bytes (4 GiB − 1: tables index rows with 32 bits).
  static constexpr std::size_t kMaxBytes = (std::size_t{1} << 32) - 1;

  /// Maps `path` ("-" reads standard input, named "<stdin>"). Throws pkm::IoError "PATH: cannot
  /// open the file: REASON", "PATH: cannot read the file: REASON" or "PATH: larger than 4 GiB;
  /// split the file".
  [[nodiscard]] static MappedFile open(const std::string& path);

  MappedFile() = default;
  ~MappedFile();
  MappedFile(MappedFile&& other) noexcept;
  MappedFile& operator=(MappedFile&& other) noexcept;
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  /// The file's bytes.
  [[nodiscard]] std::string_view bytes() const { return {data_, size_}; }
  /// The name messages use: the path, or "<stdin>".
  [[nodiscard]] const std::string& name() const { return name_; }

 private:
  void release() noexcept;

  std::string name_;
  const char* data_ = nullptr;
  std::size_t size_ = 0;
  void* map_ = nullptr;  ///< the mapping, or null when the bytes are in read_
  std::string read_;     ///< standard input or a pipe, read whole
};

}  // namespace pkm::io
