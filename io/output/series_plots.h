// PNG plots of series.csv (plots/*.png): energy, mass, maximum speed, discharge hydrographs,
// front position and speed, water surface; so a run can be judged without other tools.
#pragma once

#include "io/output/time_series.h"

#include <string>
#include <vector>

namespace talus {

/// Writes the plots the table has columns for; returns their paths relative to `outDir`.
std::vector<std::string> writeSeriesPlots(const std::string& outDir, const SeriesTable& table);

/// One line chart: y(x) per line, NaN breaks a line. Used for every plot above.
struct ChartLine {
  std::string label;
  std::vector<double> y;
  bool steps = false; ///< y[k] is a mean over (x[k-1], x[k]]: drawn as a staircase
  bool points = false; ///< each finite y[k] a dot at x[k], not joined (samples among a curve's x)
};
void writeLineChart(const std::string& path, const std::string& title, const std::string& xLabel,
                    const std::string& yLabel, const std::vector<double>& x, const std::vector<ChartLine>& lines);

} // namespace talus
