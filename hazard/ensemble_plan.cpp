#include "hazard/ensemble_plan.h"

#include "io/common/input_error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <set>

namespace talus::ensemble {

namespace {

const char* kUsage = "expected KEY=LOW:HIGH, e.g. terrain.friction=0.15:0.25";

double parseNumber(const std::string& text, const std::string& s) {
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || !end || *end || !std::isfinite(v))
    throw InputError("--vary", 0, text, "'" + s + "' is not a number (" + kUsage + ")");
  return v;
}

std::string format(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.10g", v);
  return b;
}

/// Uniform in [0, 1) from the top 53 bits: the same numbers on every platform (the standard
/// distributions are implementation-defined).
double uniform(std::mt19937_64& rng) { return double(rng() >> 11) * 0x1.0p-53; }

void shuffle(std::vector<size_t>& v, std::mt19937_64& rng) {
  for (size_t i = v.size(); i > 1; --i) std::swap(v[i - 1], v[size_t(rng() % i)]);
}

constexpr int kMorrisLevels = 4;
constexpr double kMorrisDelta = kMorrisLevels / (2.0 * (kMorrisLevels - 1)); // 2/3

} // namespace

VarySpec parseVary(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) throw InputError("--vary", 0, text, kUsage);
  VarySpec v;
  v.text = text;
  v.key = text.substr(0, eq);
  const std::string range = text.substr(eq + 1);
  const auto colon = range.find(':');
  if (colon == std::string::npos || range.find(':', colon + 1) != std::string::npos)
    throw InputError("--vary", 0, text, std::string("the range needs one ':' (") + kUsage + ")");
  v.low = parseNumber(text, range.substr(0, colon));
  v.high = parseNumber(text, range.substr(colon + 1));
  if (!(v.low < v.high))
    throw InputError("--vary", 0, text, "empty range: LOW (" + format(v.low) + ") must be below HIGH (" + format(v.high) + ")");
  return v;
}

std::vector<VarySpec> parseVaries(const std::vector<std::string>& texts) {
  std::vector<VarySpec> out;
  std::set<std::string> keys;
  for (const auto& t : texts) {
    out.push_back(parseVary(t));
    if (!keys.insert(out.back().key).second) throw InputError("--vary", 0, t, "the key is varied twice");
  }
  if (out.empty()) throw InputError("--vary", "give at least one --vary KEY=LOW:HIGH");
  return out;
}

Method parseMethod(const std::string& name) {
  if (name == "lhs") return Method::Lhs;
  if (name == "grid") return Method::Grid;
  if (name == "morris") return Method::Morris;
  throw InputError("--method", 0, name, "not one of: lhs, grid, morris");
}

std::string memberName(size_t m) {
  char b[32];
  std::snprintf(b, sizeof b, "member_%03zu", m);
  return b;
}

std::vector<std::string> Plan::overrides(size_t m) const {
  std::vector<std::string> out;
  for (size_t p = 0; p < vary.size(); ++p) out.push_back(vary[p].key + "=" + values[m][p]);
  return out;
}

std::string Plan::csv() const {
  std::string s = "member";
  for (const auto& v : vary) s += "," + v.key;
  s += "\n";
  for (size_t m = 0; m < members(); ++m) {
    s += memberName(m);
    for (const auto& v : values[m]) s += "," + v;
    s += "\n";
  }
  return s;
}

Plan makePlan(const std::vector<VarySpec>& vary, Method method, size_t samples, uint64_t seed) {
  if (samples < 1) throw InputError("--samples", "must be at least 1");
  Plan plan;
  plan.vary = vary;
  plan.method = method;
  const size_t k = vary.size();
  std::mt19937_64 rng(seed);
  if (method == Method::Lhs) {
    // One member in each of the N strata of every parameter, strata paired at random.
    plan.unit.assign(samples, std::vector<double>(k));
    for (size_t p = 0; p < k; ++p) {
      std::vector<size_t> strata(samples);
      for (size_t m = 0; m < samples; ++m) strata[m] = m;
      shuffle(strata, rng);
      for (size_t m = 0; m < samples; ++m) plan.unit[m][p] = (double(strata[m]) + uniform(rng)) / double(samples);
    }
  } else if (method == Method::Grid) {
    const double total = std::pow(double(samples), double(k));
    if (total > 100000) throw InputError("--samples", "a grid of " + std::to_string(samples) + "^" + std::to_string(k) + " members is too large");
    for (size_t m = 0; m < size_t(total); ++m) {
      std::vector<double> u(k);
      size_t rest = m;
      for (size_t p = k; p-- > 0;) { // last parameter fastest
        const size_t level = rest % samples;
        rest /= samples;
        u[p] = samples == 1 ? 0.5 : double(level) / double(samples - 1);
      }
      plan.unit.push_back(u);
    }
  } else {
    // Trajectories: a base point on the levels 0 .. 1 - delta, then each parameter in random
    // order moved by +delta (the base levels keep every point inside [0, 1]).
    const int baseLevels = kMorrisLevels / 2;
    for (size_t r = 0; r < samples; ++r) {
      std::vector<double> x(k);
      for (size_t p = 0; p < k; ++p) x[p] = double(rng() % baseLevels) / double(kMorrisLevels - 1);
      std::vector<size_t> order(k);
      for (size_t p = 0; p < k; ++p) order[p] = p;
      shuffle(order, rng);
      plan.unit.push_back(x);
      for (size_t p : order) {
        x[p] += kMorrisDelta;
        plan.unit.push_back(x);
      }
    }
  }
  for (const auto& u : plan.unit) {
    std::vector<std::string> vals;
    for (size_t p = 0; p < k; ++p) vals.push_back(format(vary[p].low + u[p] * (vary[p].high - vary[p].low)));
    plan.values.push_back(vals);
  }
  return plan;
}

std::vector<MorrisEffect> morrisEffects(const Plan& plan, const std::vector<double>& y) {
  const size_t k = plan.vary.size();
  std::vector<std::vector<double>> ee(k);
  if (plan.method == Method::Morris)
    for (size_t start = 0; start + k < plan.members() && start + k < y.size(); start += k + 1)
      for (size_t s = 0; s < k; ++s) {
        const auto& a = plan.unit[start + s];
        const auto& b = plan.unit[start + s + 1];
        size_t moved = 0;
        for (size_t p = 0; p < k; ++p)
          if (b[p] != a[p]) moved = p;
        const double d = (y[start + s + 1] - y[start + s]) / (b[moved] - a[moved]);
        if (std::isfinite(d)) ee[moved].push_back(d);
      }
  std::vector<MorrisEffect> out;
  for (size_t p = 0; p < k; ++p) {
    MorrisEffect e;
    e.key = plan.vary[p].key;
    e.effects = ee[p].size();
    for (double d : ee[p]) e.mu += d, e.muStar += std::abs(d);
    if (e.effects) e.mu /= double(e.effects), e.muStar /= double(e.effects);
    for (double d : ee[p]) e.sigma += (d - e.mu) * (d - e.mu);
    e.sigma = e.effects > 1 ? std::sqrt(e.sigma / double(e.effects - 1)) : 0.0;
    out.push_back(e);
  }
  return out;
}

} // namespace talus::ensemble
