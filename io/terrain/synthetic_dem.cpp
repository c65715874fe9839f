#include "io/terrain/synthetic_dem.h"

#include "io/common/resource_limits.h"

#include "io/terrain/dem_raster.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <map>
#include <sstream>

namespace talus {

namespace {

constexpr double kDeg = M_PI / 180.0;

using Params = std::map<std::string, double>;

/// A profile descending towards +x through segments of given horizontal length and slope
/// angle; the angle changes smoothly (tanh over +-blend m) between segments.
struct Profile {
  std::vector<double> h; ///< sampled every `step` m from x = 0
  double step = 1;
  Profile(const std::vector<std::pair<double, double>>& segs, double blend, double length, double stepM) : step(stepM) {
    const size_t n = size_t(std::ceil(length / step)) + 2;
    h.assign(n, 0.0);
    auto angle = [&](double x) {
      double a = segs.front().second, edge = 0;
      for (size_t i = 0; i + 1 < segs.size(); ++i) {
        edge += segs[i].first;
        a += (segs[i + 1].second - segs[i].second) * 0.5 * (1 + std::tanh((x - edge) / std::max(blend, 1e-6)));
      }
      return a * kDeg;
    };
    for (size_t i = 1; i < n; ++i) h[i] = h[i - 1] - step * std::tan(angle((double(i) - 0.5) * step));
  }
  double operator()(double x) const {
    const double u = std::clamp(x / step, 0.0, double(h.size() - 1) - 1e-9);
    const size_t i = size_t(u);
    return h[i] + (u - double(i)) * (h[i + 1] - h[i]);
  }
};

double window(double x, double a, double b, double blend) { // ~1 on [a, b], smooth edges
  return 0.25 * (1 + std::tanh((x - a) / blend)) * (1 + std::tanh((b - x) / blend));
}

struct Kind {
  SyntheticDemKind info;
  double sizeX, sizeY, base;
  /// Height relative to the kind's lowest point (shifted afterwards), at (X, Y) from the
  /// south-west corner.
  std::function<std::function<double(double, double)>(const Params&, double Lx, double Ly)> make;
};

const std::vector<Kind>& kinds() {
  static const std::vector<Kind> k = [] {
    std::vector<Kind> v;
    v.push_back({{"slope_valley",
                  "a plateau, a planar slope steepening to slope_angle, a flat valley floor draining north and a counter slope",
                  {{"top_length", 150, "plateau length (m)"},
                   {"top_angle", 10, "plateau slope (deg)"},
                   {"slope_length", 600, "slope horizontal length (m)"},
                   {"slope_angle", 35, "slope angle (deg)"},
                   {"floor_length", 400, "valley floor length (m)"},
                   {"counter_length", 250, "counter slope length (m)"},
                   {"counter_angle", 20, "counter slope angle (deg)"},
                   {"valley_slope", 2, "floor inclination towards north (deg)"},
                   {"blend", 40, "half width of the slope transitions (m)"}}},
                 1400, 800, 1000,
                 [](const Params& p, double Lx, double Ly) -> std::function<double(double, double)> {
                   auto prof = std::make_shared<Profile>(
                       std::vector<std::pair<double, double>>{{p.at("top_length"), p.at("top_angle")},
                                                              {p.at("slope_length"), p.at("slope_angle")},
                                                              {p.at("floor_length"), 0.0},
                                                              {p.at("counter_length"), -p.at("counter_angle")}},
                       p.at("blend"), Lx, 0.5);
                   const double vs = std::tan(p.at("valley_slope") * kDeg);
                   return [prof, vs, Ly](double X, double Y) { return (*prof)(X) + (Ly - Y) * vs; };
                 }});
    v.push_back({{"vajont",
                  "a valley running north: a reservoir basin closed by a dam in a narrow gorge, a steep west flank (the slide's "
                  "side) and an east flank",
                  {{"basin_width", 300, "basin floor width (m)"},
                   {"gorge_width", 40, "gorge floor width below the dam (m)"},
                   {"gorge_depth", 60, "drop of the gorge floor below the basin floor (m)"},
                   {"dam_y", 1300, "dam position from the south edge (m)"},
                   {"dam_height", 180, "dam crest above the basin floor (m)"},
                   {"dam_thickness", 25, "dam thickness (m)"},
                   {"west_angle", 32, "west flank angle (deg)"},
                   {"east_angle", 38, "east flank angle (deg)"},
                   {"flank_height", 700, "flank relief before it levels off (m)"},
                   {"valley_slope", 0.5, "floor inclination towards north (deg)"}}},
                 1600, 2000, 500,
                 [](const Params& p, double Lx, double Ly) -> std::function<double(double, double)> {
                   return [p, Lx, Ly](double X, double Y) {
                     const double vs = std::tan(p.at("valley_slope") * kDeg);
                     const double damY = p.at("dam_y");
                     // The valley narrows to the gorge before the dam; the gorge floor drops after it.
                     const double narrow = 0.5 * (1 + std::tanh((Y - (damY - 80)) / 30));
                     const double drop = 0.5 * (1 + std::tanh((Y - (damY + 30)) / 30));
                     const double halfw = 0.5 * (p.at("basin_width") * (1 - narrow) + p.at("gorge_width") * narrow);
                     const double floor = (Ly - Y) * vs - p.at("gorge_depth") * drop;
                     const double xc = 0.5 * Lx, d = std::fabs(X - xc) - halfw;
                     const double ang = (X < xc ? p.at("west_angle") : p.at("east_angle")) * kDeg;
                     const double H = p.at("flank_height");
                     double h = floor + (d > 0 ? H * std::tanh(d * std::tan(ang) / H) : 0.0);
                     if (std::fabs(Y - damY) <= 0.5 * p.at("dam_thickness"))
                       h = std::max(h, (Ly - damY) * vs + p.at("dam_height"));
                     return h;
                   };
                 }});
    v.push_back({{"cengalo",
                  "a steep rock face above a glacier ramp and a valley, in a U-shaped trough",
                  {{"ridge_length", 100, "summit ridge length (m)"},
                   {"ridge_angle", 10, "summit ridge slope (deg)"},
                   {"face_length", 400, "rock face horizontal length (m)"},
                   {"face_angle", 60, "rock face angle (deg)"},
                   {"glacier_length", 700, "glacier length (m)"},
                   {"glacier_angle", 15, "glacier slope (deg)"},
                   {"valley_length", 1000, "valley length (m)"},
                   {"valley_angle", 6, "valley slope (deg)"},
                   {"trough_depth", 30, "trough rise at +-trough_width/2 from the axis (m)"},
                   {"trough_width", 600, "trough width (m)"},
                   {"blend", 30, "half width of the slope transitions (m)"}}},
                 2200, 1200, 1800,
                 [](const Params& p, double Lx, double Ly) -> std::function<double(double, double)> {
                   auto prof = std::make_shared<Profile>(
                       std::vector<std::pair<double, double>>{{p.at("ridge_length"), p.at("ridge_angle")},
                                                              {p.at("face_length"), p.at("face_angle")},
                                                              {p.at("glacier_length"), p.at("glacier_angle")},
                                                              {p.at("valley_length"), p.at("valley_angle")}},
                       p.at("blend"), Lx, 0.5);
                   const double depth = p.at("trough_depth"), hw = 0.5 * p.at("trough_width");
                   return [prof, depth, hw, Ly](double X, double Y) {
                     const double r = (Y - 0.5 * Ly) / hw;
                     return (*prof)(X) + depth * r * r;
                   };
                 }});
    v.push_back({{"fluela",
                  "a steep rock face above a combe (an overdeepened bowl) and an outlet slope",
                  {{"ridge_length", 80, "summit ridge length (m)"},
                   {"ridge_angle", 20, "summit ridge slope (deg)"},
                   {"face_length", 200, "rock face horizontal length (m)"},
                   {"face_angle", 55, "rock face angle (deg)"},
                   {"combe_length", 500, "combe length (m)"},
                   {"combe_angle", 12, "combe mean slope (deg)"},
                   {"combe_depth", 40, "depth of the bowl below the mean slope (m)"},
                   {"combe_width", 500, "bowl width (m)"},
                   {"outlet_length", 500, "outlet slope length (m)"},
                   {"outlet_angle", 25, "outlet slope angle (deg)"},
                   {"blend", 25, "half width of the slope transitions (m)"}}},
                 1300, 900, 2200,
                 [](const Params& p, double Lx, double Ly) -> std::function<double(double, double)> {
                   auto prof = std::make_shared<Profile>(
                       std::vector<std::pair<double, double>>{{p.at("ridge_length"), p.at("ridge_angle")},
                                                              {p.at("face_length"), p.at("face_angle")},
                                                              {p.at("combe_length"), p.at("combe_angle")},
                                                              {p.at("outlet_length"), p.at("outlet_angle")}},
                       p.at("blend"), Lx, 0.5);
                   const double x0 = p.at("ridge_length") + p.at("face_length");
                   const double xc = x0 + 0.5 * p.at("combe_length"), lx = 0.5 * p.at("combe_length");
                   const double ly = 0.5 * p.at("combe_width"), depth = p.at("combe_depth");
                   return [prof, xc, lx, ly, depth, Ly](double X, double Y) {
                     const double u = (X - xc) / lx, w = (Y - 0.5 * Ly) / ly;
                     return (*prof)(X) - depth * std::exp(-(u * u + w * w)) + 0.25 * depth * w * w;
                   };
                 }});
    v.push_back({{"whymper",
                  "a hanging glacier ending in an ice cliff above a couloir, a terrace and the valley floor",
                  {{"upper_length", 150, "upper glacier length (m)"},
                   {"upper_angle", 25, "upper glacier slope (deg)"},
                   {"glacier_length", 300, "hanging glacier length (m)"},
                   {"glacier_angle", 32, "hanging glacier slope (deg)"},
                   {"cliff_length", 60, "ice cliff / lip horizontal length (m)"},
                   {"cliff_angle", 65, "ice cliff angle (deg)"},
                   {"couloir_length", 450, "couloir length (m)"},
                   {"couloir_angle", 48, "couloir slope (deg)"},
                   {"couloir_depth", 35, "couloir incision depth (m)"},
                   {"couloir_width", 120, "couloir width (m)"},
                   {"terrace_length", 450, "terrace length (m)"},
                   {"terrace_angle", 15, "terrace slope (deg)"},
                   {"valley_length", 400, "valley floor length (m)"},
                   {"valley_angle", 5, "valley floor slope (deg)"},
                   {"blend", 15, "half width of the slope transitions (m)"},
                   {"side_offset", 0, "second track: its axis this far south of the couloir's (m); 0 = none"},
                   {"side_width", 160, "second track: trough width (m)"},
                   {"side_depth", 15, "second track: trough depth (m)"},
                   {"side_length", 600, "second track: length of its glacier ramp below the ice cliff (m)"},
                   {"side_angle", 35, "second track: ramp angle (deg)"},
                   {"side_runout_angle", 12, "second track: slope below the ramp (deg)"},
                   {"side_ridge", 20, "second track: height of the ridge parting the tracks, from mid-cliff down (m)"}}},
                 1800, 800, 2400,
                 [](const Params& p, double Lx, double Ly) -> std::function<double(double, double)> {
                   auto prof = std::make_shared<Profile>(
                       std::vector<std::pair<double, double>>{{p.at("upper_length"), p.at("upper_angle")},
                                                              {p.at("glacier_length"), p.at("glacier_angle")},
                                                              {p.at("cliff_length"), p.at("cliff_angle")},
                                                              {p.at("couloir_length"), p.at("couloir_angle")},
                                                              {p.at("terrace_length"), p.at("terrace_angle")},
                                                              {p.at("valley_length"), p.at("valley_angle")}},
                       p.at("blend"), Lx, 0.5);
                   const double a = p.at("upper_length") + p.at("glacier_length") + p.at("cliff_length");
                   const double b = a + p.at("couloir_length");
                   const double depth = p.at("couloir_depth"), hw = 0.5 * p.at("couloir_width");
                   const double blend = std::max(p.at("blend"), 1.0);
                   // Optional second track (the paper's Planpincieux branch): south of the couloir,
                   // below the same ice cliff, a gentler glacier ramp in a trough replaces the
                   // couloir. The tracks part at a dividing line side_width/2 + 40 m north of the
                   // second track's axis: above the cliff the hanging glacier's cross-slope is then
                   // centred on that line (ice falling there splits between the tracks); below it,
                   // north of the line the couloir's valley, south of it the second track's own
                   // valley and trough, level with it on the line, where a ridge rises to part the
                   // flow. A steep step grows between the tracks downstream, as the couloir drops
                   // faster.
                   const double off = p.at("side_offset");
                   std::shared_ptr<Profile> side;
                   if (off > 0)
                     side = std::make_shared<Profile>(
                         std::vector<std::pair<double, double>>{{p.at("upper_length"), p.at("upper_angle")},
                                                                {p.at("glacier_length"), p.at("glacier_angle")},
                                                                {p.at("cliff_length"), p.at("cliff_angle")},
                                                                {p.at("side_length"), p.at("side_angle")},
                                                                {Lx, p.at("side_runout_angle")}},
                         p.at("blend"), Lx, 0.5);
                   const double shw = 0.5 * p.at("side_width"), sdepth = p.at("side_depth"), ridge = p.at("side_ridge");
                   const double cliff = p.at("cliff_length");
                   return [prof, side, a, b, depth, hw, blend, Ly, off, shw, sdepth, ridge, cliff](double X, double Y) {
                     auto lateral = [&](double y) { return 0.02 * (y - 0.5 * Ly) * (y - 0.5 * Ly) / hw; };
                     const double r = (Y - 0.5 * Ly) / hw;
                     const double notch = std::max(0.0, 1 - r * r) * window(X, a, b, blend);
                     const double main = (*prof)(X) - depth * notch + lateral(Y);
                     if (!side) return main;
                     const double ys = 0.5 * Ly - off, yd = ys + shw + 40, rs = (Y - ys) / shw;
                     const double upper = (*prof)(X) + lateral(yd) + 0.02 * (Y - yd) * (Y - yd) / hw;
                     const double trough = sdepth * std::max(0.0, 1 - rs * rs);
                     const double sideLateral = lateral(yd) + 0.02 * ((Y - ys) * (Y - ys) - (yd - ys) * (yd - ys)) / shw;
                     const double lower = (*side)(X) - trough + sideLateral;
                     const double below = 0.5 * (1 + std::tanh((X - a - 20) / 20)); // 0 above the cliff's foot
                     const double south = 0.5 * (1 - std::tanh((Y - yd) / 20));
                     // A ridge along the dividing line, rising from the middle of the cliff (a
                     // buttress), parts the flow.
                     const double parting = ridge * std::exp(-(Y - yd) * (Y - yd) / 400) * 0.5 * (1 + std::tanh((X - a + 0.5 * cliff) / 15));
                     return (1 - below) * upper + below * ((1 - south) * main + south * lower) + parting;
                   };
                 }});
    return v;
  }();
  return k;
}

} // namespace

const std::vector<SyntheticDemKind>& syntheticDemKinds() {
  static const std::vector<SyntheticDemKind> k = [] {
    std::vector<SyntheticDemKind> v;
    for (const auto& kind : kinds()) v.push_back(kind.info);
    return v;
  }();
  return k;
}

DemRaster makeSyntheticDem(const ConfigTable& t) {
  std::vector<std::string> names;
  for (const auto& k : kinds()) names.push_back(k.info.name);
  const std::string name = t.choice("kind", "", names);
  const Kind& kind = *std::find_if(kinds().begin(), kinds().end(), [&](const Kind& k) { return k.info.name == name; });
  Params p;
  for (const auto& par : kind.info.params) {
    const bool angle = par.name.find("angle") != std::string::npos || par.name == "valley_slope";
    p[par.name] = angle ? t.inRange(par.name, par.value, -80, 85) : t.positive(par.name, par.value, true);
  }
  const double cell = t.positive("cell_size", 5.0);
  double Lx = kind.sizeX, Ly = kind.sizeY;
  if (t.has("size")) {
    const auto s = t.numbers("size");
    if (s.size() != 2 || !(s[0] > 0) || !(s[1] > 0)) t.fail("size", "expected 2 positive numbers [x, y] (m)");
    Lx = s[0], Ly = s[1];
  }
  const int nx = int(std::lround(Lx / cell)), ny = int(std::lround(Ly / cell));
  if (nx < 2 || ny < 2) t.fail("cell_size", "the DEM must be at least 2 x 2 cells");
  if (double(nx) * double(ny) > resourceLimits().maxRasterCells)
    t.fail("cell_size", "more than " + std::to_string(resourceLimits().maxRasterCells) + " cells: use a coarser cell_size");
  std::vector<double> origin{2600000.0, 1200000.0};
  if (t.has("origin")) {
    origin = t.numbers("origin");
    if (origin.size() != 2) t.fail("origin", "expected [x, y] of the south-west corner (m)");
  }
  const double base = t.number("base_elevation", kind.base);
  DemRaster dem;
  try {
    dem.grid.crsWkt = crsToWkt(t.string("crs", "EPSG:2056"));
  } catch (const InputError& e) {
    t.fail("crs", e.what());
  }
  dem.grid.nx = nx, dem.grid.ny = ny, dem.grid.cellSize = cell;
  dem.grid.originX = origin[0], dem.grid.originY = origin[1] + ny * cell;
  dem.sourcePath = "synthetic:" + name;
  const auto f = kind.make(p, nx * cell, ny * cell);
  dem.height.resize(dem.grid.size());
  double lo = INFINITY;
  std::vector<double> h(dem.grid.size());
  for (int r = 0; r < ny; ++r)
    for (int c = 0; c < nx; ++c) {
      const double X = (c + 0.5) * cell, Y = (ny - r - 0.5) * cell;
      h[dem.grid.index(c, r)] = f(X, Y);
      lo = std::min(lo, h[dem.grid.index(c, r)]);
    }
  for (size_t i = 0; i < h.size(); ++i) dem.height[i] = float(h[i] - lo + base);
  return dem;
}

std::string syntheticDemHelp() {
  std::ostringstream s;
  s << "Common keys: cell_size (m, 5), size = [x, y] (m), origin = [x, y] south-west corner (m, [2600000, 1200000]),\n"
       "crs (\"EPSG:2056\"), base_elevation (m, lowest point). Slopes descend towards +x (east).\n";
  for (const auto& k : kinds()) {
    s << "\n" << k.info.name << " (" << k.sizeX << " x " << k.sizeY << " m, base " << k.base << " m): " << k.info.description
      << "\n";
    for (const auto& p : k.info.params) s << "  " << p.name << " = " << p.value << "  " << p.meaning << "\n";
  }
  return s.str();
}

} // namespace talus
