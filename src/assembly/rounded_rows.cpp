#include "pcsim/assembly/rounded_rows.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "pcsim/core/vector_units.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define PCSIM_X86_KERNEL 1
#endif

namespace pcsim::assembly {

namespace {

constexpr double kUnitHalf = 4.8828125e-04;             // 2^-11
constexpr double kUnitSingle = 5.9604644775390625e-08;  // 2^-24
constexpr int kLanes = 8;
constexpr int kRowExponent = 15;  // a row's largest entry scaled into [2^14, 2^15)

// The 8 lanes' sums of a row, added in a tree of 3 (both kernels).
float lane_tree(const float* p) {
  const float q0 = p[0] + p[4], q1 = p[1] + p[5], q2 = p[2] + p[6], q3 = p[3] + p[7];
  return (q0 + q2) + (q1 + q3);
}

float stored_value(std::uint16_t h) {
  return RoundedRows::from_half(h);
}
float stored_value(float v) {
  return v;
}

template <class Stored>
void portable_rows(const Stored* h, long rows, long stride, const float* x, float* y) {
  for (long d = 0; d < rows; ++d) {
    float lane[kLanes] = {};
    const Stored* row = h + d * stride;
    for (long j = 0; j < stride; j += kLanes)
      for (int k = 0; k < kLanes; ++k)
        lane[k] = std::fma(stored_value(row[j + k]), x[j + k], lane[k]);
    y[d] = lane_tree(lane);
  }
}

#ifdef PCSIM_X86_KERNEL
// 8 stored values in float (a half's conversion is exact).
#define PCSIM_LOAD_LANES(p)                                 \
  (std::is_same_v<Stored, float>                            \
       ? _mm256_loadu_ps(reinterpret_cast<const float*>(p)) \
       : _mm256_cvtph_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p))))

// Eight rows at a time share each load of x (eight independent chains of
// fused multiply-adds); each row's lanes are summed as the portable kernel
// sums them (lane_tree).
template <class Stored>
__attribute__((target("avx2,fma,f16c"))) void vector_rows(const Stored* h, long rows, long stride,
                                                          const float* x, float* y) {
  constexpr int kBlock = 8;
  alignas(32) float lanes[kBlock][kLanes];
  long d = 0;
  for (; d + kBlock <= rows; d += kBlock) {
    const Stored* r = h + d * stride;
    __m256 a0 = _mm256_setzero_ps(), a1 = a0, a2 = a0, a3 = a0, a4 = a0, a5 = a0, a6 = a0, a7 = a0;
    for (long j = 0; j < stride; j += kLanes) {
      const __m256 xv = _mm256_loadu_ps(x + j);
      a0 = _mm256_fmadd_ps(PCSIM_LOAD_LANES(r + j), xv, a0);
      a1 = _mm256_fmadd_ps(PCSIM_LOAD_LANES(r + stride + j), xv, a1);
      a2 = _mm256_fmadd_ps(PCSIM_LOAD_LANES(r + 2 * stride + j), xv, a2);
      a3 = _mm256_fmadd_ps(PCSIM_LOAD_LANES(r + 3 * stride + j), xv, a3);
      a4 = _mm256_fmadd_ps(PCSIM_LOAD_LANES(r + 4 * stride + j), xv, a4);
      a5 = _mm256_fmadd_ps(PCSIM_LOAD_LANES(r + 5 * stride + j), xv, a5);
      a6 = _mm256_fmadd_ps(PCSIM_LOAD_LANES(r + 6 * stride + j), xv, a6);
      a7 = _mm256_fmadd_ps(PCSIM_LOAD_LANES(r + 7 * stride + j), xv, a7);
    }
    _mm256_store_ps(lanes[0], a0);
    _mm256_store_ps(lanes[1], a1);
    _mm256_store_ps(lanes[2], a2);
    _mm256_store_ps(lanes[3], a3);
    _mm256_store_ps(lanes[4], a4);
    _mm256_store_ps(lanes[5], a5);
    _mm256_store_ps(lanes[6], a6);
    _mm256_store_ps(lanes[7], a7);
    for (int k = 0; k < kBlock; ++k) y[d + k] = lane_tree(lanes[k]);
  }
  for (; d < rows; ++d) {
    const Stored* r = h + d * stride;
    __m256 a0 = _mm256_setzero_ps();
    for (long j = 0; j < stride; j += kLanes)
      a0 = _mm256_fmadd_ps(PCSIM_LOAD_LANES(r + j), _mm256_loadu_ps(x + j), a0);
    _mm256_store_ps(lanes[0], a0);
    y[d] = lane_tree(lanes[0]);
  }
}

#undef PCSIM_LOAD_LANES
#endif  // PCSIM_X86_KERNEL

}  // namespace

bool RoundedRows::vector_kernel_available() {
#ifdef PCSIM_X86_KERNEL
  return vector_units().avx2_fma && vector_units().f16c;
#else
  return false;
#endif
}

std::uint16_t RoundedRows::to_half(double v) {
  const std::uint16_t sign = std::signbit(v) ? 0x8000 : 0;
  const double a = std::abs(v);
  if (!(a < 65520.0)) throw std::invalid_argument("RoundedRows::to_half: value out of range");
  if (a < 0x1p-14)  // subnormal (or the smallest normal after rounding)
    return static_cast<std::uint16_t>(sign | static_cast<int>(std::nearbyint(a * 0x1p24)));
  int e2 = 0;
  const double fraction = std::frexp(a, &e2);  // a = fraction 2^e2, fraction in [0.5, 1)
  int exponent = e2 - 1;
  int mantissa = static_cast<int>(std::nearbyint((2 * fraction - 1) * 1024));
  if (mantissa == 1024) mantissa = 0, ++exponent;
  return static_cast<std::uint16_t>(sign | ((exponent + 15) << 10) | mantissa);
}

float RoundedRows::from_half(std::uint16_t h) {
  const int exponent = (h >> 10) & 31, mantissa = h & 1023;
  const float magnitude = exponent == 0
                              ? std::ldexp(static_cast<float>(mantissa), -24)
                              : std::ldexp(static_cast<float>(1024 + mantissa), exponent - 25);
  return (h & 0x8000) ? -magnitude : magnitude;
}

// Each row scaled by 2^(15 - E), its largest entry in [2^(E-1), 2^E).
RoundedRows::RoundedRows(const RowMatrix& rows, Precision precision)
    : rows_(rows.rows()),
      cols_(rows.cols()),
      stride_((rows.cols() + kLanes - 1) / kLanes * kLanes) {
  const auto size = static_cast<std::size_t>(rows_ * stride_);
  const bool half = precision == Precision::half;
  if (half)
    halves_.assign(size, 0);
  else
    singles_.assign(size, 0.0f);
  unscale_.assign(static_cast<std::size_t>(rows_), 1.0);
  x_single_.assign(static_cast<std::size_t>(stride_), 0.0f);
  sums_.assign(static_cast<std::size_t>(rows_), 0.0f);
  for (long d = 0; d < rows_; ++d) {
    const double largest = rows.row(d).cwiseAbs().maxCoeff();
    if (!(largest > 0)) continue;  // a zero row stays zero
    int e2 = 0;
    std::frexp(largest, &e2);
    const double scale = std::ldexp(1.0, kRowExponent - e2);
    unscale_[d] = std::ldexp(1.0, e2 - kRowExponent);
    for (long i = 0; i < cols_; ++i) {
      const double v = rows(d, i) * scale;
      if (half)
        halves_[d * stride_ + i] = to_half(v);
      else
        singles_[d * stride_ + i] = static_cast<float>(v);
    }
  }
  // The bound (header): the rounding of b (u_h or u_s relative; a half's
  // 2^-25 absolute below 2^-14 is 2^-39 of the row's largest entry), of x
  // scaled to max |x_i| in [1, 2) (u_s), and of ceil(n/8) fused
  // multiply-adds and 3 additions in float (gamma_K); 2^-100 covers the
  // products of the absolute parts and the float underflows (2^-150).
  const double n = static_cast<double>(std::max(cols_, 1L));
  const double g = rounding_gamma(static_cast<double>(stride_ / kLanes + 3), kUnitSingle);
  const double unit = half ? kUnitHalf : kUnitSingle, absolute = half ? 0x1p-39 : 0.0;
  error_factor_ = unit * (1 + kUnitSingle) + kUnitSingle + g * (1 + unit) * (1 + kUnitSingle) +
                  (1 + g) * absolute * (1 + kUnitSingle) * std::sqrt(n) + 0x1p-100;
}

double RoundedRows::value(long d, long i) const {
  const auto k = static_cast<std::size_t>(d * stride_ + i);
  return (halves_.empty() ? singles_[k] : from_half(halves_[k])) * unscale_[d];
}

std::size_t RoundedRows::bytes() const {
  return halves_.size() * sizeof(std::uint16_t) + singles_.size() * sizeof(float);
}

void RoundedRows::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y, Kernel kernel) const {
  y.resize(rows_);
  // Eigen's vectorised reductions (a loop whose test chains the elements
  // runs one element at a time): finite first, then the largest |x_i|.
  const auto head = x.head(cols_);
  if (!head.allFinite()) {  // as a product in floating point would
    y.setConstant(std::numeric_limits<double>::quiet_NaN());
    return;
  }
  const double largest = cols_ > 0 ? head.cwiseAbs().maxCoeff() : 0.0;
  if (!(largest > 0)) {
    y.setZero();
    return;
  }
  int e2 = 0;
  std::frexp(largest, &e2);                        // x scaled by 2^(1 - e2): max |x_i| in [1, 2)
  const double scale_x = std::ldexp(1.0, 1 - e2);  // a power of two: x[i] * scale_x is exact
  // x_single_'s padding beyond cols_ stays zero (the constructor's).
  for (long i = 0; i < cols_; ++i) x_single_[i] = static_cast<float>(x[i] * scale_x);
  const float* xs = x_single_.data();
  float* sums = sums_.data();
#ifdef PCSIM_X86_KERNEL
  static const bool vector = vector_kernel_available();
  if (kernel == Kernel::automatic && vector) {
    if (halves_.empty())
      vector_rows(singles_.data(), rows_, stride_, xs, sums);
    else
      vector_rows(halves_.data(), rows_, stride_, xs, sums);
  } else
#endif
  {
    if (halves_.empty())
      portable_rows(singles_.data(), rows_, stride_, xs, sums);
    else
      portable_rows(halves_.data(), rows_, stride_, xs, sums);
  }
  const double unscale_x = std::ldexp(1.0, e2 - 1);
  for (long d = 0; d < rows_; ++d) y[d] = static_cast<double>(sums_[d]) * unscale_[d] * unscale_x;
}

}  // namespace pcsim::assembly
