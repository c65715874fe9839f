// Modified Cam Clay for snow (Gaume et al. 2018; physics.md 4.2).
//
//   y(p, q) = q^2 (1 + 2 beta) + M^2 (p + beta p0)(p - p0)
//   p0 = K sinh(xi max(-eps_v, 0))       (eps_v: volumetric plastic Hencky strain)
//
// The surface is an ellipse in (p, q) centred at p0 (1 - beta)/2. The return is associative:
// the closest point on the ellipse in the elastic energy norm |dp|^2/K + |dq|^2/(3 mu), which
// in coordinates scaled by sqrt(K) and sqrt(3 mu) is the Euclidean closest point on an
// axis-aligned ellipse (a monotone 1-D root). Hardening is consistent: p0 is iterated with the
// plastic volume change until it stops moving, so the state lands on the updated ellipse
// (compaction grows p0, dilation shrinks it, down to zero: loose, cohesionless snow).
// After the first yield the critical-state slope is M_s instead of M, and the first plastic
// step already projects onto the M_s surface, so the mapping is idempotent.
#pragma once

#include "materials/hencky.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace talus {

struct CamClayParams {
  double M = 1.2;        ///< critical state slope before yield
  double Ms = 0.4;       ///< critical state slope after first yield
  double p0 = 175e3;     ///< initial pre-consolidation pressure (Pa)
  double beta = 0.4;     ///< tension / compression strength ratio
  double xi = 0.1;       ///< hardening factor
};

struct CamClayModel {
  static constexpr const char* kName = "cam_clay";
  /// eps_v (negative when compacted) and the first-yield flag in one float: eps_v rounded to a
  /// float whose last mantissa bit is the flag, so a particle takes 128 bytes (issue 36; a flag
  /// byte and its padding made 132). The flag costs eps_v at most one float ulp (1.2e-7 relative)
  /// where storing it as a float at all costs half of one.
  class State {
  public:
    float volumetricPlasticStrain() const { return value_; }
    bool yielded() const { return bits() & 1u; }
    void set(double epsV, bool yielded) {
      value_ = float(epsV);
      uint32_t b = bits();
      b = (b & ~1u) | uint32_t(yielded);
      std::memcpy(&value_, &b, sizeof b);
    }

  private:
    uint32_t bits() const {
      uint32_t b;
      std::memcpy(&b, &value_, sizeof b);
      return b;
    }
    float value_ = 0;
  };

  HenckyElasticity elastic;
  CamClayParams params;

  /// eps_v that gives the table's p0 (eq. 10 inverted): particles start there.
  double initialVolumetricStrain() const { return -std::asinh(params.p0 / elastic.bulk()) / params.xi; }
  double preconsolidation(double epsV) const { return preconsolidation(epsV, elastic.bulk()); }
  double preconsolidation(double epsV, double K) const { return K * std::sinh(params.xi * std::max(-epsV, 0.0)); }
  double slope(const State& s) const { return s.yielded() ? params.Ms : params.M; }

  double yield(double p, double q, double p0, double M) const {
    return q * q * (1 + 2 * params.beta) + M * M * (p + params.beta * p0) * (p - p0);
  }
  double yield(const Vec3d& eps, const State& s) const {
    const double tr = eps.sum();
    const double q = std::sqrt(1.5) * 2 * elastic.mu * (eps - Vec3d::Constant(tr / 3)).norm();
    return yield(-elastic.bulk() * tr, q, preconsolidation(s.volumetricPlasticStrain()), slope(s));
  }

  Vec3d stress(const Vec3d& eps, const State&) const { return elastic.stress(eps); }
  double waveSpeed(double rho) const { return elastic.waveSpeed(rho); }
  static std::vector<std::string> stateScalarNames() { return {"yielded", "volumetric_plastic_strain"}; }
  float stateScalar(const State& s, const Sym3&, size_t i) const {
    return i == 0 ? float(s.yielded()) : s.volumetricPlasticStrain();
  }

  /// Closest point (px, py) on the ellipse (x/A)^2 + (y/B)^2 = 1 to (x, y), x, y >= 0, outside.
  /// t is the root's parameter (below): on entry a guess (the last projection's, or 0 for
  /// none), on exit the root. `iterations`, if given, counts the Newton steps.
  static void closestOnEllipse(double x, double y, double A, double B, double& px, double& py, double& t,
                               int* iterations = nullptr) {
    // The closest point is (A^2 x / (t + A^2), B^2 y / (t + B^2)) at the root t >= 0 of
    // S(t) = (A x / (t + A^2))^2 + (B y / (t + B^2))^2 = 1 (Eberly). Newton runs on
    // g(t) = S^(-1/2) - 1: with u = 1/(t + alpha) per axis and weights c^2 = (A x)^2, (B y)^2,
    // g' = S^(-3/2) sum c^2 u^3 > 0 and g'' = 3 S^(-5/2) ((sum c^2 u^3)^2 - S sum c^2 u^4) <= 0
    // (Cauchy-Schwarz): g increases and is concave, so from any t left of the root each step lands
    // left of it and closer. g is exactly linear for a circle and nearly so far from the ellipse,
    // where S ~ 1/t^2 and Newton on S itself gained only ~1.5x per step (measured steps: the test
    // CamClay.ClosestPointOnTheEllipseMatchesBisectionInFewNewtonSteps, docs/throughput.md).
    // S >= R^2 / (t + max(A^2, B^2))^2 with R = |(A x, B y)|, so t = R - max(A^2, B^2) is left of it.
    const double a = A * x, b = B * y, A2 = A * A, B2 = B * B;
    auto eval = [&](double s, double& D) { // S(s), and D = sum c^2 u^3 = -S'/2
      const double ua = 1 / (s + A2), ub = 1 / (s + B2);
      const double ra = a * ua, rb = b * ub;
      D = ra * ra * ua + rb * rb * ub;
      return ra * ra + rb * rb;
    };
    auto step = [](double S, double D) { return S * (std::sqrt(S) - 1) / D; }; // -g / g'
    const double bound = std::max(0.0, std::sqrt(a * a + b * b) - std::max(A2, B2));
    const double guess = t;
    t = bound;
    int n = 0;
    if (guess > bound) { // the hardening solve's previous root, for a slightly different ellipse
      double D;
      const double S = eval(guess, D);
      // Right of the root, one step lands left of it (g is concave): kept no further left than the bound.
      t = S >= 1 ? guess : std::max(bound, guess + step(S, D));
      n += S < 1;
    }
    for (int it = 0; it < 100; ++it) {
      double D;
      const double S = eval(t, D);
      if (S - 1 <= 1e-15) break;
      const double dt = step(S, D);
      t += dt;
      ++n;
      if (dt <= 1e-16 * (t + A2 + B2)) break;
    }
    if (iterations) *iterations = n;
    px = A2 * x / (t + A2);
    py = B2 * y / (t + B2);
  }

  /// Square roots the projection needs, computed once per yielding particle (the hardening
  /// solve projects two or three times per particle).
  struct Scales {
    double sK, s3mu, sqrtTension;
    explicit Scales(const CamClayModel& m)
        : sK(std::sqrt(m.elastic.bulk())), s3mu(std::sqrt(3 * m.elastic.mu)),
          sqrtTension(std::sqrt(1 + 2 * m.params.beta)) {}
  };

  /// Energy-norm closest point (p, q) of (pTr, qTr) on the M_s ellipse of pre-consolidation p0,
  /// with its rate of change as the ellipse grows, dp/dp0 and dq/dp0.
  /// The surface is homogeneous in (p, q, p0), so P(p0) = p0 P_1(z / p0) and
  /// dP/dp0 = (P - J z) / p0, J being the projection's Jacobian: in the scaled (Euclidean)
  /// coordinates J = T T^T / (1 + kappa d) (unit tangent T, curvature kappa, distance d).
  /// t: closestOnEllipse's parameter, a guess on entry (0: none) and the root on exit.
  void projectOntoEllipse(const Scales& c, double pTr, double qTr, double p0, double& p, double& q,
                          double& dp, double& dq, double& t) const {
    const double sK = c.sK, s3mu = c.s3mu;
    const double beta = params.beta;
    dp = 0, dq = 0;
    if (p0 <= 0) { // no strength left
      p = 0, q = 0;
      return;
    }
    const double ap = 0.5 * (1 + beta) * p0, centre = 0.5 * (1 - beta) * p0;
    const double aq = params.Ms * ap / c.sqrtTension;
    const double x = (pTr - centre) / sK, y = qTr / s3mu, A = ap / sK, B = aq / s3mu;
    if ((x / A) * (x / A) + (y / B) * (y / B) <= 1) { // already inside: P = z, J = I
      p = pTr, q = qTr;
      return;
    }
    double X, Y;
    closestOnEllipse(std::abs(x), y, A, B, X, Y, t);
    const double sign = x < 0 ? -1.0 : 1.0;
    p = centre + sK * sign * X;
    q = s3mu * Y;
    // In the reflected frame: normal n = (X/A^2, Y/B^2), tangent (-n_y, n_x) / |n|, the trial
    // point at distance t |n|, curvature 1 / (A^2 B^2 |n|^3).
    const double nx = X / (A * A), ny = Y / (B * B), n2 = nx * nx + ny * ny;
    const double tangential = (-ny * sign * pTr / sK + nx * y) / (n2 * (1 + t / (A * A * B * B * n2)));
    dp = (p - sK * sign * (-ny) * tangential) / p0;
    dq = (q - s3mu * nx * tangential) / p0;
  }

  /// Return mapping; true when eps was changed. Rate-independent: dt unused.
  bool project(Vec3d& eps, State& s, double /*dt*/) const {
    const double K = elastic.bulk(), k = std::sqrt(1.5) * 2 * elastic.mu;
    const double tr = eps.sum(), pTr = -K * tr;
    const Vec3d dev = eps - Vec3d::Constant(tr / 3);
    const double a = dev.norm(), qTr = k * a;
    const double ev0 = s.volumetricPlasticStrain(), p00 = preconsolidation(ev0);
    if (yield(pTr, qTr, p00, slope(s)) <= 0) return false;
    double ev, p, q;
    if (!hardenNewton(pTr, qTr, ev0, p00, ev, p, q)) hardenBracketed(pTr, qTr, ev0, p00, ev, p, q);
    s.set(ev, true);
    eps = Vec3d::Constant(-p / (3 * K)) + (a > 0 ? q / qTr : 0.0) * dev;
    return true;
  }

  // Consistent hardening: eps_v solves G(eps_v) = eps_v - ev0 - (p(eps_v) - pTr) / K = 0, p(eps_v)
  // being the projection onto the ellipse of p0(eps_v). G runs from -inf (huge p0, trial inside)
  // to +inf (p0 = 0), so a bracket always exists.

  /// Newton on G with the projection's analytic derivative: 2-3 projections per yielding
  /// particle. False (and nothing to use) when it does not converge in a few steps; the caller
  /// then brackets. The last, tiny step moves p and q along their tangent instead of
  /// projecting again (error ~ step^2, below the float the state is stored in).
  bool hardenNewton(double pTr, double qTr, double ev0, double p00, double& ev, double& p, double& q,
                    int* projections = nullptr) const {
    const double K = elastic.bulk(), xi = params.xi;
    const Scales scales(*this);
    ev = ev0;
    double p0 = p00, t = 0;
    for (int it = 0; it < 12; ++it) {
      double dp, dq;
      projectOntoEllipse(scales, pTr, qTr, p0, p, q, dp, dq, t);
      if (projections) *projections = it + 1;
      const double dp0 = ev < 0 ? -xi * std::sqrt(K * K + p0 * p0) : 0.0; // dp0/d eps_v (eq. 10)
      const double g = ev - ev0 - (p - pTr) / K, slopeG = 1 - dp * dp0 / K;
      if (!(slopeG > 0)) return false;
      const double step = -g / slopeG;
      if (!std::isfinite(step)) return false;
      ev += step;
      if (std::abs(step) <= 1e-9 * (1 + std::abs(ev))) {
        p += dp * dp0 * step, q += dq * dp0 * step;
        return true;
      }
      p0 = preconsolidation(ev, K);
    }
    return false;
  }

  /// Bracket and Illinois false position on G: slow (~6 projections) but always converges.
  void hardenBracketed(double pTr, double qTr, double ev0, double p00, double& ev, double& p,
                       double& q) const {
    const double K = elastic.bulk();
    double evaluatedAt = ev0; // p, q are those of the last G evaluation
    const Scales scales(*this);
    auto Gp0 = [&](double e, double p0) {
      double dp, dq, t = 0;
      projectOntoEllipse(scales, pTr, qTr, p0, p, q, dp, dq, t);
      evaluatedAt = e;
      return e - ev0 - (p - pTr) / K;
    };
    auto G = [&](double e) { return Gp0(e, preconsolidation(e, K)); };
    double x0 = ev0, g0 = Gp0(x0, p00);
    double lo, hi, glo, ghi;
    double step = std::abs(g0) + 1e-9;
    if (g0 > 0) {
      hi = x0, ghi = g0, lo = x0 - step, glo = G(lo);
      while (glo > 0) step *= 2, hi = lo, ghi = glo, lo = x0 - step, glo = G(lo);
    } else {
      lo = x0, glo = g0, hi = x0 + step, ghi = G(hi);
      while (ghi < 0) step *= 2, lo = hi, glo = ghi, hi = x0 + step, ghi = G(hi);
    }
    double x = hi;
    int side = 0;
    for (int it = 0; it < 100 && hi - lo > 1e-14 * (1 + std::abs(hi)); ++it) {
      x = (lo * ghi - hi * glo) / (ghi - glo);
      const double gx = G(x);
      if (gx == 0) break;
      if (gx > 0) {
        hi = x, ghi = gx;
        if (side == 1) glo *= 0.5;
        side = 1;
      } else {
        lo = x, glo = gx;
        if (side == -1) ghi *= 0.5;
        side = -1;
      }
    }
    if (evaluatedAt != x) G(x); // p, q of the final eps_v
    ev = x;
  }
};

} // namespace talus
