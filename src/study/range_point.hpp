// The points of a range of a sweep's axis or of converge --vary: `count`
// points from `from` to `to`, linearly or log-spaced. Private to src/study.
#pragma once

#include <algorithm>
#include <cmath>

namespace barimpact::detail {

/// The point at the fraction s in [0, 1] of the range from `from` to `to`
/// (finite; for `log` both > 0): from + (to - from) s, or from (to / from)^s.
/// Where those overflow (to - from, or to / from, beyond the largest double,
/// or the ratio below the smallest normal one), the same point by a form
/// that cannot: every point of a range of finite ends is finite and lies
/// between them, and ranges that never overflowed keep their values.
inline double range_point(double from, double to, double s, bool log) {
  const double ratio = to / from;
  const double x = log ? from * std::pow(ratio, s) : from + (to - from) * s;
  if (std::isfinite(x) && (!log || (x > 0 && std::isnormal(ratio)))) return x;
  const double y = log ? std::exp(std::lerp(std::log(from), std::log(to), s)) : std::lerp(from, to, s);
  return s == 0 ? from : s == 1 ? to : std::clamp(y, std::min(from, to), std::max(from, to));
}

}  // namespace barimpact::detail
