// Random numbers that are the same with every standard library, for seeded generators whose
// output must be reproducible across platforms (synthetic floors, simulated fleets).
// std::mt19937's output sequence is fixed by the standard; std::uniform_*_distribution and
// std::normal_distribution are not (their mapping differs between libstdc++, libc++ and MSVC),
// so the mapping to ranges and to a normal distribution is done here by hand.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

namespace fleetmerge {

class PortableRng {
 public:
  explicit PortableRng(std::uint32_t seed) : engine_(seed) {}

  // Uniform in [lo, hi).
  double Uniform(double lo, double hi) {
    return lo + (hi - lo) * (static_cast<double>(engine_()) / 4294967296.0);  // / 2^32
  }
  // Uniform integer in [lo, hi] (hi >= lo).
  int UniformInt(int lo, int hi) {
    return std::min(hi, lo + static_cast<int>(std::floor(Uniform(0.0, hi - lo + 1.0))));
  }
  // Normal with mean 0 and standard deviation `sigma` (Box-Muller; one draw per call keeps the
  // stream position independent of earlier calls' parity). sigma == 0 draws nothing.
  double Normal(double sigma) {
    if (sigma == 0.0) return 0.0;
    const double u1 = 1.0 - Uniform(0.0, 1.0);  // (0, 1]: log is finite
    const double u2 = Uniform(0.0, 1.0);
    return sigma * std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }
  // A seed for a sub-generator (one per robot, say), drawn from this stream.
  std::uint32_t NextSeed() { return engine_(); }

 private:
  std::mt19937 engine_;
};

}  // namespace fleetmerge
