#include "pkm/metrology/straightness.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "pkm/core/error.hpp"
#include "pkm/metrology/checks.hpp"

namespace pkm::metrology {
namespace {

void validate(std::span<const double> x, std::span<const double> d) {
  PKM_CHECK(
      x.size() == d.size(), "straightness: {} positions but {} deviations", x.size(), d.size());
  requireFinite(x, "straightness positions");
  requireFinite(d, "straightness deviations");
  requireCount(x.size(), 2, "straightness");
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  PKM_CHECK(*lo < *hi, "straightness: needs at least 2 distinct positions, all are {}", *lo);
}

/// (b - a) × (c - a) for points given by index.
double cross(std::span<const double> x,
             std::span<const double> d,
             std::size_t a,
             std::size_t b,
             std::size_t c) {
  return (x[b] - x[a]) * (d[c] - d[a]) - (d[b] - d[a]) * (x[c] - x[a]);
}

/// Monotone-chain half hull (Andrew 1979) over indices sorted by strictly increasing x.
/// sign = +1: lower hull (left turns kept), -1: upper hull.
std::vector<std::size_t> halfHull(std::span<const double> x,
                                  std::span<const double> d,
                                  const std::vector<std::size_t>& order,
                                  double sign) {
  std::vector<std::size_t> hull;
  for (std::size_t i : order) {
    while (hull.size() >= 2 && sign * cross(x, d, hull[hull.size() - 2], hull.back(), i) <= 0.0) {
      hull.pop_back();
    }
    hull.push_back(i);
  }
  return hull;
}

/// One breakpoint of the zone width: the slope of a hull edge.
struct Candidate {
  double slope;
  bool lower;        ///< edge of the lower hull (else upper)
  std::size_t edge;  ///< index of the edge's first vertex in its hull
};

/// The lower and upper convex hulls of a profile (indices in increasing x).
struct StraightnessHulls {
  std::vector<std::size_t> lower, upper;
};

/// The half hulls of the points (x, d): per distinct x the lowest point feeds the lower hull and
/// the highest the upper hull, so neither hull has a vertical edge.
StraightnessHulls straightnessHulls(std::span<const double> x, std::span<const double> d) {
  std::vector<std::size_t> order(x.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  if (!std::is_sorted(x.begin(), x.end())) {  // measured lines usually come sorted: O(n) then
    std::sort(
        order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return x[a] < x[b]; });
  }
  std::vector<std::size_t> lows, highs;
  for (std::size_t i = 0; i < order.size();) {
    std::size_t low = order[i], high = order[i], j = i + 1;
    for (; j < order.size() && x[order[j]] == x[order[i]]; ++j) {
      if (d[order[j]] < d[low]) low = order[j];
      if (d[order[j]] > d[high]) high = order[j];
    }
    lows.push_back(low);
    highs.push_back(high);
    i = j;
  }
  return {halfHull(x, d, lows, 1.0), halfHull(x, d, highs, -1.0)};
}

/// The slopes of the hull edges, the breakpoints of the zone width, in increasing order.
std::vector<Candidate> hullEdgeSlopes(std::span<const double> x,
                                      std::span<const double> d,
                                      const StraightnessHulls& hulls) {
  const std::vector<std::size_t>& lower = hulls.lower;
  const std::vector<std::size_t>& upper = hulls.upper;
  std::vector<Candidate> candidates;
  const auto slopeOf = [&](std::size_t a, std::size_t b) { return (d[b] - d[a]) / (x[b] - x[a]); };
  for (std::size_t e = 0; e + 1 < lower.size(); ++e) {
    candidates.push_back({slopeOf(lower[e], lower[e + 1]), true, e});
  }
  for (std::size_t e = 0; e + 1 < upper.size(); ++e) {
    candidates.push_back({slopeOf(upper[e], upper[e + 1]), false, e});
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return a.slope < b.slope;
  });
  return candidates;
}

/// The three contacts of the minimum zone of slope best.slope, in increasing x: the end points
/// of the optimal edge `best` and the opposite contact; t and b are the top and bottom of d − m x
/// over the upper and lower hull.
std::array<std::size_t, 3> minimumZoneContacts(std::span<const double> x,
                                               std::span<const double> d,
                                               const StraightnessHulls& hulls,
                                               const Candidate& best,
                                               double t,
                                               double b) {
  const double m = best.slope;
  const std::vector<std::size_t>& own = best.lower ? hulls.lower : hulls.upper;
  const std::vector<std::size_t>& other = best.lower ? hulls.upper : hulls.lower;
  const std::size_t a = own[best.edge], c = own[best.edge + 1];
  // The opposite contact: the extreme vertex of the other hull, preferring one between the
  // edge's end points (it exists at the optimum; ties are resolved within rounding).
  const double scale = std::max({std::abs(t), std::abs(b), t - b});
  const double eps = 1e-12 * scale + std::numeric_limits<double>::min();
  std::size_t pick = other.front();
  double pick_gap = std::numeric_limits<double>::infinity();
  bool pick_inside = false;
  for (std::size_t i : other) {
    const double r = d[i] - m * x[i];
    const double gap = best.lower ? t - r : r - b;
    const bool inside = x[i] >= x[a] && x[i] <= x[c] && gap <= eps;
    if ((inside && !pick_inside) || (inside == pick_inside && gap < pick_gap)) {
      pick = i;
      pick_gap = gap;
      pick_inside = inside;
    }
  }
  std::array<std::size_t, 3> contacts = {a, pick, c};
  std::sort(
      contacts.begin(), contacts.end(), [&](std::size_t p, std::size_t q) { return x[p] < x[q]; });
  return contacts;
}

}  // namespace

std::string_view toString(StraightnessReference reference) {
  switch (reference) {
    case StraightnessReference::kEndpoint:
      return "endpoint";
    case StraightnessReference::kLeastSquares:
      return "lsq";
    case StraightnessReference::kMinimumZone:
      return "minzone";
  }
  return "lsq";
}

StraightnessReference parseStraightnessReference(std::string_view name) {
  if (name == "endpoint") return StraightnessReference::kEndpoint;
  if (name == "lsq" || name == "least-squares") return StraightnessReference::kLeastSquares;
  if (name == "minzone" || name == "minimum-zone") return StraightnessReference::kMinimumZone;
  throw InvalidArgument(
      fmt::format("unknown straightness reference '{}' (endpoint, lsq, minzone)", name));
}

ReferenceLine endpointLine(std::span<const double> x, std::span<const double> d) {
  validate(x, d);
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  const double x1 = *lo, xn = *hi;
  double d1 = 0.0, dn = 0.0;
  int n1 = 0, nn = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (x[k] == x1) {
      d1 += d[k];
      ++n1;
    }
    if (x[k] == xn) {
      dn += d[k];
      ++nn;
    }
  }
  d1 /= n1;
  dn /= nn;
  // m_EP = (d_N - d_1) / (x_N - x_1); line(x) = d_1 + m_EP (x - x_1)   (HP 5528A User's Guide §21)
  const double slope = (dn - d1) / (xn - x1);
  return {slope, d1 - slope * x1};
}

ReferenceLine leastSquaresLine(std::span<const double> x, std::span<const double> d) {
  validate(x, d);
  const auto n = static_cast<double>(x.size());
  const double xm = std::accumulate(x.begin(), x.end(), 0.0) / n;
  const double dm = std::accumulate(d.begin(), d.end(), 0.0) / n;
  double sxx = 0.0, sxd = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    sxx += (x[k] - xm) * (x[k] - xm);
    sxd += (x[k] - xm) * (d[k] - dm);
  }
  // m_LS = [N Σxd - Σx Σd] / [N Σx² - (Σx)²] = Σ(x-x̄)(d-d̄) / Σ(x-x̄)²   (ISO 230-1)
  const double slope = sxd / sxx;
  return {slope, dm - slope * xm};
}

ReferenceLine minimumZoneLine(std::span<const double> x,
                              std::span<const double> d,
                              std::array<std::size_t, 3>* contacts) {
  validate(x, d);
  const StraightnessHulls hulls = straightnessHulls(x, d);
  const std::vector<std::size_t>& lower = hulls.lower;
  const std::vector<std::size_t>& upper = hulls.upper;
  const std::vector<Candidate> candidates = hullEdgeSlopes(x, d, hulls);

  // Zone width for slope m: max over the upper hull minus min over the lower hull of d - m x.
  const auto top = [&](double m) {
    double v = -std::numeric_limits<double>::infinity();
    for (std::size_t i : upper) v = std::max(v, d[i] - m * x[i]);
    return v;
  };
  const auto bottom = [&](double m) {
    double v = std::numeric_limits<double>::infinity();
    for (std::size_t i : lower) v = std::min(v, d[i] - m * x[i]);
    return v;
  };
  const auto width = [&](std::size_t k) {
    const double m = candidates[k].slope;
    return top(m) - bottom(m);
  };
  // The width is convex in m and linear between consecutive breakpoints: binary search.
  std::size_t lo = 0, hi = candidates.size() - 1;
  while (lo < hi) {
    const std::size_t mid = lo + (hi - lo) / 2;
    if (width(mid) <= width(mid + 1)) {
      hi = mid;
    } else {
      lo = mid + 1;
    }
  }
  const Candidate& best = candidates[lo];
  const double m = best.slope;
  const double t = top(m), b = bottom(m);

  if (contacts != nullptr) *contacts = minimumZoneContacts(x, d, hulls, best, t, b);
  return {m, 0.5 * (t + b)};
}

StraightnessResult evaluateStraightness(std::span<const double> x,
                                        std::span<const double> d,
                                        StraightnessReference reference) {
  StraightnessResult result;
  result.reference = reference;
  switch (reference) {
    case StraightnessReference::kEndpoint:
      result.line = endpointLine(x, d);
      break;
    case StraightnessReference::kLeastSquares:
      result.line = leastSquaresLine(x, d);
      break;
    case StraightnessReference::kMinimumZone: {
      std::array<std::size_t, 3> contacts{};
      result.line = minimumZoneLine(x, d, &contacts);
      result.contact_points.assign(contacts.begin(), contacts.end());
      break;
    }
  }
  result.residuals.resize(x.size());
  for (std::size_t k = 0; k < x.size(); ++k) result.residuals[k] = d[k] - result.line.at(x[k]);
  const auto [lo, hi] = std::minmax_element(result.residuals.begin(), result.residuals.end());
  result.straightness = *hi - *lo;  // max_k r_k - min_k r_k   (ISO 230-1)
  return result;
}

}  // namespace pkm::metrology
