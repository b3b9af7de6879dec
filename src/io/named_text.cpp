#include "pkm/io/named_text.hpp"

#include <fstream>
#include <iostream>
#include <sstream>

#include "pkm/core/error.hpp"

namespace pkm::io {

NamedText readNamedText(const std::string& path) {
  std::ostringstream text;
  if (path == "-") {
    text << std::cin.rdbuf();
    return {"<stdin>", text.str()};
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(locate(path, 0, "cannot open the file"));
  text << in.rdbuf();
  if (in.bad()) throw IoError(locate(path, 0, "cannot read the file"));
  return {path, text.str()};
}

std::vector<NamedText> readNamedTexts(const std::vector<std::string>& paths) {
  std::vector<NamedText> out;
  out.reserve(paths.size());
  for (const std::string& p : paths) out.push_back(readNamedText(p));
  return out;
}

}  // namespace pkm::io
