// The work-precision chart of `talus work-precision` (docs/performance.md's picture).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace talus::work_precision {

/// One run of a case: its resolution, error and cost.
struct Point {
  double cells = 0, error = 0, wall = 0;
  size_t particles = 0;
  unsigned long long steps = 0;
  std::string detail; ///< case-specific figures behind the error, printed with it
};

/// Writes a log-log PNG of error against wall time, one polyline per case (names[i] for
/// series[i]); points without a positive wall time and error are left out. Writes nothing when
/// no point has both. Throws std::runtime_error when the PNG cannot be written.
void plot(const std::string& path, const std::vector<std::string>& names, const std::vector<std::vector<Point>>& series);

} // namespace talus::work_precision
