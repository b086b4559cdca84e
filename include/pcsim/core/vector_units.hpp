// The processor's vector units that pcsim's own kernels use (the dropper
// check's rounded rows, the Woodbury capacitance's products), asked once:
// each kernel has a portable twin for a processor without them.
#pragma once

namespace pcsim {

struct VectorUnits {
  bool avx2_fma = false;  // AVX2 with fused multiply-adds (x86-64-v3)
  bool f16c = false;      // half-precision conversions
};

const VectorUnits& vector_units();

}  // namespace pcsim
