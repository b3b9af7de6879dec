#include "pkm/cnc/move.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string_view>

#include "csv_field.hpp"

namespace pkm::cnc {

const char* toString(MoveKind kind) {
  switch (kind) {
    case MoveKind::kRapid:
      return "rapid";
    case MoveKind::kLinear:
      return "linear";
    case MoveKind::kArc:
      return "arc";
  }
  return "?";
}

const char* toString(Plane plane) {
  switch (plane) {
    case Plane::kXY:
      return "XY";
    case Plane::kXZ:
      return "XZ";
    case Plane::kYZ:
      return "YZ";
  }
  return "?";
}

std::array<std::size_t, 3> planeAxes(Plane plane) {
  switch (plane) {
    case Plane::kXY:
      return {0, 1, 2};
    case Plane::kXZ:
      return {2, 0, 1};  // LinuxCNC's G18: first axis Z, second X (normal Y)
    case Plane::kYZ:
      return {1, 2, 0};
  }
  return {0, 1, 2};
}

namespace {

char* writeField(char* out, double value) {
  *out++ = ',';
  if (std::isnan(value)) return out;
  if (value == 0.0) {  // also drops the sign of -0
    *out++ = '0';
    return out;
  }
  return detail::writeShortest(out, value);
}

constexpr std::array<std::string_view, 3> kKindText{"rapid", "linear", "arc"};  // toString
constexpr std::array<std::string_view, 3> kPlaneText{"XY", "XZ", "YZ"};         // toString

char* writeText(char* out, std::string_view text) {
  std::memcpy(out, text.data(), text.size());
  return out + text.size();
}

}  // namespace

// Room: line 20 digits, kind 6, ten number fields of at most 1 + kMaxShortest, turns 11, plane 2,
// four separators and the newline: 20 + 6 + 10 * 33 + 11 + 2 + 5 = 374 < kMaxMoveCsvRow.
char* writeMoveCsv(char* out, const Move& move) {
  out = std::to_chars(out, out + 24, move.line).ptr;
  *out++ = ',';
  out = writeText(out, kKindText[static_cast<std::size_t>(move.kind)]);
  for (double v : move.end) out = writeField(out, v);
  for (double v : move.centre) out = writeField(out, v);
  *out++ = ',';
  out = std::to_chars(out, out + 12, move.turns).ptr;
  *out++ = ',';
  out = writeText(out, kPlaneText[static_cast<std::size_t>(move.plane)]);
  out = writeField(out, move.feed);
  *out++ = '\n';
  return out;
}

void appendMoveCsv(std::string& out, const Move& move) {
  char buf[kMaxMoveCsvRow];
  out.append(buf, writeMoveCsv(buf, move));
}

}  // namespace pkm::cnc
