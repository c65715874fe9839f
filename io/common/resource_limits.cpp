#include "io/common/resource_limits.h"

namespace talus {

ResourceLimits& resourceLimits() {
  static ResourceLimits limits;
  return limits;
}

} // namespace talus
