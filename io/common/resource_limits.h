// Upper bounds on the work a scene may ask for, so a typo such as dx = 1e-6 gets a clear error
// instead of exhausting memory. `[simulation] max_particles` sets the first; the fuzz target
// tightens all of them.
#pragma once

#include "io/common/input_error.h"

#include <string>

namespace talus {

struct ResourceLimits {
  double maxParticles = 2e9;    ///< particles a scene may seed (about 300 GB)
  double maxRasterCells = 4e8;  ///< cells of a generated or resampled DEM
  double maxVoxels = 4e9;       ///< narrow-band voxels of a terrain level set
};

/// Process-wide limits (the defaults above unless changed).
ResourceLimits& resourceLimits();

} // namespace talus
