/// @file
/// @brief Internal helpers shared by ErrorTable1d and ErrorGrid3d: validation of interpolation
/// nodes and the search of the interval that holds a query position.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string_view>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/geometry/error_table.hpp"

namespace pkm::geometry::detail {

/// Throws pkm::InvalidArgument unless `nodes` is non-empty, finite and strictly increasing.
/// `what` names the node list in the message (e.g. "error table positions").
inline void validateNodes(const std::vector<double>& nodes, std::string_view what) {
  PKM_CHECK(!nodes.empty(), "{}: no nodes", what);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    PKM_CHECK(std::isfinite(nodes[i]), "{}: node {} is not finite ({})", what, i, nodes[i]);
    PKM_CHECK(i == 0 || nodes[i] > nodes[i - 1],
              "{}: nodes must be strictly increasing (node {} = {} after node {} = {})",
              what,
              i,
              nodes[i],
              i - 1,
              nodes[i - 1]);
  }
}

/// Linear-interpolation bracket: the value at the query is (1 − t)·v[lo] + t·v[hi].
struct Bracket {
  std::size_t lo = 0;
  std::size_t hi = 0;
  double t = 0.0;
};

/// The bracket of `s` among `nodes` (validated with validateNodes). Exact at nodes (t = 0 or 1).
/// Outside [front, back]: kClamp holds the end node, kThrow throws pkm::InvalidArgument. A single
/// node gives lo = hi = 0 (a constant). A non-finite `s` always throws.
inline Bracket bracket(const std::vector<double>& nodes,
                       double s,
                       OutOfRange policy,
                       std::string_view what) {
  PKM_CHECK(std::isfinite(s), "{}: query position is not finite ({})", what, s);
  const double front = nodes.front(), back = nodes.back();
  if (s < front || s > back) {
    PKM_CHECK(policy == OutOfRange::kClamp,
              "{}: position {} is outside the range [{}, {}]",
              what,
              s,
              front,
              back);
    const std::size_t end = s < front ? 0 : nodes.size() - 1;
    return {end, end, 0.0};
  }
  if (nodes.size() == 1) return {0, 0, 0.0};
  // First node > s, limited so that [lo, hi] is a valid interval (s == back gives t = 1).
  const auto it = std::upper_bound(nodes.begin() + 1, nodes.end() - 1, s);
  const auto hi = static_cast<std::size_t>(it - nodes.begin());
  const std::size_t lo = hi - 1;
  return {lo, hi, (s - nodes[lo]) / (nodes[hi] - nodes[lo])};
}

}  // namespace pkm::geometry::detail
