#pragma once
/// @file
/// The simulator's own random numbers: xoshiro256** seeded through SplitMix64, with uniform and
/// normal draws written here so that a (scenario, seed) gives the same bytes on every platform
/// (std:: distributions are implementation-defined).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace swlio::sim {

class Rng {
 public:
  explicit Rng(uint64_t seed) {
    uint64_t x = seed;
    for (auto& s : state_) s = SplitMix(x);
  }

  /// Next 64 random bits (xoshiro256**, Blackman & Vigna 2018).
  uint64_t Next() {
    const uint64_t result = Rotl(state_[1] * 5, 7) * 9;
    const uint64_t t = state_[1] << 17;
    state_[2] ^= state_[0];
    state_[3] ^= state_[1];
    state_[1] ^= state_[2];
    state_[0] ^= state_[3];
    state_[2] ^= t;
    state_[3] = Rotl(state_[3], 45);
    return result;
  }

  /// Uniform in [0, 1).
  double Uniform() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  /// Uniform integer in [0, n).
  uint64_t Below(uint64_t n) { return n == 0 ? 0 : Next() % n; }

  /// Standard normal (Box–Muller; the second value is cached).
  double Normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u1 = Uniform();
    while (u1 <= 0.0) u1 = Uniform();
    const double u2 = Uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * std::numbers::pi * u2);
    has_spare_ = true;
    return r * std::cos(2.0 * std::numbers::pi * u2);
  }
  double Normal(double sigma) { return sigma * Normal(); }

 private:
  static uint64_t Rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  static uint64_t SplitMix(uint64_t& x) {
    uint64_t z = (x += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

  uint64_t state_[4];
  double spare_ = 0.0;
  bool has_spare_ = false;
};

/// Stateless hash of integers to [0, 1): deterministic per-ray / per-cell noise.
inline double HashUniform(uint64_t a, uint64_t b, uint64_t c = 0) {
  uint64_t z = a * 0x9E3779B97F4A7C15ull ^ (b + 0x632BE59BD9B4E019ull) * 0xBF58476D1CE4E5B9ull ^
               (c + 0x85EBCA77C2B2AE63ull) * 0x94D049BB133111EBull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}

/// Draws tied to a key (one LiDAR ray, one packet) instead of to their place in a stream
/// (common random numbers): a key gets the same numbers however many draws were made for
/// other keys. A drive simulated with and without a disturbance that adds or removes returns
/// (people, vibration, rain) then differs by the disturbance alone; drawn from one stream, the
/// first ray that hits differently reshuffles the noise of every later ray, and that alone moved
/// `loop943` seed 1's yaw after 24 s by 0.03-0.11° (bench/README, "The field").
class KeyedDraws {
 public:
  KeyedDraws(uint64_t seed, uint64_t key) : seed_(seed), key_(key) {}

  double Uniform() { return HashUniform(seed_, key_, count_++); }
  /// A normal draw of standard deviation `sigma` (Box–Muller, one per two uniforms).
  double Normal(double sigma) {
    const double u1 = std::max(Uniform(), 0x1.0p-53);
    const double u2 = Uniform();
    return sigma * std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
  }

 private:
  uint64_t seed_;
  uint64_t key_;
  uint64_t count_ = 0;
};

}  // namespace swlio::sim
