// Basic numeric types shared by the whole engine.
#pragma once

#include <Eigen/Dense>
#include <cstdint>

namespace talus {

/// Storage precision of particle and grid data (float by default; -DTALUS_DOUBLE=ON for double).
/// Constitutive math (SVD, logarithms, return mappings) always runs in double: it is scalar code,
/// so double costs little there and keeps return mappings accurate to 1e-6.
#ifdef TALUS_DOUBLE
using Real = double;
#else
using Real = float;
#endif

using Vec3 = Eigen::Matrix<Real, 3, 1>;
using Mat3 = Eigen::Matrix<Real, 3, 3>;
using Vec3d = Eigen::Vector3d;
using Mat3d = Eigen::Matrix3d;
using Vec3i = Eigen::Vector3i;
/// Grid node record: (mass, momentum) during P2G, (mass, velocity) after the grid update.
using Vec4 = Eigen::Matrix<Real, 4, 1>;

/// Symmetric 3x3 tensor stored as its six independent components (xx, yy, zz, xy, xz, yz).
struct Sym3 {
  Real xx = 0, yy = 0, zz = 0, xy = 0, xz = 0, yz = 0;

  static Sym3 fromMatrix(const Mat3d& m) {
    Sym3 s;
    s.xx = Real(m(0, 0)); s.yy = Real(m(1, 1)); s.zz = Real(m(2, 2));
    s.xy = Real(0.5 * (m(0, 1) + m(1, 0)));
    s.xz = Real(0.5 * (m(0, 2) + m(2, 0)));
    s.yz = Real(0.5 * (m(1, 2) + m(2, 1)));
    return s;
  }
  Mat3 matrix() const {
    Mat3 m;
    m << xx, xy, xz, xy, yy, yz, xz, yz, zz;
    return m;
  }
  Real trace() const { return xx + yy + zz; }
};

/// Axis-aligned domain box in the local frame. Nodes on or beyond a face meet the face's collider
/// (when it has one); particles beyond a face are removed and their mass reported (at an open
/// face; half a cell beyond the first node row a closed face holds: engine/particle_cull.h).
struct DomainBox {
  Eigen::Vector3d min = Eigen::Vector3d::Zero(), max = Eigen::Vector3d::Ones();
};

/// Integer coordinate of an 8x8x8 block of grid nodes (node index >> 3).
struct BlockCoord {
  int32_t x = 0, y = 0, z = 0;
  bool operator==(const BlockCoord& o) const { return x == o.x && y == o.y && z == o.z; }
  bool operator!=(const BlockCoord& o) const { return !(*this == o); }
};

constexpr int kBlockLog2 = 3;              ///< 8 nodes per block edge, the OpenVDB leaf size
constexpr int kBlockDim = 1 << kBlockLog2; ///< nodes per block edge
constexpr int kBlockNodes = kBlockDim * kBlockDim * kBlockDim;

/// A block coordinate packed into 64 bits (21 bits per axis), as a hash-map key.
inline uint64_t blockKey(const BlockCoord& c) {
  return (uint64_t(uint32_t(c.x) & 0x1fffff) << 42) | (uint64_t(uint32_t(c.y) & 0x1fffff) << 21) |
         uint64_t(uint32_t(c.z) & 0x1fffff);
}

/// Linear index of node (i, j, k) inside a block, x-major like an OpenVDB leaf.
/// Key of a vertical column (i, j) of grid nodes or cells, for hash maps over plan positions.
inline constexpr uint64_t columnKey(int32_t i, int32_t j) { return (uint64_t(uint32_t(i)) << 32) | uint32_t(j); }

inline constexpr int blockNodeIndex(int i, int j, int k) {
  return (i << (2 * kBlockLog2)) | (j << kBlockLog2) | k;
}

} // namespace talus
