// Binning's reorder (engine/particle_set.h, gatherInPlace): every element type a particle array
// holds, narrower and wider than the 12-byte slices it moves at a time, against the permutation
// applied by copying.
#include "engine/particle_set.h"

#include <algorithm>
#include <cstring>
#include <gtest/gtest.h>
#include <numeric>
#include <random>

using namespace talus;

namespace {

/// 16 bytes: one whole 12-byte slice and a 4-byte remainder.
struct Sixteen {
  float a, b, c, d;
};

/// Distinct bytes in every element, so a byte moved from the wrong element or slice shows.
template <class T> std::vector<T> numbered(size_t n) {
  std::vector<T> v(n);
  for (size_t i = 0; i < n; ++i) {
    unsigned char* bytes = reinterpret_cast<unsigned char*>(detail::elementBytes(v[i]));
    for (size_t k = 0; k < sizeof(T); ++k) bytes[k] = static_cast<unsigned char>(i * 31 + k * 7 + 1);
  }
  return v;
}

template <class T> void expectGathered(size_t n, size_t begin, size_t end) {
  std::vector<T> a = numbered<T>(n);
  Permutation perm;
  perm.index.resize(n);
  std::iota(perm.index.begin(), perm.index.end(), 0u);
  std::mt19937 rng(7);
  std::shuffle(perm.index.begin() + long(begin), perm.index.begin() + long(end), rng);
  perm.begin = begin, perm.end = end;
  const std::vector<T> before = a;
  ReorderScratch scratch;
  gatherInPlace(a, perm, scratch);
  for (size_t i = 0; i < n; ++i) {
    const T& want = before[perm.index[i]];
    ASSERT_EQ(std::memcmp(detail::elementBytes(const_cast<T&>(want)), detail::elementBytes(a[i]), sizeof(T)), 0)
        << "element " << i << " of " << sizeof(T) << "-byte values";
  }
  // The scratch holds at most a slice per moved particle, whatever the element's width.
  EXPECT_LE(scratch.bytes(), (end - begin) * std::max<size_t>(std::min(sizeof(T), detail::kGatherSliceBytes), sizeof(double)) + sizeof(double));
}

} // namespace

TEST(ParticleSet, GatherInPlaceMovesEveryElementTypeWholeAndLeavesTheRestAlone) {
  // A range inside the array (the identity outside it), over several of the reorder's 8192-particle
  // chunks, so the threads' split is crossed too.
  const size_t n = 30000, begin = 1234, end = 27000;
  expectGathered<float>(n, begin, end);   // 4 bytes: moved whole
  expectGathered<Vec3>(n, begin, end);    // 12: one slice, moved whole
  expectGathered<Sixteen>(n, begin, end); // 12 + 4
  expectGathered<Sym3>(n, begin, end);    // 24: two slices
  expectGathered<Mat3>(n, begin, end);    // 36: three slices
}
