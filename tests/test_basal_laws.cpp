// Speed-dependent basal laws against their analytic solutions: a plug (a stiff slab) on an
// infinite slope, made infinite by periodic x and y axes with gravity tilted by the slope angle
// over a flat bed. The slab's mean speed must follow du/dt = s(t) [g (sin - mu cos) - tau_turb / (rho h)]
// where s(t) is the smooth gravity ramp that starts the slab without elastic ringing.
#include "engine/samosat_law.h"
#include "forest_plug.h"
#include "terrain_test_support.h"
#include "test_support.h"

#include <cmath>
#include <functional>
#include <gtest/gtest.h>

using namespace talus;

namespace {

constexpr double kG = 9.81;

/// A stiff slab of thickness h filling a periodic 8 x 8-cell patch (one block), on a bed with `law`.
std::string plugScene(double thetaDeg, double h, double dx, const std::string& law, double ramp) {
  const double t = thetaDeg * M_PI / 180;
  char buf[1400];
  std::snprintf(buf, sizeof buf, R"(
[simulation]
dx = %g
end_time = 100
gravity = [%.12g, 0, %.12g]
gravity_ramp = %g
[domain]
min = [0, 0, 0]
max = [%g, %g, %g]
periodic = ["x", "y"]
walls = "slip"
z_min = %s
)",
                dx, kG * std::sin(t), -kG * std::cos(t), ramp, 8 * dx, 8 * dx, h + 8 * dx, law.c_str());
  return buf + test::plugSlab(dx, h);
}

/// The gravity ramp of engine/simulation.cpp: (1 - cos(pi t / T)) / 2 until T.
double ramp(double t, double T) { return t >= T ? 1.0 : 0.5 * (1 - std::cos(M_PI * t / T)); }

/// RK4 of du/dt = s(t) (a - drag(u)).
double integrate(double tEnd, double a, double T, const std::function<double(double)>& drag) {
  double u = 0, t = 0;
  const double h = 1e-4;
  auto f = [&](double tt, double uu) { return ramp(tt, T) * (a - drag(uu)); };
  while (t < tEnd - 1e-12) {
    const double s = std::min(h, tEnd - t);
    const double k1 = f(t, u), k2 = f(t + s / 2, u + s / 2 * k1), k3 = f(t + s / 2, u + s / 2 * k2), k4 = f(t + s, u + s * k3);
    u = std::max(0.0, u + s / 6 * (k1 + 2 * k2 + 2 * k3 + k4));
    t += s;
  }
  return u;
}

struct PlugRun {
  std::vector<double> t, u, exact;
  double maxRelError = 0;
};

PlugRun runPlug(const std::string& scene, double tEnd, double a, double T,
                const std::function<double(double)>& drag, double uMin) {
  auto sim = test::makeSimulation(scene);
  PlugRun r;
  for (double next = 0.5; next <= tEnd + 1e-9; next += 0.5) {
    sim->advanceTo(next);
    const double u = sim->meanVelocity().x(), e = integrate(next, a, T, drag);
    r.t.push_back(next), r.u.push_back(u), r.exact.push_back(e);
    std::printf("  t = %4.1f s  u = %7.3f m/s  analytic %7.3f  error %+.2f%%\n", next, u, e, 100 * (u / e - 1));
    if (e > uMin) r.maxRelError = std::max(r.maxRelError, std::abs(u / e - 1));
  }
  return r;
}

} // namespace

TEST(BasalLaws, VoellmyPlugReachesItsTerminalSpeedAlongTheAnalyticApproach) {
  // 30 degrees, mu 0.2, xi 200 m/s2, h 0.4 m: u_inf = sqrt(xi h (sin - mu cos)) = 5.11 m/s.
  const double theta = 30 * M_PI / 180, mu = 0.2, xi = 200, h = 0.4, T = 0.2;
  const double a = kG * (std::sin(theta) - mu * std::cos(theta));
  const double uInf = std::sqrt(xi * h * (std::sin(theta) - mu * std::cos(theta)));
  const PlugRun r = runPlug(plugScene(30, h, 0.05, "{ law = \"voellmy\", friction = 0.2, xi = 200 }", T), 5.0, a, T,
                            [&](double u) { return kG * u * u / (xi * h); }, 0.5);
  std::printf("  u_inf %.3f m/s; at 5 s %.3f m/s\n", uInf, r.u.back());
  // 3 %: the issue's tolerance for the approach (from 0.5 m/s on) and for the terminal speed.
  EXPECT_LT(r.maxRelError, 0.03);
  EXPECT_NEAR(r.u.back(), uInf, 0.03 * uInf); // 5 s is 3.1 relaxation times: tanh = 0.996
}

TEST(BasalLaws, SamosAtPlugReachesTheSpeedWhereItsShearBalancesTheSlope) {
  // 40 degrees, AvaFrame's default samosAT, h 0.2 m: the terminal speed solves
  // tau(u) / sigma = tan(theta) with sigma = rho g cos(theta) h (found here by bisection).
  const double theta = 40 * M_PI / 180, h = 0.2, T = 0.2, rho = 300;
  const double sigma = rho * kG * std::cos(theta) * h;
  const double p[6] = {0.155, 0, 0.222, 0.43, 0.05, 4.13};
  auto shear = [&](double u) { return SamosAtLaw::shearOverNormal(u, sigma, rho, h, p); };
  double lo = 0, hi = 100;
  for (int i = 0; i < 200; ++i) (shear(0.5 * (lo + hi)) < std::tan(theta) ? lo : hi) = 0.5 * (lo + hi);
  const double uInf = 0.5 * (lo + hi);
  const PlugRun r = runPlug(plugScene(40, h, 0.05, "\"samosat\"", T), 5.0, kG * std::sin(theta), T,
                            [&](double u) { return kG * std::cos(theta) * shear(u); }, 0.5);
  std::printf("  u_inf %.3f m/s; at 5 s %.3f m/s\n", uInf, r.u.back());
  EXPECT_NEAR(r.u.back(), uInf, 0.03 * uInf); // 3 %: the issue's tolerance
  EXPECT_LT(r.maxRelError, 0.03);
}

namespace {

/// Mean x-velocity of one material's particles.
double groupSpeed(const Simulation& sim, const std::string& name) {
  for (const MaterialGroup* g : sim.groups())
    if (g->name() == name) {
      double m = 0, p = 0;
      for (size_t i = 0; i < g->size(); ++i) m += g->particles.mass[i], p += g->particles.mass[i] * g->particles.v[i].x();
      return p / m;
    }
  return NAN;
}

} // namespace

TEST(BasalLaws, EachMaterialSlidesByItsOwnLawOnOneSlope) {
  // Two slabs side by side on one 30-degree bed whose law is Coulomb 0.2: "rock" keeps the bed's
  // law, "snow" brings its own (sticky, then Coulomb 0.4). Each must move as its law says:
  // u = a t after the ramp (a = g (sin - mu cos)), or not at all.
  const double theta = 30 * M_PI / 180, dx = 0.05, T = 0.2, tEnd = 1.0;
  auto scene = [&](const std::string& snowBasal) {
    char buf[1600];
    std::snprintf(buf, sizeof buf, R"(
[simulation]
dx = %g
end_time = 10
gravity = [%.12g, 0, %.12g]
gravity_ramp = %g
[domain]
min = [0, 0, 0]
max = [0.4, 0.8, 0.6]
periodic = ["x"]
walls = "slip"
z_min = { law = "coulomb", friction = 0.2 }
[[materials]]
name = "rock"
model = "elastic"
density = 300
youngs_modulus = 1e6
poisson_ratio = 0.3
[[materials]]
name = "snow"
model = "elastic"
density = 300
youngs_modulus = 1e6
poisson_ratio = 0.3
basal = %s
[[bodies]]
material = "rock"
shape = "box"
min = [0, 0, 0]
max = [0.4, 0.3, 0.2]
[[bodies]]
material = "snow"
shape = "box"
min = [0, 0.5, 0]
max = [0.4, 0.8, 0.2]
)",
                  dx, kG * std::sin(theta), -kG * std::cos(theta), T, snowBasal.c_str());
    return std::string(buf);
  };
  // Speed after the cosine ramp: a (t - T/2) for t >= T.
  auto coulomb = [&](double mu) { return kG * (std::sin(theta) - mu * std::cos(theta)) * (tEnd - T / 2); };
  {
    auto sim = test::makeSimulation(scene("\"sticky\""));
    sim->advanceTo(tEnd);
    const double rock = groupSpeed(*sim, "rock"), snow = groupSpeed(*sim, "snow");
    std::printf("  sticky snow %.4f m/s, rock %.3f m/s (Coulomb 0.2: %.3f)\n", snow, rock, coulomb(0.2));
    // 2 %: the plug tests above follow the analytic speed to 0.2 %; the slabs' edges touch the
    // y walls (slip) and a 4-cell gap keeps the slabs off each other's nodes (MPM couples bodies that share one).
    EXPECT_NEAR(rock, coulomb(0.2), 0.02 * coulomb(0.2));
    EXPECT_LT(std::abs(snow), 0.01 * coulomb(0.2)); // held: only elastic creep of the slab
  }
  {
    auto sim = test::makeSimulation(scene("{ law = \"coulomb\", friction = 0.4 }"));
    sim->advanceTo(tEnd);
    const double rock = groupSpeed(*sim, "rock"), snow = groupSpeed(*sim, "snow");
    std::printf("  snow (Coulomb 0.4) %.3f m/s (analytic %.3f), rock %.3f m/s\n", snow, coulomb(0.4), rock);
    EXPECT_NEAR(snow, coulomb(0.4), 0.02 * coulomb(0.4));
    EXPECT_NEAR(rock, coulomb(0.2), 0.02 * coulomb(0.2));
  }
}


TEST(BasalLaws, AForestsDragBringsAPlugToAvaFramesTerminalSpeed) {
  // AvaFrame's resistance du/dt = -cResH u^2 / h (F = -cResH rho A |u| u) on Coulomb 0.3 at 30
  // degrees: u_inf = sqrt(g (sin - mu cos) h / cResH). h 0.8 m, cResH 0.5 1/m: u_inf = 1.94 m/s,
  // 0.82 s relaxation.
  const std::string dir = test::tempDir("basal_forest");
  const double theta = 30 * M_PI / 180, mu = 0.3, h = 0.8, cRes = 0.5, T = 0.2;
  const double a = kG * (std::sin(theta) - mu * std::cos(theta));
  const double uInf = std::sqrt(a * h / cRes);
  // detrainment = 0: AvaFrame's forest without detrainment drags at every speed and thickness
  // (with it, not below 6 m/s: tests/test_detrainment.cpp).
  const PlugRun r = runPlug(test::forestPlugScene(dir, h, 0.1, mu, cRes, T, "detrainment = 0"), 4.0, a, T,
                            [&](double u) { return cRes * u * u / h; }, 0.3);
  std::printf("  u_inf %.3f m/s; at 4 s %.3f m/s\n", uInf, r.u.back());
  // Measured within 0.1 % all along; 1 % leaves room for the step size and still fails a drag
  // off by 2 % (the terminal speed goes as its inverse square root).
  EXPECT_LT(r.maxRelError, 0.01);
  EXPECT_NEAR(r.u.back(), uInf, 0.01 * uInf); // 4 s is 4.9 relaxation times
}
