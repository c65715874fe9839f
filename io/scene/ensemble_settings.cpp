#include "io/scene/ensemble_settings.h"

#include "io/common/polyline.h"
#include "io/terrain/terrain_loader.h"

#include <algorithm>

namespace talus {

EnsembleSettings readEnsembleSettings(const ConfigTable* t, const std::vector<Eigen::Vector2d>& fallbackPath) {
  EnsembleSettings e;
  e.path = fallbackPath;
  if (!t) return e;
  static const std::vector<std::string> types{"pft", "pfv", "ppr", "pfd"};
  if (const ConfigTable* th = t->table("thresholds")) {
    e.thresholds.clear();
    for (const auto& [k, v] : th->values()) {
      if (std::find(types.begin(), types.end(), k) == types.end())
        th->fail(k, "not a peak result type (pft, pfv, ppr, pfd)");
      for (double x : th->numbers(k))
        if (!(x >= 0)) th->fail(k, "thresholds must be non-negative");
      e.thresholds[k] = th->numbers(k);
    }
  }
  if (t->has("quantiles")) {
    e.quantiles = t->numbers("quantiles");
    for (double q : e.quantiles)
      if (!(q >= 0 && q <= 1)) t->fail("quantiles", "quantiles lie in [0, 1]");
  }
  e.runoutResult = t->choice("runout_result", e.runoutResult, types);
  e.runoutThreshold = t->positive("runout_threshold", e.runoutThreshold, true);
  e.domainWidth = t->positive("domain_width", e.domainWidth);
  if (t->has("path")) {
    const ConfigValue& v = t->values().at("path");
    try {
      if (v.isString()) {
        e.path = Polyline::parse(resolveScenePath(t->file(), t->string("path"))).points();
      } else {
        e.path.clear();
        const auto& arr = v.isArray() ? std::get<ConfigValue::Array>(v.data) : ConfigValue::Array{};
        for (const auto& p : arr) {
          const auto* xy = p.isArray() ? &std::get<ConfigValue::Array>(p.data) : nullptr;
          if (!xy || xy->size() != 2 || !(*xy)[0].isNumber() || !(*xy)[1].isNumber())
            t->fail("path", "expected a line file or [[x, y], ...]");
          e.path.emplace_back(std::get<double>((*xy)[0].data), std::get<double>((*xy)[1].data));
        }
        if (e.path.size() < 2) t->fail("path", "needs at least two points");
      }
    } catch (const InputError& err) {
      if (err.located()) throw;
      t->fail("path", err.what());
    } catch (const std::exception& err) { // a malformed line, or a path the system refuses
      t->fail("path", err.what());
    }
  }
  return e;
}

} // namespace talus
