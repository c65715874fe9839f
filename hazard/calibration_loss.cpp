#include "hazard/calibration_loss.h"

#include "hazard/ensemble_aggregate.h"
#include "io/common/input_error.h"
#include "io/terrain/dem_raster.h"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace talus::calibration {

namespace {

const char* kindName(ObservedKind k) {
  return k == ObservedKind::Footprint ? "footprint" : k == ObservedKind::Runout ? "runout" : "raster";
}

DemRaster readKeepingNodata(const std::string& file) {
  DemReadOptions opt;
  opt.keepNodata = true;
  return readDem(file, opt);
}

/// A footprint given as a raster (another model's peak field) rather than a polygon file.
bool isRaster(const std::string& file) {
  const auto dot = file.rfind('.');
  const std::string ext = dot == std::string::npos ? "" : file.substr(dot);
  return ext == ".asc" || ext == ".tif" || ext == ".tiff";
}

std::string number(double v) {
  if (!std::isfinite(v)) return "nan";
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

} // namespace

Observation parseObservation(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq + 1 == text.size())
    throw InputError("--observed", 0, text, "expected footprint=FILE, runout=X,Y or raster=FILE");
  Observation o;
  o.text = text;
  const std::string kind = text.substr(0, eq), value = text.substr(eq + 1);
  if (kind == "footprint" || kind == "raster") {
    o.kind = kind == "footprint" ? ObservedKind::Footprint : ObservedKind::Raster;
    o.file = value;
    return o;
  }
  if (kind != "runout") throw InputError("--observed", 0, text, "'" + kind + "' is not one of: footprint, runout, raster");
  o.kind = ObservedKind::Runout;
  char tail = 0;
  if (std::sscanf(value.c_str(), "%lf,%lf%c", &o.point.x(), &o.point.y(), &tail) != 2 || !o.point.allFinite())
    throw InputError("--observed", 0, text, "expected runout=X,Y (world coordinates of the observed run-out point)");
  return o;
}

void applyWeight(std::vector<Observation>& observations, const std::string& text) {
  const auto eq = text.find('=');
  char* end = nullptr;
  const double w = eq == std::string::npos ? NAN : std::strtod(text.c_str() + eq + 1, &end);
  if (!(w >= 0) || !std::isfinite(w) || (end && *end))
    throw InputError("--weight", 0, text, "expected KIND=W with W >= 0 (KIND footprint, runout or raster)");
  bool found = false;
  for (auto& o : observations)
    if (text.compare(0, eq, kindName(o.kind)) == 0 && std::string(kindName(o.kind)).size() == eq) o.weight = w, found = true;
  if (!found) throw InputError("--weight", 0, text, "no --observed of that kind");
}

ObservedEvent::ObservedEvent(std::vector<Observation> observations, const EnsembleSettings& settings,
                             std::string rasterResult, std::shared_ptr<const DemRaster> ground)
    : observations_(std::move(observations)), settings_(settings), rasterResult_(std::move(rasterResult)),
      ground_(std::move(ground)) {
  if (observations_.empty()) throw InputError("--observed", "give at least one observation of the event");
  if (settings_.path.size() < 2)
    throw InputError("[ensemble] path", "calibration compares runs with the event along AIMEC's path grid: give "
                                        "[ensemble] path (or an [[output.paths]] line, or an AvaFrame folder's path)");
  if (rasterResult_.empty()) rasterResult_ = settings_.runoutResult;
  for (const auto& o : observations_) {
    if (o.kind == ObservedKind::Footprint && isRaster(o.file)) footprintRasters_.push_back(readKeepingNodata(o.file));
    else if (o.kind == ObservedKind::Footprint) polygons_.push_back(PolygonSet::read(o.file));
    if (o.kind == ObservedKind::Raster) {
      if (rasterFile_) throw InputError("--observed", 0, o.text, "one raster observation at most");
      rasterFile_ = std::make_unique<DemRaster>(readKeepingNodata(o.file));
    }
    if (o.kind == ObservedKind::Runout) {
      if (std::isfinite(sObserved_)) throw InputError("--observed", 0, o.text, "one run-out observation at most");
      bool beyond = false;
      sObserved_ = Polyline(settings_.path).project(o.point, nullptr, &beyond);
      if (beyond || !(sObserved_ > 0))
        throw InputError("--observed", 0, o.text, "the point does not project onto the path (beyond its ends)");
    }
  }
}

bool ObservedEvent::has(ObservedKind k) const {
  for (const auto& o : observations_)
    if (o.kind == k) return true;
  return false;
}

void ObservedEvent::prepare(double cellSize) {
  if (transform_) return;
  transform_ = std::make_unique<aimec::Transform>(
      aimec::makeTransform(Polyline(settings_.path), settings_.domainWidth, cellSize, ground_.get()));
  const aimec::Transform& t = *transform_;
  if (!polygons_.empty() || !footprintRasters_.empty()) {
    footprint_.assign(t.x.size(), 0.0f);
    for (size_t p = 0; p < t.x.size(); ++p)
      for (const auto& poly : polygons_)
        if (poly.contains(t.x[p], t.y[p])) footprint_[p] = 1.0f;
    for (const auto& r : footprintRasters_) {
      const std::vector<float> v = aimec::resample(t, r);
      for (size_t p = 0; p < t.x.size(); ++p)
        if (v[p] > settings_.runoutThreshold) footprint_[p] = 1.0f;
    }
  }
  if (rasterFile_) raster_ = aimec::resample(t, *rasterFile_);
}

std::vector<float> ObservedEvent::runField(const std::string& runDir, const std::string& type) {
  const std::string f = ensemble::findPeakFile(runDir, type);
  if (f.empty()) return {};
  const DemRaster raster = readKeepingNodata(f);
  prepare(raster.grid.cellSize); // the first run read fixes the path grid
  std::vector<float> v = aimec::resample(*transform_, raster);
  for (auto& x : v) x = std::isfinite(x) ? x : 0.0f; // AIMEC: no data on the run's side = not reached
  return v;
}

std::vector<float> ObservedEvent::footprintOf(const std::vector<float>& run) const {
  std::vector<float> indicator(run.size());
  for (size_t p = 0; p < run.size(); ++p) indicator[p] = run[p] > settings_.runoutThreshold ? 1.0f : 0.0f;
  return indicator;
}

LossTerms ObservedEvent::evaluate(const std::string& runDir) {
  LossTerms out;
  const std::vector<float> run = runField(runDir, settings_.runoutResult);
  if (run.empty()) return out;
  const aimec::Transform& t = *transform_;
  double total = 0;
  for (const auto& o : observations_) {
    if (o.kind == ObservedKind::Footprint) {
      const aimec::AreaComparison c = aimec::compareAreas(t, footprintOf(run), footprint_, 0.5);
      out.footprintFP = c.alphaFP, out.footprintFN = c.alphaFN;
      total += o.weight * (c.alphaFP + c.alphaFN);
    } else if (o.kind == ObservedKind::Runout) {
      const aimec::PathStats ps = aimec::analyse(t, run, settings_.runoutThreshold);
      out.runoutObserved = sObserved_;
      out.runoutRun = ps.sRunout;
      out.runout = ps.found ? std::abs(ps.sRunout - sObserved_) / sObserved_ : 1.0;
      total += o.weight * out.runout;
    } else {
      const std::vector<float> field = rasterResult_ == settings_.runoutResult ? run : runField(runDir, rasterResult_);
      if (field.empty()) return out;
      const aimec::AreaComparison c = aimec::compareAreas(t, field, raster_, settings_.runoutThreshold);
      double sq = 0, unionArea = 0, obsSum = 0, obsArea = 0;
      for (size_t p = 0; p < field.size(); ++p) {
        if (!std::isfinite(raster_[p])) continue;
        const bool s = field[p] > settings_.runoutThreshold, r = raster_[p] > settings_.runoutThreshold;
        if (s || r) sq += t.area[p] * std::pow(double(field[p]) - raster_[p], 2), unionArea += t.area[p];
        if (r) obsSum += t.area[p] * raster_[p], obsArea += t.area[p];
      }
      out.rasterFP = c.alphaFP, out.rasterFN = c.alphaFN;
      out.rasterMisfit = obsArea > 0 && unionArea > 0 ? std::sqrt(sq / unionArea) / (obsSum / obsArea) : NAN;
      total += o.weight * (c.alphaFP + c.alphaFN + out.rasterMisfit);
    }
  }
  out.total = total;
  return out;
}

std::string ObservedEvent::csvHeader() const {
  std::string h;
  if (has(ObservedKind::Footprint)) h += "footprint_fp,footprint_fn,";
  if (has(ObservedKind::Runout)) h += "runout_run_m,runout_observed_m,runout_error,";
  if (has(ObservedKind::Raster)) h += "raster_fp,raster_fn,raster_misfit,";
  return h + "loss";
}

std::string ObservedEvent::csvValues(const LossTerms& v) const {
  std::ostringstream s;
  if (has(ObservedKind::Footprint)) s << number(v.footprintFP) << ',' << number(v.footprintFN) << ',';
  if (has(ObservedKind::Runout))
    s << number(v.runoutRun) << ',' << number(v.runoutObserved) << ',' << number(v.runout) << ',';
  if (has(ObservedKind::Raster)) s << number(v.rasterFP) << ',' << number(v.rasterFN) << ',' << number(v.rasterMisfit) << ',';
  s << number(v.total);
  return s.str();
}

std::vector<uint8_t> ObservedEvent::classes(const std::string& runDir) {
  if (!transform_ || (footprint_.empty() && raster_.empty())) return {};
  const std::vector<float> run = runField(runDir, footprint_.empty() ? rasterResult_ : settings_.runoutResult);
  if (run.empty()) return {};
  if (!footprint_.empty()) {
    return aimec::compareAreas(*transform_, footprintOf(run), footprint_, 0.5).classes;
  }
  return aimec::compareAreas(*transform_, run, raster_, settings_.runoutThreshold).classes;
}

} // namespace talus::calibration
