// The cases of `talus work-precision`: each validation case of tools/validation_cases.h with the
// error it is judged by, the resolutions it is refined over and the figures printed beside it.
// One family a function; a new case is one entry in its family.
#pragma once

#include "tools/validation_cases.h"
#include "tools/work_precision_plot.h"

#include <functional>
#include <string>
#include <vector>

namespace talus::work_precision {

struct Case {
  std::string name, what, errorMeaning, cellsMeaning;
  std::function<Point(const validation::Resolution& res)> run;
  std::vector<double> levels, quickLevels; ///< cells of the full and the quick refinement
  /// The scene file the case runs at a resolution, for a case that is one scene; null otherwise.
  std::function<std::string(const validation::Resolution& res)> scene = nullptr;
};

/// printf of one number, for the report's cells.
std::string fmt(const char* f, double v);

/// Every case; those reading data in `shared` (../shared) only when it is given.
std::vector<Case> cases(const std::string& shared);

} // namespace talus::work_precision
