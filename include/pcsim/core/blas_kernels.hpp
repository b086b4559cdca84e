// The kernels of the BLAS behind libblas.so.3, and their choice where BLIS
// would take its generic ones.
//
// BLIS (scripts/setup-deps.sh) picks its kernels by the processor at its
// first call. BLIS 0.9 (Debian 12) does not know newer processors, AMD's
// family 26 (Zen 5) among them, and there falls back to its generic kernels:
// 14.3-14.8 GFlop/s on the window shift's dgemm against 83.5 with its
// AVX-512 ones on the same machine (runs/bench_blas.sh, BLIS_ARCH_TYPE=0) (docs/benchmarks.md,
// "BLIS on a processor it does not know"). select_blas_kernels(), before any BLAS call, asks BLIS
// which kernels it would take (its library libblis.so.4 beside the loaded libblas.so.3) and, where
// those are the generic ones, sets BLIS_ARCH_TYPE to BLIS's own skx kernels (AVX-512 F, DQ, BW and
// VL) or haswell kernels (AVX2 and FMA) by what the processor has. A BLIS_ARCH_TYPE of the user's
// wins; another BLAS is left alone. BLIS reads BLIS_ARCH_TYPE once, at its first call: where that
// may have come already (Python with numpy imported before pcsim: numpy's import starts BLIS), it
// is not set, and text() says which BLIS_ARCH_TYPE to set before the process starts.
#pragma once

#include <string>

namespace pcsim {

struct BlasKernels {
  std::string library;   // the loaded libblas.so.3, its real path ("" if none was found)
  bool is_blis = false;  // that library is BLIS (it lies in a folder of BLIS's)
  std::string blis;      // BLIS's version, where BLIS was asked
  std::string detected;  // the kernels BLIS's own detection takes ("" if not asked)
  std::string kernels;   // the kernels in use: detected, chosen, or "BLIS_ARCH_TYPE=N" the user's
  bool chosen = false;   // pcsim set BLIS_ARCH_TYPE
  std::string too_late;  // BLIS had started: the BLIS_ARCH_TYPE pcsim would have set, else ""
  std::string text() const;  // one line for logs and records
  // An optimised BLAS: BLIS on kernels other than its generic ones, OpenBLAS
  // or MKL (not the reference BLAS), whose dgemv SLEPc's contiguous basis
  // storage runs well (solvers/modes.cpp, configure_slicing).
  bool optimised() const;
};

// Once per process, before the first BLAS call (main, the Python module);
// blis_started: BLIS may have made its choice already (ask, do not set).
void select_blas_kernels(bool blis_started = false);
// What select_blas_kernels() found (empty fields before it ran).
const BlasKernels& blas_kernels();

}  // namespace pcsim
