#include "pkm/cnc/move.hpp"

#include <charconv>
#include <cmath>

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

namespace {

void appendField(std::string& out, double value) {
  out.push_back(',');
  if (std::isnan(value)) return;
  if (value == 0.0) {  // also drops the sign of -0
    out.push_back('0');
    return;
  }
  detail::appendShortest(out, value);
}

}  // namespace

void appendMoveCsv(std::string& out, const Move& move) {
  char buf[32];
  auto result = std::to_chars(buf, buf + sizeof buf, move.line);
  out.append(buf, result.ptr);
  out.push_back(',');
  out.append(toString(move.kind));
  for (double v : move.end) appendField(out, v);
  for (double v : move.centre) appendField(out, v);
  out.push_back(',');
  result = std::to_chars(buf, buf + sizeof buf, move.turns);
  out.append(buf, result.ptr);
  out.push_back(',');
  out.append(toString(move.plane));
  appendField(out, move.feed);
  out.push_back('\n');
}

}  // namespace pkm::cnc
