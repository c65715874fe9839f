// The state behind HazardMaps (io/output/hazard_maps.h), shared by its accumulation
// (hazard_maps.cpp) and its files (hazard_map_files.cpp). Private to those two files.
#pragma once

#include "io/output/hazard_maps.h"

#include <array>
#include <limits>
#include <string>
#include <vector>

namespace talus {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr int kMaxima = 4; // MaxHeightVertical .. MaxPressure
constexpr int kSums = 4;   // per cell during a step: volume, mass, mass*speed, mass*speed^2

/// One particle's bilinear splat: first column, offsets in cells, and the summed quantities in
/// units of 2^unit[k] (exactly scaled floats; each cell sums them as rounded integers).
struct Splat {
  int32_t col;
  float tx, ty;
  float q[kSums];
};

struct HazardMaps::Impl {
  RasterGrid window; ///< the part of the grid the domain covers (same cells, shifted origin)
  int c0 = 0, r0 = 0;
  size_t cells = 0;
  int layers = 1; ///< 0 = all material, 1 + i = material group i
  std::vector<std::string> layerMaterial;
  std::vector<std::vector<float>> maxima;  ///< [layer][q * cells + cell]
  std::vector<std::vector<int64_t>> sums;  ///< [layer][kSums * cell + k], in units of 2^unit[k];
                                           ///< with materials' layers, layer 0 only at the fold
  int firstLayer() const { return layers > 1 ? 1 : 0; } ///< the first layer summed and sent
  int unit[kSums] = {0, 0, 0, 0};          ///< this accumulation's unit exponents (from PartBounds)
  std::vector<uint32_t> touched;           ///< cells with sums, in band order
  std::vector<std::vector<uint32_t>> bandTouched; ///< scratch: per band of rows
  std::vector<std::vector<float>> deposit, erosion, initial, start; ///< [layer][cell]; initial: erodible only
  std::vector<uint8_t> erodibleGroup;
  std::vector<float> cosSlope; ///< NaN until known
  bool slopeKnown = false;     ///< cosSlope is whole from the start (a DEM, or no terrain)
  /// cosSlope of every cell from the DEM's heights on `grid` (the map grid).
  void slopeFromDem(const RasterGrid& grid, const DemRaster& dem);
  std::vector<uint8_t> mark; ///< cell has sums this accumulation
  std::vector<std::vector<uint32_t>> rowStart; ///< per group: first splat of each first splat row
  std::vector<std::vector<Splat>> splats;      ///< per group: splats by first row, particle order within a row
  std::vector<int32_t> rowOf;                  ///< scratch: first splat row + 1 per particle, -1 outside
  double a = 1, bx = 0, by = 0; ///< window cell coordinates: fx = a x + bx, fy = -a y + by (local x, y)
  double lastTime = -std::numeric_limits<double>::infinity();
  int animationNext = 0;                         ///< index of the next animation frame (rank 0)
  int self = 0;              ///< this process's rank (partByOwner); 0 in one process
  bool framePending = false; ///< this accumulation records a film frame (resultDue)
  bool frameDue = false;     ///< rank 0: the frame partDue found due, for its parts to the others
  std::vector<float> frameThickness, frameSpeed; ///< that frame's rasters while it is recorded
  /// The film's frames this process wrote, numbered from 0 without a gap (else filmKnown is
  /// false: a resumed run, a skipped frame), and their largest values, for the film's scale.
  int filmFrames = 0;
  bool filmKnown = true;
  std::array<float, 2> filmLargest{};
  double endTime = 0;
  std::shared_ptr<const Sdf> terrain;
  Vec3d origin = Vec3d::Zero();
  double zLo = 0, zHi = 0, dx = 1;

  /// The units of the next sums, from every process's maxima.
  void setUnits(const Simulation& sim, const PartBounds& b);
  /// The splats of the particles of the groups in `use`, sorted by the map row they start in
  /// (see accumulate). Stored in that order, not per particle: the sums then read them in
  /// sequence (a gather through a particle index missed the cache on most of them).
  /// Only particles at least `minSpeed` fast (m/s) are splatted when it is positive.
  void binSplats(const Simulation& sim, const std::vector<uint8_t>& use, float minSpeed = 0);
  /// The sums of `local`'s particles in the units of `b` (setUnits, binSplats, sumBands).
  void sumOwn(const Simulation& local, const PartBounds& b, float minSpeed);
  /// Adds the binned splats into `sums` (bands of rows in parallel; integer sums, so exact in
  /// any order) and lists the cells touched in `touched`.
  void sumBands(const Simulation& sim, const std::vector<uint8_t>& use);
  /// The touched cells' sums as parts by owner (OutputObserver::ownerOfRow): outs[r] gets those
  /// of the cells rank r of `ranks` owns (their indices, then kSums * layers integers each), and
  /// clears them; those `self` owns stay in place and in `touched` (self -1: none).
  void writeTouched(std::vector<char>* outs, int ranks, int self);
  /// Adds a part's cells into `sums` and `touched`.
  /// @throw std::runtime_error if the part does not hold whole cells of this map
  void addPart(std::string_view part);
  /// Calls fold(cell, s) for every touched cell, in parallel, with s[l * kSums + k] its
  /// quantity k of layer l as a float; then clears the sums.
  template <class Fold> void foldTouched(Fold&& fold);

  /// Volume thickness (m) per cell of the groups selected by `use`, into layer 0 and per material.
  void thickness(const Simulation& sim, const std::vector<uint8_t>& use, std::vector<std::vector<float>>& out);

  /// cos(slope) of the terrain SDF under a cell: the ground is found by bisection on the
  /// signed distance along the vertical, the normal by central differences there.
  float terrainCos(uint32_t cell) const {
    if (!terrain) return 1.f;
    const int c = int(cell % uint32_t(window.nx)), r = int(cell / uint32_t(window.nx));
    const double x = window.cellCentreX(c) - origin.x(), y = window.cellCentreY(r) - origin.y();
    auto phi = [&](double px, double py, double pz) { return terrain->distance(Vec3d(px, py, pz)); };
    double lo = zLo, hi = zHi;
    if (!(phi(x, y, lo) < 0 && phi(x, y, hi) > 0)) return 1.f; // no ground crossing in this column
    for (int i = 0; i < 48 && hi - lo > 1e-4 * dx; ++i) {
      const double mid = 0.5 * (lo + hi);
      (phi(x, y, mid) < 0 ? lo : hi) = mid;
    }
    const double z = 0.5 * (lo + hi), e = 0.5 * dx;
    const Vec3d g((phi(x + e, y, z) - phi(x - e, y, z)) / (2 * e), (phi(x, y + e, z) - phi(x, y - e, z)) / (2 * e),
                  (phi(x, y, z + e) - phi(x, y, z - e)) / (2 * e));
    const double n = g.norm();
    return n > 1e-9 ? float(std::abs(g.z()) / n) : 1.f;
  }

  float cosAt(uint32_t cell) {
    float& c = cosSlope[cell];
    if (std::isnan(c)) c = terrainCos(cell);
    return c;
  }
};

} // namespace talus
