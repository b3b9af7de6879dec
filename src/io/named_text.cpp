#include "pkm/io/named_text.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "pkm/core/error.hpp"

namespace pkm::io {
namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

/// The whole stream `f` in one string: one read into a string of the file's size when the size
/// is known (a regular file), 1 MiB reads otherwise (a pipe, standard input).
std::string readAll(std::FILE* f, const std::string& name) {
  std::string text;
  if (std::fseek(f, 0, SEEK_END) == 0) {
    const long size = std::ftell(f);
    if (size > 0 && std::fseek(f, 0, SEEK_SET) == 0) {
      text.resize(static_cast<std::size_t>(size));
      text.resize(std::fread(text.data(), 1, text.size(), f));
    } else {
      std::rewind(f);
    }
  }
  constexpr std::size_t kChunk = std::size_t{1} << 20;
  char probe[4096];  // the rest, if any (a file that grew, or a pipe), without growing text first
  while (!std::feof(f) && !std::ferror(f)) {
    const std::size_t got = std::fread(probe, 1, sizeof probe, f);
    if (got == 0) continue;
    if (text.capacity() < text.size() + got) text.reserve(std::max(2 * text.size(), kChunk));
    text.append(probe, got);
  }
  if (std::ferror(f))
    throw IoError(locate(name, 0, fmt::format("cannot read the file: {}", std::strerror(errno))));
  return text;
}

}  // namespace

NamedText readNamedText(const std::string& path) {
  if (path == "-") return {"<stdin>", readAll(stdin, "<stdin>")};
  const std::unique_ptr<std::FILE, FileCloser> f(std::fopen(path.c_str(), "rb"));
  if (!f) throw IoError(locate(path, 0, "cannot open the file"));
  return {path, readAll(f.get(), path)};
}

std::vector<NamedText> readNamedTexts(const std::vector<std::string>& paths) {
  std::vector<NamedText> out;
  out.reserve(paths.size());
  for (const std::string& p : paths) out.push_back(readNamedText(p));
  return out;
}

}  // namespace pkm::io
