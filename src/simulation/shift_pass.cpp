// A modal window's shift pass (shift_pass.hpp).
#include "shift_pass.hpp"

#include <cmath>

#include "pcsim/core/vector_units.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define PCSIM_X86_KERNEL 1
#endif

namespace pcsim::simulation {

namespace {

constexpr int kLanes = 8;

// The 8 lanes' sums, added in a tree of 3 (both kernels).
double lane_tree(const double* l) {
  return ((l[0] + l[4]) + (l[2] + l[6])) + ((l[1] + l[5]) + (l[3] + l[7]));
}

// One row's body (the multiples of 8) and tail for the three vectors.
void portable_row(const float* row, long m, const double* const x[3], double sums[3]) {
  const long body = m / kLanes * kLanes;
  for (int s = 0; s < 3; ++s) {
    double lane[kLanes] = {};
    for (long k = 0; k < body; k += kLanes)
      for (int l = 0; l < kLanes; ++l)
        lane[l] = std::fma(static_cast<double>(row[k + l]), x[s][k + l], lane[l]);
    sums[s] = lane_tree(lane);
  }
}

void finish_row(const float* row, long m, const double* const x[3], double sums[3],
                double* const y[3], long i) {
  for (long k = m / kLanes * kLanes; k < m; ++k)
    for (int s = 0; s < 3; ++s) sums[s] = std::fma(static_cast<double>(row[k]), x[s][k], sums[s]);
  for (int s = 0; s < 3; ++s) y[s][i] = sums[s];
}

#ifdef PCSIM_X86_KERNEL
// Each 8 floats of a row are loaded once, widened to two 4-lane halves, and
// serve the three vectors: six independent chains of fused multiply-adds.
__attribute__((target("avx2,fma"))) void vector_rows(const float* P, long m,
                                                     const double* const x[3], double* const y[3],
                                                     long first, long last) {
  const long body = m / kLanes * kLanes;
  alignas(32) double lanes[3][kLanes];
  for (long i = first; i < last; ++i) {
    const float* row = P + i * m;
    __m256d u0 = _mm256_setzero_pd(), u1 = u0, v0 = u0, v1 = u0, a0 = u0, a1 = u0;
    for (long k = 0; k < body; k += kLanes) {
      const __m256 f = _mm256_loadu_ps(row + k);
      const __m256d lo = _mm256_cvtps_pd(_mm256_castps256_ps128(f));
      const __m256d hi = _mm256_cvtps_pd(_mm256_extractf128_ps(f, 1));
      u0 = _mm256_fmadd_pd(lo, _mm256_loadu_pd(x[0] + k), u0);
      u1 = _mm256_fmadd_pd(hi, _mm256_loadu_pd(x[0] + k + 4), u1);
      v0 = _mm256_fmadd_pd(lo, _mm256_loadu_pd(x[1] + k), v0);
      v1 = _mm256_fmadd_pd(hi, _mm256_loadu_pd(x[1] + k + 4), v1);
      a0 = _mm256_fmadd_pd(lo, _mm256_loadu_pd(x[2] + k), a0);
      a1 = _mm256_fmadd_pd(hi, _mm256_loadu_pd(x[2] + k + 4), a1);
    }
    _mm256_store_pd(lanes[0], u0);
    _mm256_store_pd(lanes[0] + 4, u1);
    _mm256_store_pd(lanes[1], v0);
    _mm256_store_pd(lanes[1] + 4, v1);
    _mm256_store_pd(lanes[2], a0);
    _mm256_store_pd(lanes[2] + 4, a1);
    double sums[3] = {lane_tree(lanes[0]), lane_tree(lanes[1]), lane_tree(lanes[2])};
    finish_row(row, m, x, sums, y, i);
  }
}
#endif  // PCSIM_X86_KERNEL

}  // namespace

void shift_rows_portable(const float* P, long m, const double* const x[3], double* const y[3],
                         long first, long last) {
  for (long i = first; i < last; ++i) {
    double sums[3];
    portable_row(P + i * m, m, x, sums);
    finish_row(P + i * m, m, x, sums, y, i);
  }
}

void shift_rows(const float* P, long m, const double* const x[3], double* const y[3], long first,
                long last) {
#ifdef PCSIM_X86_KERNEL
  if (vector_units().avx2_fma) return vector_rows(P, m, x, y, first, last);
#endif
  shift_rows_portable(P, m, x, y, first, last);
}

}  // namespace pcsim::simulation
