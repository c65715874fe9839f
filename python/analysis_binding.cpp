// The analyses of a run's outputs as Python functions: maps with their georeference, series,
// `talus map-stats`, `talus compare` and AIMEC's path analysis (hazard/aimec.h).
#include "python/bindings.h"

#include "hazard/aimec.h"
#include "tools/analysis.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>

namespace py = pybind11;

namespace talus::python {

namespace {

using Path = std::filesystem::path;
using namespace talus::analysis;

/// A raster as a dict: values (rows north to south, NaN for no data), GDAL's geotransform, CRS.
py::dict mapDict(const DemRaster& r) {
  py::array_t<float> values({py::ssize_t(r.grid.ny), py::ssize_t(r.grid.nx)});
  std::copy(r.height.begin(), r.height.end(), values.mutable_data());
  py::dict d;
  d["values"] = values;
  d["geotransform"] = py::make_tuple(r.grid.originX, r.grid.cellSize, 0.0, r.grid.originY, 0.0, -r.grid.cellSize);
  d["crs"] = r.grid.crsWkt;
  d["cell_size"] = r.grid.cellSize;
  d["path"] = r.sourcePath;
  return d;
}

py::dict statsDict(const MapStats& s) {
  py::dict d;
  d["threshold"] = s.threshold, d["cells"] = s.cells, d["area"] = s.area, d["max"] = s.max, d["mean"] = s.mean;
  d["volume"] = s.volume, d["runout"] = s.runout, d["runout_x"] = s.runoutX, d["runout_y"] = s.runoutY;
  return d;
}

/// A path as a line file GDAL reads (AvaFrame's LINES/path_aimec.shp), "x,y x,y ..." text, or
/// points [(x, y), ...].
Polyline polylineOf(const py::object& path) {
  if (py::isinstance<py::str>(path) || py::hasattr(path, "__fspath__"))
    return Polyline::parse(py::str(py::module_::import("os").attr("fspath")(path)).cast<std::string>());
  std::vector<Eigen::Vector2d> p;
  for (const auto& q : path.cast<std::vector<std::array<double, 2>>>()) p.emplace_back(q[0], q[1]);
  if (p.size() < 2) throw py::value_error("a path needs at least two points");
  return Polyline(std::move(p));
}

py::dict seriesDict(const Path& path) {
  const SeriesTable t = readSeries(path.string());
  py::dict d;
  for (size_t c = 0; c < t.header.size(); ++c) {
    py::array_t<double> col(py::ssize_t(t.rows.size()));
    auto m = col.mutable_unchecked<1>();
    for (size_t r = 0; r < t.rows.size(); ++r) m(py::ssize_t(r)) = c < t.rows[r].size() ? t.rows[r][c] : NAN;
    d[py::str(t.header[c])] = col;
  }
  return d;
}

py::dict compareDict(const Path& sim, const Path& ref, double threshold) {
  const DemRaster r = readRaster(ref.string());
  const Comparison c = compare(resample(readRaster(sim.string()), r.grid), r, threshold);
  py::dict d;
  d["threshold"] = c.threshold, d["simulation"] = statsDict(c.sim), d["reference"] = statsDict(c.ref);
  d["area_both"] = c.areaBoth, d["area_simulation_only"] = c.areaSimOnly, d["area_reference_only"] = c.areaRefOnly;
  d["overlap"] = c.overlap, d["bias"] = c.bias, d["rmse"] = c.rmse;
  return d;
}

/// AIMEC along `path`: the simulation's run-out and its areas against the reference's, both
/// resampled on the path's (s, l) grid at the reference's cell size.
py::dict aimecDict(const Path& sim, const Path& ref, const py::object& path,
                   double threshold, double width, const std::optional<Path>& dem) {
  const DemRaster r = readRaster(ref.string()), s = readRaster(sim.string());
  std::optional<DemRaster> ground;
  if (dem) ground = readRaster(dem->string());
  const aimec::Transform t = aimec::makeTransform(polylineOf(path), width, r.grid.cellSize, ground ? &*ground : nullptr);
  const std::vector<float> fs = aimec::resample(t, s), fr = aimec::resample(t, r);
  const aimec::PathStats ps = aimec::analyse(t, fs, threshold), pr = aimec::analyse(t, fr, threshold);
  const aimec::AreaComparison a = aimec::compareAreas(t, fs, fr, threshold);
  py::dict d;
  d["threshold"] = threshold;
  d["s_runout"] = ps.sRunout, d["s_runout_reference"] = pr.sRunout, d["runout_difference"] = a.runoutDifference;
  d["runout_angle"] = ps.runoutAngle, d["max_along_path"] = ps.mma, d["mean_along_path"] = ps.ama;
  d["true_positive_area"] = a.tp, d["false_positive_area"] = a.fp, d["false_negative_area"] = a.fn;
  d["alpha_tp"] = a.alphaTP, d["alpha_fp"] = a.alphaFP, d["alpha_fn"] = a.alphaFN;
  d["s"] = t.s;
  d["cross_max"] = ps.crossMax;
  d["cross_max_reference"] = pr.crossMax;
  return d;
}

} // namespace

void registerAnalysis(py::module_& m) {
  m.def("read_map", [](const Path& p) { return mapDict(readRaster(p.string())); }, py::arg("path"),
        "A map (GeoTIFF or ESRI ASCII grid) as {'values', 'geotransform', 'crs', 'cell_size', 'path'}.");
  m.def("read_series", &seriesDict, py::arg("path"), "series.csv as {column: array}.");
  m.def("map_stats", [](const Path& p, double threshold) { return statsDict(mapStats(readRaster(p.string()), threshold)); },
        py::arg("path"), py::arg("threshold") = 0.0, "`talus map-stats`: cells, area, max, mean, volume at a threshold.");
  m.def("compare", &compareDict, py::arg("simulation"), py::arg("reference"), py::arg("threshold") = 1.0,
        "`talus compare`: a map against a reference on the reference's grid (areas, overlap, bias, rmse).");
  m.def("aimec", &aimecDict, py::arg("simulation"), py::arg("reference"), py::arg("path"), py::arg("threshold") = 1.0,
        py::arg("width") = 600.0, py::arg("dem") = py::none(),
        "AIMEC along `path` (a line file, \"x,y x,y\" text or [(x, y), ...]): run-out (s), its difference, areas and alphas, cross-section maxima.");
}

} // namespace talus::python
