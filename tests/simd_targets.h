// Running a test's kernels on every SIMD target this machine has (engine/stencil_lanes.h).
#pragma once

#include "engine/stencil_lanes.h"

#include <gtest/gtest.h>

#include <cstdio>

namespace talus {

/// Calls fn() once per Highway target compiled in and supported here, every kernel switched to
/// it; the best target is restored afterwards, also when an assertion in fn returns early.
template <class Fn>
void forEachSimdTarget(Fn&& fn) {
  const std::vector<int64_t> targets = simdTargets();
  EXPECT_GE(targets.size(), 2u) << "the portable target and at least one SIMD target";
  struct Restore {
    ~Restore() { useSimdTarget(0); }
  } restore;
  for (int64_t target : targets) {
    useSimdTarget(target);
    SCOPED_TRACE(simdTargetName());
    std::printf("[ target   ] %s\n", simdTargetName());
    fn();
  }
}

} // namespace talus
