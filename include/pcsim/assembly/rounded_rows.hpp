// The rows of a dense matrix stored rounded, in half precision (IEEE
// binary16) or in single precision, each row scaled by a power of two, and
// multiplied by a vector in single precision with a proven error bound: the
// modal dropper check's and records' products (modal_slack_set.cpp). Half
// rows read half the bytes of float rows (the products are bound by the
// level-2 cache's bandwidth); both sum in 8 lanes, which makes their
// rounding bound n/8 times tighter than a product summed in one chain.
//
// Error: for the double vector x, every y_d of multiply() is within
// error_factor() |b_d| |x| of the exact b_d . x (Cauchy-Schwarz on the
// elementwise bound of the rounding of b_d, of x and of the float sums; |x|
// the 2-norm). The sums run in 8 lanes of ceil(n/8) fused multiply-adds
// each, then a tree of 3 additions, on every kernel, so the portable kernel
// gives the same bits as the vector one.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace pcsim::assembly {

// gamma_n = n u / (1 - n u) (Higham): the rounding bound of an n-term sum of
// products with unit roundoff u.
inline double rounding_gamma(double n, double u) {
  return n * u / (1 - n * u);
}

class RoundedRows {
 public:
  using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  enum class Precision { half, single };
  enum class Kernel { automatic, portable };

  RoundedRows() = default;
  RoundedRows(const RowMatrix& rows, Precision precision);

  // y = B x: x scaled by a power of two and rounded to float, each row's
  // products summed in float, y unscaled in double (exactly).
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y,
                Kernel kernel = Kernel::automatic) const;
  // g of the bound |y_d - b_d . x| <= g |b_d| |x|.
  double error_factor() const { return error_factor_; }
  // The stored value of entry (d, i) (the rounded b_di).
  double value(long d, long i) const;
  long rows() const { return rows_; }
  long cols() const { return cols_; }
  std::size_t bytes() const;
  // True if multiply() takes the AVX2/F16C/FMA kernels on this processor.
  static bool vector_kernel_available();

  // The nearest binary16 (ties to even) of |v| < 65520, and its value.
  static std::uint16_t to_half(double v);
  static float from_half(std::uint16_t h);

 private:
  long rows_ = 0, cols_ = 0, stride_ = 0;  // stride_: cols_ padded to a multiple of 8
  // rows_ x stride_ (one of them), row d scaled by 1 / unscale_[d]
  std::vector<std::uint16_t> halves_;
  std::vector<float> singles_;
  std::vector<double> unscale_;  // a power of two per row
  double error_factor_ = 0;
  // x in float (zero beyond cols_) and the row sums: sized once, by the constructor
  mutable std::vector<float> x_single_, sums_;
};

}  // namespace pcsim::assembly
