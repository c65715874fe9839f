#include "hazard/ensemble_aggregate.h"
#include "hazard/ensemble_report.h"

#include "hazard/aimec.h"
#include "hazard/ensemble_runner.h"
#include "io/common/geotiff_writer.h"
#include "io/output/map_quicklook.h"
#include "io/output/series_plots.h"
#include "io/terrain/dem_raster.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

namespace talus::ensemble {

namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kTypes{"pft", "pfv", "ppr", "pfd"};

const char* title(const std::string& type) {
  if (type == "pft") return "peak flow thickness";
  if (type == "pfv") return "peak flow velocity";
  if (type == "ppr") return "peak pressure";
  return "peak flow depth (vertical)";
}
const char* unit(const std::string& type) { return type == "pfv" ? "m/s" : type == "ppr" ? "kPa" : "m"; }

std::string num(double v, const char* f = "%g") {
  if (!std::isfinite(v)) return "nan";
  char b[48];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

/// Per cell: the finite member values.
template <class F>
std::vector<float> perCell(const std::vector<const DemRaster*>& m, F f) {
  if (m.empty()) return {};
  std::vector<float> out(m[0]->height.size(), NAN);
  std::vector<double> v;
  for (size_t c = 0; c < out.size(); ++c) {
    v.clear();
    for (const DemRaster* r : m)
      if (std::isfinite(r->height[c])) v.push_back(r->height[c]);
    if (!v.empty()) out[c] = float(f(v));
  }
  return out;
}

bool sameGrid(const RasterGrid& a, const RasterGrid& b) {
  return a.nx == b.nx && a.ny == b.ny && std::abs(a.originX - b.originX) < 1e-6 * a.cellSize &&
         std::abs(a.originY - b.originY) < 1e-6 * a.cellSize && std::abs(a.cellSize - b.cellSize) < 1e-9 * a.cellSize;
}

/// Hard link (the same bytes, no copy), else a copy.
void link(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::remove(to, ec);
  fs::create_hard_link(from, to, ec);
  if (ec) fs::copy_file(from, to, fs::copy_options::overwrite_existing);
}

} // namespace

std::string findPeakFile(const std::string& memberDir, const std::string& type) {
  const fs::path dir = fs::path(memberDir) / "peakFiles";
  if (!fs::is_directory(dir)) return "";
  std::string asc;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string n = e.path().filename().string(), suffix = "_" + type;
    if (e.path().stem().string().size() < suffix.size() ||
        e.path().stem().string().compare(e.path().stem().string().size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    if (e.path().extension() == ".tif") return e.path().string();
    if (e.path().extension() == ".asc") asc = e.path().string();
  }
  return asc;
}

std::vector<float> exceedanceProbability(const std::vector<const DemRaster*>& m, double threshold) {
  return perCell(m, [&](const std::vector<double>& v) {
    size_t n = 0;
    for (double x : v) n += x > threshold;
    return double(n) / double(v.size());
  });
}

std::vector<float> cellMean(const std::vector<const DemRaster*>& m) {
  return perCell(m, [](const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return s / double(v.size());
  });
}

std::vector<float> cellQuantile(const std::vector<const DemRaster*>& m, double q) {
  return perCell(m, [&](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const double h = q * double(v.size() - 1);
    const size_t lo = size_t(std::floor(h)), hi = std::min(lo + 1, v.size() - 1);
    return v[lo] + (h - double(lo)) * (v[hi] - v[lo]);
  });
}

AggregateReport aggregate(const std::string& dirIn, const Plan& plan, const EnsembleSettings& set,
                          std::shared_ptr<const DemRaster> ground) {
  const fs::path dir(dirIn);
  AggregateReport rep;
  rep.members.resize(plan.members());
  // Completed members' rasters per type.
  std::map<std::string, std::vector<DemRaster>> rasters;
  std::vector<size_t> done;
  fs::create_directories(dir / "peakFiles");
  for (size_t m = 0; m < plan.members(); ++m) {
    const std::string md = (dir / memberName(m)).string();
    MemberOutcome& o = rep.members[m];
    o.completed = memberState(md) == MemberState::Completed;
    o.wallSeconds = memberWallSeconds(md);
    if (!o.completed) continue;
    for (const auto& type : kTypes) {
      const std::string f = findPeakFile(md, type);
      if (f.empty()) throw std::runtime_error(md + "/peakFiles: no " + type + " peak file (the run wrote no AvaFrame peak files)");
      DemReadOptions opt;
      opt.keepNodata = true;
      rasters[type].push_back(readDem(f, opt));
      if (!sameGrid(rasters[type].back().grid, rasters[type].front().grid))
        throw std::runtime_error(f + ": not on the grid of the other members' peak files");
      link(f, dir / "peakFiles" / fs::path(f).filename()); // AvaFrame reads the ensemble as one folder
      const fs::path prj = fs::path(f).replace_extension(".prj");
      if (fs::exists(prj)) link(prj, dir / "peakFiles" / prj.filename());
    }
    done.push_back(m);
  }
  if (done.empty()) throw std::runtime_error(dirIn + ": no completed member to aggregate");
  const RasterGrid grid = rasters["pft"].front().grid;
  std::vector<float> heights;
  if (ground && sameGrid(ground->grid, grid)) heights = ground->height;

  fs::create_directories(dir / "maps");
  auto writeMap = [&](const std::string& stem, const std::vector<float>& v, const std::string& titleText,
                      const std::string& u, const std::string& band, double scaleMax, chart::Ramp ramp) {
    GeoTiffBand b;
    b.description = band;
    b.unit = u;
    b.metadata = {{"TALUS_ENSEMBLE_MEMBERS", std::to_string(done.size())}};
    std::vector<float> out(v);
    for (float& x : out)
      if (!std::isfinite(x)) x = -9999.f;
    writeGeoTiff((dir / "maps" / (stem + ".tif")).string(), grid, out, b);
    QuicklookStyle st;
    st.title = titleText;
    st.subtitle = std::to_string(done.size()) + " ensemble members";
    st.unit = u;
    st.ramp = ramp;
    st.scaleMax = scaleMax;
    writeMapQuicklook((dir / "maps" / (stem + ".png")).string(), grid, out, heights, st, -9999.f);
    rep.files.push_back("maps/" + stem + ".tif");
    rep.files.push_back("maps/" + stem + ".png");
  };
  std::map<std::string, std::vector<const DemRaster*>> ptrs;
  for (const auto& type : kTypes)
    for (const auto& r : rasters[type]) ptrs[type].push_back(&r);
  for (const auto& [type, ts] : set.thresholds)
    for (double t : ts)
      writeMap("prob_" + type + "_lim" + num(t), exceedanceProbability(ptrs[type], t),
               std::string("P(") + title(type) + " > " + num(t) + " " + unit(type) + ")", "probability",
               "probability_" + type + "_gt_" + num(t), 1.0, chart::Ramp::Magma);
  for (const auto& type : {"pft", "pfv", "ppr"}) {
    writeMap(std::string("mean_") + type, cellMean(ptrs[type]), std::string("Mean ") + title(type), unit(type),
             std::string("mean_") + type, 0, chart::Ramp::Viridis);
    for (double q : set.quantiles) {
      char qs[16];
      std::snprintf(qs, sizeof qs, "q%02d", int(std::lround(q * 100)));
      writeMap(std::string(qs) + "_" + type, cellQuantile(ptrs[type], q),
               num(q * 100) + " % quantile of " + title(type), unit(type), std::string(qs) + "_" + type, 0,
               chart::Ramp::Viridis);
    }
  }

  // Outcomes per member; the run-out along the path by AIMEC's criterion.
  std::unique_ptr<aimec::Transform> tr;
  if (set.path.size() >= 2)
    tr = std::make_unique<aimec::Transform>(aimec::makeTransform(Polyline(set.path), set.domainWidth, grid.cellSize,
                                                                 ground.get()));
  const double pftLimit = set.thresholds.count("pft") && !set.thresholds.at("pft").empty() ? set.thresholds.at("pft")[0] : 0.1;
  std::vector<double> reachedCount(tr ? tr->ns : 0, 0.0);
  for (size_t k = 0; k < done.size(); ++k) {
    MemberOutcome& o = rep.members[done[k]];
    auto maxOf = [](const DemRaster& r) {
      double m = NAN;
      for (float v : r.height)
        if (std::isfinite(v) && !(m >= v)) m = v;
      return m;
    };
    o.maxPft = maxOf(rasters["pft"][k]), o.maxPfv = maxOf(rasters["pfv"][k]), o.maxPpr = maxOf(rasters["ppr"][k]);
    o.areaPft = 0;
    for (float v : rasters["pft"][k].height) o.areaPft += v > pftLimit ? grid.cellSize * grid.cellSize : 0.0;
    if (tr) {
      const aimec::PathStats ps = aimec::analyse(*tr, aimec::resample(*tr, rasters[set.runoutResult][k]), set.runoutThreshold);
      o.runout = ps.sRunout, o.runoutX = ps.xRunout, o.runoutY = ps.yRunout;
      for (size_t i = 0; i < tr->ns; ++i) reachedCount[i] += ps.crossMax[i] > set.runoutThreshold;
    }
  }

  {
    std::ofstream csv(dir / "members.csv");
    csv << "member";
    for (const auto& v : plan.vary) csv << "," << v.key;
    csv << ",status,wall_s,runout_m,runout_x,runout_y,max_pft_m,max_pfv_m_s,max_ppr_kPa,area_pft_gt_" << num(pftLimit)
        << "_m2\n";
    for (size_t m = 0; m < plan.members(); ++m) {
      const MemberOutcome& o = rep.members[m];
      csv << memberName(m);
      for (const auto& v : plan.values[m]) csv << "," << v;
      csv << "," << (o.completed ? "completed" : "failed") << "," << num(o.wallSeconds, "%.1f") << ","
          << num(o.runout, "%.1f") << "," << num(o.runoutX, "%.2f") << "," << num(o.runoutY, "%.2f") << ","
          << num(o.maxPft, "%.4g") << "," << num(o.maxPfv, "%.4g") << "," << num(o.maxPpr, "%.4g") << ","
          << num(o.areaPft, "%.0f") << "\n";
    }
    rep.files.push_back("members.csv");
  }
  if (tr) {
    // P(the flow reaches s), and P(run-out beyond s) from the members' run-out points.
    std::vector<double> reached, beyond;
    for (size_t i = 0; i < tr->ns; ++i) {
      reached.push_back(reachedCount[i] / double(done.size()));
      size_t n = 0;
      for (size_t m : done) n += rep.members[m].runout > tr->s[i];
      beyond.push_back(double(n) / double(done.size()));
    }
    std::ofstream csv(dir / "runout.csv");
    csv << "s_m,p_reached,p_runout_beyond\n";
    for (size_t i = 0; i < tr->ns; ++i) csv << num(tr->s[i], "%.2f") << "," << num(reached[i]) << "," << num(beyond[i]) << "\n";
    const std::string crit = std::string(set.runoutResult) + " > " + num(set.runoutThreshold) + " " + unit(set.runoutResult);
    writeLineChart((dir / "runout.png").string(), "Run-out along the path (" + crit + ", " + std::to_string(done.size()) + " members)",
                   "distance along the path s (m)", "probability",
                   tr->s, {{"reached at s", reached, false}, {"run-out beyond s", beyond, true}});
    rep.files.push_back("runout.csv");
    rep.files.push_back("runout.png");
  }
  if (plan.method == Method::Morris) {
    std::ofstream csv(dir / "morris.csv");
    csv << "outcome,parameter,mu_star,mu,sigma,effects\n";
    auto write = [&](const std::string& name, double MemberOutcome::*field) {
      std::vector<double> y;
      for (const auto& o : rep.members) y.push_back(o.completed ? o.*field : NAN);
      for (const auto& e : morrisEffects(plan, y))
        csv << name << "," << e.key << "," << num(e.muStar, "%.6g") << "," << num(e.mu, "%.6g") << ","
            << num(e.sigma, "%.6g") << "," << e.effects << "\n";
    };
    if (tr) write("runout_m", &MemberOutcome::runout);
    write("max_pft_m", &MemberOutcome::maxPft);
    write("max_ppr_kPa", &MemberOutcome::maxPpr);
    write("area_pft_m2", &MemberOutcome::areaPft);
    rep.files.push_back("morris.csv");
  }
  // The ensemble on one page: members, screening, maps and run-out.
  writeEnsembleReport(dir.string(), rep.files);
  rep.files.push_back("report.html");
  return rep;
}

} // namespace talus::ensemble
