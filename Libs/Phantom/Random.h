#pragma once
// Deterministic pseudo-random numbers for the phantom. Every value is a pure function of
// (seed, stream, draw number) or of a hash of its inputs, so results never depend on thread
// scheduling, and one part of the phantom drawing more numbers never shifts another part.
#include <cmath>
#include <cstdint>

namespace colonmap {
namespace phantom {

// SplitMix64 finaliser: a fast, well-mixed 64-bit hash.
inline std::uint64_t Mix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

inline std::uint64_t Hash(std::uint64_t a, std::uint64_t b) { return Mix64(Mix64(a) ^ (b * 0xD1B54A32D192ED03ull)); }
inline std::uint64_t Hash(std::uint64_t a, std::uint64_t b, std::uint64_t c) { return Hash(Hash(a, b), c); }

// Uniform in [0,1) from the top 53 bits of a hash.
inline double HashToUnit(std::uint64_t h) { return static_cast<double>(h >> 11) * (1.0 / 9007199254740992.0); }

// Approximately standard normal from one hash: Irwin-Hall sum of four 16-bit uniforms, scaled to
// unit variance. Bounded to +-3.46 sigma; cheap enough to call once per voxel.
inline double HashToNormal(std::uint64_t h) {
  const double sum = static_cast<double>(h & 0xFFFF) + static_cast<double>((h >> 16) & 0xFFFF) +
                     static_cast<double>((h >> 32) & 0xFFFF) + static_cast<double>(h >> 48);
  return (sum / 65536.0 - 2.0) * 1.7320508075688772;
}

// Sequential generator, one per purpose ("stream"), used while building the anatomy.
class Rng {
 public:
  Rng(std::uint64_t seed, std::uint64_t stream) : state_(Hash(seed, stream)) {}
  std::uint64_t Next() { return Mix64(state_ += 0x9E3779B97F4A7C15ull); }
  double Uniform() { return HashToUnit(Next()); }
  double Uniform(double a, double b) { return a + (b - a) * Uniform(); }
  // Integer in [lo, hi].
  int Integer(int lo, int hi) {
    const int v = lo + static_cast<int>(Uniform() * (hi - lo + 1));
    return v > hi ? hi : v;
  }
  double Sign() { return Uniform() < 0.5 ? -1.0 : 1.0; }

 private:
  std::uint64_t state_;
};

}  // namespace phantom
}  // namespace colonmap
