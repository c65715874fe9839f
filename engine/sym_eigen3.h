// Eigen-decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations.
//
// For the b = F F^T of an MPM particle (close to a multiple of the identity, or a rotation of a
// moderately stretched diagonal), two or three sweeps reach machine precision; that is several
// times cheaper than a closed-form solver (acos/cos/sin per call) and, unlike the closed form,
// accurate for nearly equal eigenvalues.
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace talus {

/// S = V diag(lambda) V^T with V a rotation. Columns of V are unit eigenvectors (unsorted).
inline void symmetricEigen3(const Eigen::Matrix3d& S0, Eigen::Vector3d& lambda, Eigen::Matrix3d& V) {
  double a00 = S0(0, 0), a11 = S0(1, 1), a22 = S0(2, 2);
  double a01 = 0.5 * (S0(0, 1) + S0(1, 0)), a02 = 0.5 * (S0(0, 2) + S0(2, 0)), a12 = 0.5 * (S0(1, 2) + S0(2, 1));
  V.setIdentity();
  const double scale = std::abs(a00) + std::abs(a11) + std::abs(a22) + 1e-300;
  // One rotation in the (p, q) plane zeroing a_pq; r is the third index.
  auto rotate = [&](double& app, double& aqq, double& apq, double& apr, double& aqr, int p, int q) {
    if (std::abs(apq) <= 1e-300) return;
    const double tau = (aqq - app) / (2 * apq);
    const double t = (tau >= 0 ? 1.0 : -1.0) / (std::abs(tau) + std::sqrt(1 + tau * tau));
    const double c = 1 / std::sqrt(1 + t * t), s = t * c;
    app -= t * apq;
    aqq += t * apq;
    apq = 0;
    const double pr = apr, qr = aqr;
    apr = c * pr - s * qr;
    aqr = s * pr + c * qr;
    for (int k = 0; k < 3; ++k) {
      const double vp = V(k, p), vq = V(k, q);
      V(k, p) = c * vp - s * vq;
      V(k, q) = s * vp + c * vq;
    }
  };
  for (int sweep = 0; sweep < 10; ++sweep) {
    if (!(std::abs(a01) + std::abs(a02) + std::abs(a12) > 1e-16 * scale)) break; // also stops on NaN
    rotate(a00, a11, a01, a02, a12, 0, 1);
    rotate(a00, a22, a02, a01, a12, 0, 2);
    rotate(a11, a22, a12, a01, a02, 1, 2);
  }
  lambda = Eigen::Vector3d(a00, a11, a22);
}

} // namespace talus
