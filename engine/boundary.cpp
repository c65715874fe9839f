#include "engine/boundary.h"

namespace talus {

const char* boundaryTypeName(BoundaryType t) {
  switch (t) {
  case BoundaryType::Sticky: return "sticky";
  case BoundaryType::Slip: return "slip";
  case BoundaryType::Friction: return "friction";
  case BoundaryType::Open: return "open";
  }
  return "?";
}

} // namespace talus
