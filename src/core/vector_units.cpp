#include "pcsim/core/vector_units.hpp"

namespace pcsim {

const VectorUnits& vector_units() {
  static const VectorUnits units = [] {
    VectorUnits u;
#if defined(__x86_64__) || defined(__i386__)
    __builtin_cpu_init();
    u.avx2_fma = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    u.f16c = __builtin_cpu_supports("f16c");
#endif
    return u;
  }();
  return units;
}

}  // namespace pcsim
