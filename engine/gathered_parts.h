// Every rank's bytes gathered to rank 0 (Communicator::gather), seen as one part per rank.
#pragma once

#include "engine/communicator.h"

#include <string_view>
#include <vector>

namespace talus {

/// The bytes rank 0 gathered and a view of each rank's part in them, in rank order. Moved, never
/// copied: the parts point into its bytes (a moved vector keeps its storage).
struct GatheredParts {
  std::vector<char> bytes;
  std::vector<std::string_view> parts; ///< into `bytes`; empty on the other ranks

  GatheredParts() = default;
  GatheredParts(GatheredParts&&) = default;
  GatheredParts& operator=(GatheredParts&&) = default;
  GatheredParts(const GatheredParts&) = delete;
  GatheredParts& operator=(const GatheredParts&) = delete;
};

/// Collective: Communicator::gather of `mine`, split into each rank's part on rank 0 (empty
/// GatheredParts elsewhere).
inline GatheredParts gatherParts(Communicator& comm, const std::vector<char>& mine) {
  GatheredParts g;
  std::vector<size_t> counts;
  g.bytes = comm.gather(mine, counts);
  if (comm.rank() != 0) return g;
  for (size_t at = 0, r = 0; r < counts.size(); at += counts[r++]) g.parts.emplace_back(g.bytes.data() + at, counts[r]);
  return g;
}

} // namespace talus
