// Seeded random numbers that are the same on every platform (the standard
// distributions are not specified bit for bit): irregular wires, roof motion.
#pragma once

#include <random>

namespace pcsim {

// Uniform in [0, 1) from a 64-bit Mersenne twister: its top 53 bits.
inline double unit_random(std::mt19937_64& gen) {
  return static_cast<double>(gen() >> 11) * (1.0 / 9007199254740992.0);
}

}  // namespace pcsim
