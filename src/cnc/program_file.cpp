// A G-code file mapped into memory (POSIX mmap), or read whole when it cannot be mapped.
#include "pkm/cnc/program_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <utility>

#include "pkm/cnc/program.hpp"
#include "pkm/core/error.hpp"

namespace pkm::cnc {

ProgramFile::ProgramFile(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw IoError(fmt::format("{}: cannot open G-code file", path));
  struct stat st {};
  if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0) {
    const auto size = static_cast<std::size_t>(st.st_size);
    // MAP_POPULATE maps the whole file at once: no page fault per 4 KiB when it is read.
    void* map = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
    if (map != MAP_FAILED) {
      map_ = map;
      size_ = size;
      text_ = std::string_view(static_cast<const char*>(map), size);
    }
  }
  ::close(fd);
  if (map_ == nullptr) {  // empty, not a regular file, or not mappable: read it as a stream
    owned_ = Program::readFile(path);
    text_ = owned_;
  }
}

ProgramFile::~ProgramFile() { release(); }

ProgramFile::ProgramFile(ProgramFile&& other) noexcept { *this = std::move(other); }

ProgramFile& ProgramFile::operator=(ProgramFile&& other) noexcept {
  if (this == &other) return *this;
  release();
  map_ = std::exchange(other.map_, nullptr);
  size_ = std::exchange(other.size_, 0);
  owned_ = std::move(other.owned_);
  text_ = map_ != nullptr ? std::string_view(static_cast<const char*>(map_), size_)
                          : std::string_view(owned_);
  other.owned_.clear();
  other.text_ = {};
  return *this;
}

void ProgramFile::release() noexcept {
  if (map_ != nullptr) ::munmap(map_, size_);
  map_ = nullptr;
  size_ = 0;
}

}  // namespace pkm::cnc
