// Contact-law parameters that vary over the terrain (friction by region, as AvaFrame's spatial
// Voellmy): a field sampled once per grid node when the node's block first becomes active, cached
// by the collider, and handed to the law through ContactNode::params.
#pragma once

#include "engine/types.h"

namespace talus {

class ParameterField {
public:
  virtual ~ParameterField() = default;
  /// Values per node, in the law's parameterNames() order.
  virtual int count() const = 0;
  /// The values at local position x (m) into out[0 .. count()).
  virtual void sample(const Vec3d& x, float* out) const = 0;
};

} // namespace talus
