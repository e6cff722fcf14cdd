#include "render/random.h"

#include <cmath>

namespace comic::render {
namespace {

uint64_t Finalise(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

constexpr uint64_t kGolden = 0x9e3779b97f4a7c15ULL;

}  // namespace

uint64_t MixSeed(uint64_t seed, uint64_t tag_a, uint64_t tag_b) {
  return Finalise(Finalise(Finalise(seed + kGolden) + tag_a * kGolden) + tag_b);
}

uint64_t Random::Next() {
  state_ += kGolden;
  return Finalise(state_);
}

double Random::Uniform() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }

int Random::Index(int n) { return static_cast<int>(Uniform() * n); }

double Random::Normal() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  // 1 - Uniform() lies in (0, 1], so the logarithm is finite.
  const double radius = std::sqrt(-2.0 * std::log(1.0 - Uniform()));
  const double angle = 2.0 * M_PI * Uniform();
  spare_ = radius * std::sin(angle);
  has_spare_ = true;
  return radius * std::cos(angle);
}

double SmoothNoise(uint64_t seed, uint64_t stream, double time, double period) {
  const double x = time / period;
  const double knot = std::floor(x);
  const double f = x - knot;
  const auto value = [&](double k) {
    Random random(seed, stream, static_cast<uint64_t>(static_cast<int64_t>(k)));
    return 2.0 * random.Uniform() - 1.0;
  };
  const double w = 0.5 - 0.5 * std::cos(M_PI * f);
  return (1.0 - w) * value(knot) + w * value(knot + 1.0);
}

}  // namespace comic::render
