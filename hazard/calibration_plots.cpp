#include "hazard/calibration_plots.h"

#include "io/output/map_quicklook.h"
#include "io/output/series_plots.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace talus::calibration {

void writeLossSlices(const std::string& dir, const LossSlices& sl) {
  for (size_t d = 0; d < sl.specs.size(); ++d) {
    const auto& v = sl.specs[d];
    // x: a dense grid for the surrogate and the members' own values, merged in order.
    std::vector<std::pair<double, double>> xs; // (unit x, member loss or NaN)
    for (int i = 0; i <= 200; ++i) xs.emplace_back(i / 200.0, NAN);
    for (const auto& m : sl.members)
      if (std::isfinite(m.loss)) xs.emplace_back(m.x[Eigen::Index(d)], m.loss);
    std::stable_sort(xs.begin(), xs.end(), [](auto& a, auto& b) { return a.first < b.first; });
    std::vector<double> x;
    ChartLine mean{"surrogate mean", {}}, lo{"mean - 2 sd", {}}, hi{"mean + 2 sd", {}};
    ChartLine runs{"members (all parameters)", {}}, level{"best + tolerance", {}};
    runs.points = true;
    for (const auto& [u, loss] : xs) {
      Eigen::VectorXd at = sl.best;
      at[Eigen::Index(d)] = u;
      double m = 0, sd = 0;
      sl.gp->predict(at, m, sd);
      x.push_back(v.low + u * (v.high - v.low));
      mean.y.push_back(m), lo.y.push_back(m - 2 * sd), hi.y.push_back(m + 2 * sd);
      runs.y.push_back(loss), level.y.push_back(sl.level);
    }
    std::string name = v.key;
    std::replace(name.begin(), name.end(), '.', '_');
    writeLineChart((std::filesystem::path(dir) / ("loss_" + name + ".png")).string(),
                   "Loss against " + v.key + " (the others at the best member)", v.key, "loss", x,
                   {mean, lo, hi, runs, level});
  }
}

void writeRunAgainstEvent(const std::string& path, ObservedEvent& event, const std::string& runDir,
                          const std::string& label) {
  const std::vector<uint8_t> classes = event.classes(runDir);
  const aimec::Transform* t = event.transform();
  if (classes.empty() || !t) return;
  // Rows are cross-sections (s down the picture), columns lanes (l, left of the path first).
  RasterGrid g;
  g.nx = int(t->nl), g.ny = int(t->ns), g.cellSize = t->cellSize;
  std::vector<float> values(g.size()), heights;
  for (size_t i = 0; i < t->ns; ++i)
    for (size_t k = 0; k < t->nl; ++k) {
      const uint8_t c = classes[t->index(i, t->nl - 1 - k)];
      values[g.index(int(k), int(i))] = c == 255 ? -9999.0f : float(c);
    }
  QuicklookStyle st;
  st.title = "Best run against the observed event";
  st.subtitle = label + " on AIMEC's path grid (path from top to bottom)";
  st.classes = {{"observed only", {0.17, 0.45, 0.80}}, {"both", {0.45, 0.25, 0.55}}, {"run only", {0.85, 0.25, 0.15}}};
  st.northUp = false;
  writeMapQuicklook(path, g, values, heights, st, -9999);
}

} // namespace talus::calibration
