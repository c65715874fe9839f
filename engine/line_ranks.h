// Which ranks can hold blocks of a thickness line (engine/flow_thickness.h), so a rank asks only
// them for the lines it reads instead of every rank sending every block with flow to every rank.
//
// A rank's grid holds its own blocks and the blocks one step above them on each axis (a
// particle's stencil starts in its own block and reaches the next). So a rank holds a block of a
// line only if it owns a block whose in-plane coordinates lie within one of the line's, somewhere
// along it: the owners of that 3 x 3 prism over the domain's extent are the line's holders. The
// answer depends on the line and the ranges only (OpenVDB-style contract: no collective).
#pragma once

#include "engine/domain_decomposition.h"

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace talus {

class LineRanks {
public:
  /// @param lo, hi  the blocks any particle can own (inclusive); lines are scanned over them
  LineRanks(const DomainDecomposition& ranks, const BlockCoord& lo, const BlockCoord& hi)
      : ranks_(ranks), lo_(lo), hi_(hi) {}

  /// Ranks (ascending) that may hold a block of the line through c along axis (0, 1, 2). Cached
  /// per line; the cache is dropped when the decomposition's ranges change (its generation), so
  /// the reference stays valid until then.
  const std::vector<int>& holders(const BlockCoord& c, int axis);

  /// In-plane reach of the blocks a rank holds beyond those it owns (the stencil's next block).
  static constexpr int kReach = 1;

private:
  /// Bit mask of the ranks owning a block of the single line through c along axis (one 64-bit
  /// word per 64 ranks), cached.
  const std::vector<uint64_t>& lineOwners(const BlockCoord& c, int axis);

  const DomainDecomposition& ranks_;
  BlockCoord lo_, hi_;
  uint64_t generation_ = UINT64_MAX;
  std::unordered_map<uint64_t, std::vector<uint64_t>> owners_[3];
  std::unordered_map<uint64_t, std::vector<int>> holders_[3];
  std::vector<uint64_t> mask_;
};

} // namespace talus
