/// @file
/// @brief An input held in memory with the name its messages use: a file read from disk, standard
/// input, or an upload in a front end. Every reader that takes a NamedText reports errors as
/// "NAME:LINE: message", whatever the text came from.
#pragma once

#include <string>
#include <vector>

namespace pkm::io {

/// The text of one input and the name that messages about it use (a path, "<stdin>", or the
/// name of an uploaded file).
struct NamedText {
  std::string name;
  std::string text;
};

/// Reads `path` whole ("-" reads standard input, named "<stdin>"). Throws pkm::IoError
/// "PATH: cannot open the file" or "PATH: cannot read the file".
[[nodiscard]] NamedText readNamedText(const std::string& path);

/// readNamedText of each path, in order. Throws as readNamedText.
[[nodiscard]] std::vector<NamedText> readNamedTexts(const std::vector<std::string>& paths);

}  // namespace pkm::io
