// Structure-of-arrays storage of the state every particle has, whatever its material.
#pragma once

#include "engine/types.h"

#include <algorithm>
#include <cstring>
#include <new>
#include <tbb/parallel_for.h>
#include <type_traits>
#include <vector>

namespace talus {

/// Positions are relative to the scene's local origin (see Simulation::origin()).
struct ParticleSet {
  std::vector<Vec3> x;    ///< position (m, local frame)
  std::vector<Vec3> v;    ///< velocity (m/s)
  std::vector<Mat3> C;    ///< APIC affine velocity matrix (1/s)
  std::vector<Sym3> tau;  ///< Kirchhoff stress used by the next P2G (Pa)
  std::vector<Real> mass; ///< kg, constant per particle but where a forest detrains it (engine/detrainment.h)

  size_t size() const { return x.size(); }

  template <class F> void forEachArray(F&& f) {
    f(x); f(v); f(C); f(tau); f(mass);
  }
  void resize(size_t n) {
    forEachArray([n](auto& a) { a.resize(n); });
  }
  /// Room for n particles, so appending up to n allocates nothing more.
  void reserve(size_t n) {
    forEachArray([n](auto& a) { a.reserve(n); });
  }
  /// Empty, with the arrays' memory returned (resize(0) keeps it).
  void release() {
    forEachArray([](auto& a) { std::decay_t<decltype(a)>().swap(a); });
  }
  static constexpr size_t bytesPerParticle() {
    return 2 * sizeof(Vec3) + sizeof(Mat3) + sizeof(Sym3) + sizeof(Real);
  }
};

/// A gather permutation: new[i] = old[index[i]]. Outside [begin, end) it is the identity, so a
/// reorder moves only that range: a flow that crosses blocks in one part of a scene (a slide in
/// a lake at rest) does not pay for copying the rest.
struct Permutation {
  std::vector<uint32_t> index;
  size_t begin = 0, end = 0;
};

/// Buffers the per-step reordering reuses (binning, gathers). Allocated once and kept: a buffer
/// allocated afresh every step costs a page fault per 4 KB on first touch, which was most of the
/// binning time on the lab box (60-82 -> 24-29 ns per particle-step, docs/throughput.md).
class ReorderScratch {
public:
  Permutation perm; ///< gather permutation of the sort

  /// Uninitialised room for n values of T (any element type of a particle array).
  template <class T> T* values(size_t n) {
    static_assert(alignof(T) <= alignof(double) && std::is_trivially_destructible_v<T>);
    const size_t words = (n * sizeof(T) + sizeof(double) - 1) / sizeof(double);
    if (raw_.size() < words) raw_.resize(words);
    return reinterpret_cast<T*>(raw_.data());
  }
  size_t bytes() const {
    return perm.index.capacity() * sizeof(uint32_t) + raw_.capacity() * sizeof(double);
  }

private:
  std::vector<double> raw_;
};

namespace detail {
/// Widest part of an element a reorder moves at a time: the scratch holds this many bytes per
/// moved particle, whatever the element's size (a 36-byte F or C moves in three passes).
constexpr size_t kGatherSliceBytes = 12;

/// An element's bytes. Eigen's fixed-size matrices are plain arrays of scalars, though not
/// trivially copyable by the standard's rule: their scalars are what is copied.
template <class T> char* elementBytes(T& v) {
  if constexpr (std::is_trivially_copyable_v<T>) {
    return reinterpret_cast<char*>(&v);
  } else {
    static_assert(sizeof(T) == sizeof(typename T::Scalar) * size_t(T::SizeAtCompileTime), "a padded matrix");
    return reinterpret_cast<char*>(v.data());
  }
}

/// Moves bytes [O, O + W) of every element in `moved` through `tmp` (the slice at O), then the
/// next slice. Each slice's width is a constant, so its memcpy compiles to a few moves: with the
/// width known only at run time, each was a call into libc's memmove (Vajont's binning 1.32 ->
/// 1.07 s over its first 2 s, docs/throughput.md).
template <size_t O, size_t W, class T, class Slice>
void gatherSlices(std::vector<T>& a, const uint32_t* from, const tbb::blocked_range<size_t>& moved, Slice* tmp) {
  constexpr size_t w = std::min(W, sizeof(T) - O);
  const size_t b = moved.begin();
  tbb::parallel_for(moved, [&](const auto& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) std::memcpy(tmp[i - b].bytes, elementBytes(a[from[i]]) + O, w);
  });
  tbb::parallel_for(moved, [&](const auto& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) std::memcpy(elementBytes(a[i]) + O, tmp[i - b].bytes, w);
  });
  if constexpr (O + W < sizeof(T)) gatherSlices<O + W, W>(a, from, moved, tmp);
}
} // namespace detail

/// a[i] <- a[perm.index[i]] for i in [perm.begin, perm.end) (the identity elsewhere), through
/// scratch.values. An element wider than detail::kGatherSliceBytes moves slice by slice (one
/// random pass over the array per slice), so the scratch stays at 12 bytes per moved particle:
/// measured 40 -> 16 bytes per particle with the permutation (docs/throughput.md, "Memory").
template <class T>
void gatherInPlace(std::vector<T>& a, const Permutation& perm, ReorderScratch& scratch) {
  const size_t b = perm.begin;
  const uint32_t* from = perm.index.data();
  const tbb::blocked_range<size_t> moved(b, perm.end, 8192);
  if constexpr (sizeof(T) <= detail::kGatherSliceBytes) {
    T* tmp = scratch.values<T>(perm.end - b); // tmp[i - b] for i in the range
    tbb::parallel_for(moved, [&](const auto& r) {
      for (size_t i = r.begin(); i != r.end(); ++i) new (tmp + (i - b)) T(a[from[i]]);
    });
    tbb::parallel_for(moved, [&](const auto& r) { std::copy(tmp + (r.begin() - b), tmp + (r.end() - b), a.begin() + r.begin()); });
  } else {
    constexpr size_t W = detail::kGatherSliceBytes;
    struct Slice {
      char bytes[W]; // moved by memcpy only
    };
    detail::gatherSlices<0, W>(a, from, moved, scratch.values<Slice>(perm.end - b));
  }
}

/// Keep the elements whose mask entry is non-zero, preserving order.
template <class T>
void compactInPlace(std::vector<T>& a, const std::vector<uint8_t>& keep) {
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i)
    if (keep[i]) a[n++] = a[i];
  a.resize(n);
}

} // namespace talus
