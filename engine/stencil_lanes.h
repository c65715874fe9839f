// The 27-node loops of P2G and G2P with a stencil row (3 nodes of 4 floats: mass and momentum or
// velocity, contiguous in the padded block buffer) in SIMD lanes: 12 floats, one AVX-512 vector,
// an AVX2 vector and a half, or three SSE4 vectors. Google Highway picks the target at run time.
//
// Each float lane does the same IEEE operations in the same order on every target (no fused
// multiply-adds: engine/CMakeLists.txt), so the results are the same bits on each. Particles are
// taken one after the other, in order, so P2G's sums into a node keep their order.
#pragma once

#include <cstdint>
#include <vector>

namespace talus {

/// Particles per call: those of one G2P chunk (engine/transfer_g2p.h).
constexpr int kStencilLanes = 16;

/// The stencils of up to kStencilLanes particles in a padded buffer (engine/padded_block.h).
struct StencilRows {
  int32_t first[kStencilLanes];  ///< padIndex of the stencil's first node (i, j, k = 0)
  float w[kStencilLanes][3][3];  ///< quadratic B-spline weights per axis and node
};

/// G2P's sums for one particle, over its 3 x 3 rows, as 12 floats (3 nodes of 4 channels):
/// `all` = sum w v, `alongI` = sum i w v, `alongJ` = sum j w v, i and j the row's offsets.
/// The caller folds the three nodes: v = all_0 + all_1 + all_2, the k-moment all_1 + 2 all_2.
struct GatheredRows {
  alignas(64) float all[kStencilLanes][16];
  alignas(64) float alongI[kStencilLanes][16];
  alignas(64) float alongJ[kStencilLanes][16];
};

/// G2P: the weighted sums of `nodes` (a padded buffer of (mass, velocity) records, as floats)
/// over the stencils of particles [0, n) of `s`.
void gatherRows(const float* nodes, const StencilRows& s, int n, GatheredRows& out);

/// P2G's momentum rows of one particle: node (i, j, k) of its stencil receives
/// (w_i w_j) w_k (((q0 + i a0) + j a1) + k a2), as the scalar scatter forms it; each a 4-float
/// (mass, momentum) record.
struct ScatteredRows {
  alignas(16) float q0[kStencilLanes][4];
  alignas(16) float a0[kStencilLanes][4];
  alignas(16) float a1[kStencilLanes][4];
  alignas(16) float a2[kStencilLanes][4];
};

/// P2G: adds particles [0, n) of `s` and `q`, in order, into `buf` (a padded buffer of
/// (mass, momentum) records, as floats).
void scatterRows(float* buf, const StencilRows& s, const ScatteredRows& q, int n);

/// The name of the Highway target the SIMD kernels (these and materials/solid_lanes.h) run on:
/// "AVX3" (AVX-512), "AVX2", "SSE4", "SSSE3" or the portable "SCALAR".
const char* simdTargetName();

/// For tests: the targets compiled in that this machine runs (Highway's target bits), and a way to
/// make every kernel run on one of them (0 restores the best).
std::vector<int64_t> simdTargets();
void useSimdTarget(int64_t target);

} // namespace talus
