// Per-step outputs reduced where the particles are (runs on ranks, docs/scaling.md): each process
// turns its own particles into a part (integer sums, maxima), and rank 0 merges every part. The
// sums are exact fixed-point integers, so a merged figure does not depend on how the particles
// were split between processes or threads, and one process gets the same bytes from its one part.
//
// The fixed point: a quantity bounded by B (from the largest particle mass, speed and coordinate
// over all processes, PartBounds) is counted in units of 2^e with B / 2^e <= 2^bits, e a whole
// number, so scaling by 2^-e is exact and only the rounding of each particle's value to a unit is
// lost (below 2^-bits of the largest particle's value).
#pragma once

#include "engine/simulation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string_view>
#include <vector>

namespace talus {

/// The largest particle mass (kg), squared speed (m²/s²) and |coordinate| (m, local frame) over
/// all processes: what fixes the units of a step's parts.
struct PartBounds {
  double maxMass = 0, maxSpeed2 = 0, maxCoord = 0;
  /// This process's own maxima (a pass over its particles).
  static PartBounds of(const Simulation& sim);
};

/// The exponent e of a unit 2^e that counts values up to `bound` in at most 2^bits units.
inline int unitExponent(double bound, int bits) {
  if (!(bound > 0) || !std::isfinite(bound)) return 0;
  int e;
  std::frexp(bound, &e); // bound < 2^e
  return e - bits;
}

/// Bits of the largest particle's value: kCellBits where many particles add up in one int64 (a
/// map cell, a path's bin: 2^23 of the largest fit), kTotalBits where each particle is an int64
/// and the sum 128 bits (a series total).
constexpr int kCellBits = 40, kTotalBits = 62;

/// The largest particle volume (m^3) `b` allows: its largest mass over the least dense material.
inline double volumeBound(const Simulation& sim, const PartBounds& b) {
  double invRho = 0;
  for (const auto* g : sim.groups()) invRho = std::max(invRho, 1.0 / g->density());
  return b.maxMass * invRho;
}

/// 2^e as a double; multiplying by it is exact (no libm call in the loops).
inline double powerOfTwo(int e) { return std::ldexp(1.0, e); }
/// v times `perUnit` (= 2^-e), |v perUnit| < 2^63, as whole units: exact scaling, then the
/// fraction dropped (toward zero, one instruction; the same wherever it runs).
inline int64_t toUnits(double v, double perUnit) { return int64_t(v * perUnit); }

/// Bytes appended to and read from a part, in the order written.
class PartWriter {
public:
  explicit PartWriter(std::vector<char>& out) : out_(out) {}
  template <class T> void put(const T& v) {
    const size_t at = out_.size();
    out_.resize(at + sizeof(T));
    std::memcpy(out_.data() + at, &v, sizeof(T));
  }

private:
  std::vector<char>& out_;
};

class PartReader {
public:
  explicit PartReader(std::string_view in) : in_(in) {}
  /// @throw std::runtime_error past the part's end (parts made by another build)
  template <class T> T get() {
    if (at_ + sizeof(T) > in_.size()) throw std::runtime_error("a step's part from another rank is shorter than expected");
    T v;
    std::memcpy(&v, in_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  bool done() const { return at_ == in_.size(); }

private:
  std::string_view in_;
  size_t at_ = 0;
};

/// Appends `p` after its length, so several parts share one buffer.
inline void putSized(std::vector<char>& out, const std::vector<char>& p) {
  PartWriter(out).put(uint64_t(p.size()));
  out.insert(out.end(), p.begin(), p.end());
}
/// The next part putSized wrote in `rest`, which then starts after it.
/// @throw std::runtime_error if `rest` is cut short
inline std::string_view takeSized(std::string_view& rest) {
  const uint64_t n = PartReader(rest).get<uint64_t>();
  if (rest.size() - sizeof n < n) throw std::runtime_error("a step's part from another rank is cut short");
  const std::string_view p = rest.substr(sizeof n, n);
  rest.remove_prefix(sizeof n + n);
  return p;
}

} // namespace talus
