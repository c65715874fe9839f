// Signed singular value decomposition of a 3x3 matrix, F = U diag(s) V^T with U, V rotations.
//
// Jacobi eigen-sweeps on F^T F give V; a Givens QR of F V then gives U and the singular values.
// Taking the singular values from the QR (not from the eigenvalues of F^T F) keeps small ones
// accurate. s is sorted by decreasing magnitude and only s[2] can be negative: that is how an
// inverted F (det F < 0) shows up, which is what MPM plasticity and clamping want.
#pragma once

#include <Eigen/Dense>
#include <cmath>

namespace talus {

struct Svd3 {
  Eigen::Matrix3d U, V;
  Eigen::Vector3d s;
};

namespace detail {

// Rotate columns p, q of S (symmetric) and of V to zero S(p, q).
inline void jacobiRotate(Eigen::Matrix3d& S, Eigen::Matrix3d& V, int p, int q) {
  const double apq = S(p, q);
  if (std::abs(apq) < 1e-300) return;
  const double tau = (S(q, q) - S(p, p)) / (2.0 * apq);
  const double t = (tau >= 0 ? 1.0 : -1.0) / (std::abs(tau) + std::sqrt(1.0 + tau * tau));
  const double c = 1.0 / std::sqrt(1.0 + t * t), s = t * c;
  for (int k = 0; k < 3; ++k) { // S <- S J
    const double skp = S(k, p), skq = S(k, q);
    S(k, p) = c * skp - s * skq;
    S(k, q) = s * skp + c * skq;
  }
  for (int k = 0; k < 3; ++k) { // S <- J^T S
    const double spk = S(p, k), sqk = S(q, k);
    S(p, k) = c * spk - s * sqk;
    S(q, k) = s * spk + c * sqk;
  }
  for (int k = 0; k < 3; ++k) {
    const double vkp = V(k, p), vkq = V(k, q);
    V(k, p) = c * vkp - s * vkq;
    V(k, q) = s * vkp + c * vkq;
  }
}

// Givens rotation on rows p, q of B zeroing B(q, col); accumulates Q so that B_orig = Q B.
inline void givensZero(Eigen::Matrix3d& B, Eigen::Matrix3d& Q, int p, int q, int col) {
  const double a = B(p, col), b = B(q, col);
  const double r = std::hypot(a, b);
  if (r < 1e-300) return;
  const double c = a / r, s = b / r;
  for (int k = 0; k < 3; ++k) {
    const double bp = B(p, k), bq = B(q, k);
    B(p, k) = c * bp + s * bq;
    B(q, k) = -s * bp + c * bq;
  }
  for (int k = 0; k < 3; ++k) {
    const double qp = Q(k, p), qq = Q(k, q);
    Q(k, p) = c * qp + s * qq;
    Q(k, q) = -s * qp + c * qq;
  }
}

} // namespace detail

inline Svd3 svd3(const Eigen::Matrix3d& F) {
  Eigen::Matrix3d S = F.transpose() * F;
  Eigen::Matrix3d V = Eigen::Matrix3d::Identity();
  const double scale = S.trace();
  for (int sweep = 0; sweep < 12; ++sweep) {
    const double off = std::abs(S(0, 1)) + std::abs(S(0, 2)) + std::abs(S(1, 2));
    if (!(off > 1e-17 * scale)) break; // also exits on NaN
    detail::jacobiRotate(S, V, 0, 1);
    detail::jacobiRotate(S, V, 0, 2);
    detail::jacobiRotate(S, V, 1, 2);
  }
  // Sort eigenvalues descending; each column swap flips det V, so negate one column to keep a rotation.
  Eigen::Vector3d e = S.diagonal();
  auto swapCols = [&](int a, int b) {
    std::swap(e(a), e(b));
    V.col(a).swap(V.col(b));
    V.col(b) = -V.col(b);
  };
  if (e(0) < e(1)) swapCols(0, 1);
  if (e(0) < e(2)) swapCols(0, 2);
  if (e(1) < e(2)) swapCols(1, 2);

  Eigen::Matrix3d B = F * V;
  Eigen::Matrix3d Q = Eigen::Matrix3d::Identity();
  detail::givensZero(B, Q, 0, 1, 0);
  detail::givensZero(B, Q, 0, 2, 0);
  detail::givensZero(B, Q, 1, 2, 1);
  // Make the first two diagonal entries non-negative by flipping matching columns of U and V
  // in pairs with the last one, so U and V stay rotations.
  Svd3 r;
  r.U = Q;
  r.V = V;
  r.s = B.diagonal();
  for (int i = 0; i < 2; ++i) {
    if (r.s(i) < 0) {
      r.s(i) = -r.s(i);
      r.s(2) = -r.s(2);
      r.U.col(i) = -r.U.col(i);
      r.U.col(2) = -r.U.col(2);
    }
  }
  return r;
}

} // namespace talus
