#include "pkm/io/mapped_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

#include "pkm/core/error.hpp"

namespace pkm::io {
namespace {

/// Closes a descriptor when it goes out of scope.
struct Descriptor {
  int fd = -1;
  ~Descriptor() {
    if (fd > 2) ::close(fd);
  }
};

[[noreturn]] void failRead(const std::string& name, const char* what) {
  throw IoError(locate(name, 0, fmt::format("{}: {}", what, std::strerror(errno))));
}

/// Everything `fd` still delivers (a pipe or a terminal), in blocks of 1 MiB.
std::string readStream(int fd, const std::string& name) {
  constexpr std::size_t kBlock = std::size_t{1} << 20;
  std::string out;
  std::size_t used = 0;
  while (true) {
    if (out.size() - used < kBlock) out.resize(used + kBlock);
    const ssize_t got = ::read(fd, out.data() + used, kBlock);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) failRead(name, "cannot read the file");
    if (got == 0) break;
    used += static_cast<std::size_t>(got);
    if (used > MappedFile::kMaxBytes)
      throw IoError(locate(name, 0, "larger than 4 GiB; split the file"));
  }
  out.resize(used);
  return out;
}

}  // namespace

MappedFile MappedFile::open(const std::string& path) {
  MappedFile f;
  Descriptor d;
  if (path == "-") {
    f.name_ = "<stdin>";
    d.fd = STDIN_FILENO;
  } else {
    f.name_ = path;
    d.fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (d.fd < 0) failRead(path, "cannot open the file");
  }
  struct stat st {};
  if (::fstat(d.fd, &st) != 0) failRead(f.name_, "cannot read the file");
  if (S_ISDIR(st.st_mode)) throw IoError(locate(f.name_, 0, "cannot open the file: a directory"));
  if (!S_ISREG(st.st_mode)) {
    f.read_ = readStream(d.fd, f.name_);
    f.data_ = f.read_.data();
    f.size_ = f.read_.size();
    return f;
  }
  const auto size = static_cast<std::size_t>(st.st_size);
  if (size > kMaxBytes) throw IoError(locate(f.name_, 0, "larger than 4 GiB; split the file"));
  if (size == 0) return f;
  // MAP_POPULATE: the pages are entered in one call rather than faulted in one by one.
  void* map = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE | MAP_POPULATE, d.fd, 0);
  if (map == MAP_FAILED) failRead(f.name_, "cannot read the file");
  f.map_ = map;
  f.data_ = static_cast<const char*>(map);
  f.size_ = size;
  return f;
}

MappedFile::~MappedFile() { release(); }

MappedFile::MappedFile(MappedFile&& other) noexcept { *this = std::move(other); }

MappedFile& MappedFile::operator=(MappedFile&& other) noexcept {
  if (this == &other) return *this;
  release();
  name_ = std::move(other.name_);
  read_ = std::move(other.read_);
  map_ = std::exchange(other.map_, nullptr);
  size_ = std::exchange(other.size_, 0);
  data_ = map_ != nullptr ? static_cast<const char*>(map_) : read_.data();
  other.data_ = nullptr;
  return *this;
}

void MappedFile::release() noexcept {
  if (map_ != nullptr) ::munmap(map_, size_);
  map_ = nullptr;
  data_ = nullptr;
  size_ = 0;
}

}  // namespace pkm::io
