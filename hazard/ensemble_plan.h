// Which members an ensemble runs: `--vary KEY=LOW:HIGH` specifications (any scene key, as
// `--set` addresses it) and a sampling of their box:
//   lhs     Latin hypercube, N members, seeded (AvaFrame's probRun samples the same way)
//   grid    N levels per parameter, N^k members, first parameter slowest
//   morris  N elementary-effects trajectories of k + 1 members each (Morris 1991): 4 levels,
//           step 2/3 of the range, one parameter moved per step
// Each member is the scene with `--set KEY=VALUE` for every varied key.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace talus::ensemble {

struct VarySpec {
  std::string key;
  double low = 0, high = 0;
  std::string text; ///< as given, for messages
};

/// "KEY=LOW:HIGH" -> VarySpec. Throws InputError("--vary", ...) in one line: no '=', no key,
/// not two numbers, an empty range (LOW >= HIGH).
VarySpec parseVary(const std::string& text);
/// All of them; also refuses a key given twice.
std::vector<VarySpec> parseVaries(const std::vector<std::string>& texts);

enum class Method { Lhs, Grid, Morris };
Method parseMethod(const std::string& name); ///< lhs, grid, morris; InputError otherwise

struct Plan {
  std::vector<VarySpec> vary;
  Method method = Method::Lhs;
  std::vector<std::vector<double>> unit;    ///< [member][parameter] in [0, 1]
  std::vector<std::vector<std::string>> values; ///< [member][parameter] as passed to --set
  size_t members() const { return unit.size(); }
  /// `--set` assignments of member m.
  std::vector<std::string> overrides(size_t m) const;
  /// plan.csv: "member,KEY,..." then one row per member (member_NNN and the values).
  std::string csv() const;
};

/// `samples`: members (lhs), levels per parameter (grid) or trajectories (morris); >= 1.
Plan makePlan(const std::vector<VarySpec>& vary, Method method, size_t samples, uint64_t seed);

/// member_000, member_001, ... (at least three digits).
std::string memberName(size_t m);

/// Morris elementary effects of one outcome: per parameter the mean of |EE| (mu*), the mean and
/// the standard deviation of EE, in outcome units per unit of the parameter's range. A
/// trajectory step whose outcome is NaN (a failed member) is left out.
struct MorrisEffect {
  std::string key;
  double muStar = 0, mu = 0, sigma = 0;
  size_t effects = 0;
};
std::vector<MorrisEffect> morrisEffects(const Plan& plan, const std::vector<double>& outcome);

} // namespace talus::ensemble
