// Seeded random numbers that are the same on every platform and standard library: SplitMix64
// (Steele, Lea & Flood, OOPSLA 2014) and Box–Muller for normals, never std::*_distribution
// (whose algorithms the C++ standard leaves to each library). Every generator is local to its
// user; streams are derived from (seed, purpose, index) so that adding a piece to a scene does not
// reshuffle the noise of every frame.
#pragma once

#include <cstdint>

namespace comic::render {

// One 64-bit value mixed from a seed and up to two tags (SplitMix64's finaliser).
uint64_t MixSeed(uint64_t seed, uint64_t tag_a, uint64_t tag_b = 0);

class Random {
 public:
  explicit Random(uint64_t seed) : state_(seed) {}
  Random(uint64_t seed, uint64_t tag_a, uint64_t tag_b = 0) : state_(MixSeed(seed, tag_a, tag_b)) {}

  uint64_t Next();
  // Uniform in [0, 1) with 53 random bits.
  double Uniform();
  // Uniform in [low, high).
  double Uniform(double low, double high) { return low + (high - low) * Uniform(); }
  // Uniform integer in [0, n) (n > 0).
  int Index(int n);
  // Standard normal (Box–Muller; each pair of uniforms gives two normals).
  double Normal();

 private:
  uint64_t state_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

// A smooth random function of time: values at integer knots are uniform in [-1, 1] from (seed,
// stream, knot), joined by cosine interpolation, so it is continuous (for motion-blur sub-frames)
// and the same whatever times are asked. `period` is the knot spacing.
double SmoothNoise(uint64_t seed, uint64_t stream, double time, double period);

}  // namespace comic::render
