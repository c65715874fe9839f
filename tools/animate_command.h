// `talus animate RUN_DIR`: the run's film drawn and encoded again with other choices.
#pragma once

#include "io/output/animation.h"

namespace CLI {
class App;
}

namespace talus {

struct AnimateOptions {
  std::string dir;
  AnimationStyle style;
  std::vector<double> window; ///< xmin ymin xmax ymax, or empty
};

CLI::App* addAnimateCommand(CLI::App& app, AnimateOptions& o);
/// Prints the films written (or why not) and returns the exit status; throws InputError.
int runAnimateCommand(const AnimateOptions& o);

} // namespace talus
