// The moving window's shift in an assembled basis (assemble_basis, formed in
// the shift products' own storage) against P = T^T G T formed directly, on
// synthetic data: every mode kept or the lower ones only (P smaller than G),
// with and without the droppers' Ritz vectors, the data moved or copied.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "pcsim/catenary/mesh.hpp"
#include "pcsim/catenary/reduced_basis.hpp"

using namespace pcsim::catenary;

namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

constexpr long kModes = 7, kShapes = 3, kRows = 6, kTotal = kModes + kShapes;

std::vector<double> flat(const RowMatrix& a) {
  return std::vector<double>(a.data(), a.data() + a.size());
}

// Modes of frequencies 1..7 Hz, three shapes with an M-complement of full
// rank, random rows and shift products (fixed seed: Eigen's Random uses rand).
ModalData synthetic_data() {
  std::srand(7);
  ModalData d;
  d.cutoff_hz = 7.5;
  for (long k = 0; k < kModes; ++k) d.omega2.push_back(std::pow(2 * M_PI * (k + 1), 2));
  for (long r = 0; r < kRows; ++r) d.row_keys.push_back(3 * r + 2);
  const RowMatrix C = 0.1 * RowMatrix::Random(kModes, kShapes);
  const RowMatrix A = RowMatrix::Random(kShapes, kShapes);
  const Eigen::VectorXd w2 = Eigen::Map<const Eigen::VectorXd>(d.omega2.data(), kModes);
  d.mode_rows = flat(RowMatrix::Random(kRows, kModes));
  d.shape_rows = flat(RowMatrix::Random(kRows, kShapes));
  d.mode_shape_mass = flat(C);
  d.shape_mass = flat(C.transpose() * C + A * A.transpose() + RowMatrix::Identity(3, 3));
  d.shape_flexibility = flat(C.transpose() * w2.asDiagonal() * C + 1e4 * RowMatrix::Identity(3, 3) +
                             A * A.transpose());
  d.shift_products = flat(RowMatrix::Random(kTotal, kTotal));
  return d;
}

// T = [E_keep, -E_keep CX; 0, X] recovered from the basis's rows: the Ritz
// rows are (Psi_rows - Phi_rows C) X, Phi_rows C over the kept modes.
RowMatrix transformation(const ModalData& d, const ReducedBasis& b, long m) {
  const long r = static_cast<long>(b.omega2.size()) - m;
  const Eigen::Map<const RowMatrix> mode_rows(d.mode_rows.data(), kRows, kModes);
  const Eigen::Map<const RowMatrix> shape_rows(d.shape_rows.data(), kRows, kShapes);
  const Eigen::Map<const RowMatrix> C(d.mode_shape_mass.data(), kModes, kShapes);
  const Eigen::Map<const RowMatrix> rows(b.rows.data(), kRows, m + r);
  RowMatrix T = RowMatrix::Zero(kTotal, m + r);
  T.topLeftCorner(m, m).setIdentity();
  if (r == 0) return T;
  const RowMatrix complement = shape_rows - mode_rows.leftCols(m) * C.topRows(m);
  const RowMatrix X = complement.colPivHouseholderQr().solve(RowMatrix(rows.rightCols(r)));
  T.bottomRightCorner(kShapes, r) = X;
  T.topRightCorner(m, r) = -C.topRows(m) * X;
  return T;
}

void check_shift(double cutoff_hz, bool shapes, bool moved) {
  ModalData data = synthetic_data();
  const ModalData copy = data;
  ModalSettings s;
  s.max_frequency_hz = cutoff_hz;
  s.dropper_shapes = shapes;
  s.contact_flexibility = false;
  const CatenaryMesh mesh;
  const ReducedBasis b =
      moved ? assemble_basis(std::move(data), mesh, s) : assemble_basis(data, mesh, s);
  const long m = b.eigenmodes, c = static_cast<long>(b.omega2.size());
  ASSERT_EQ(b.shift.size(), static_cast<std::size_t>(c * c));
  const RowMatrix T = transformation(copy, b, m);
  const Eigen::Map<const RowMatrix> G(copy.shift_products.data(), kTotal, kTotal);
  const RowMatrix expected = T.transpose() * G * T;
  using FloatRows = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const RowMatrix P = Eigen::Map<const FloatRows>(b.shift.data(), c, c).cast<double>();
  // P is stored rounded to float: within 2^-24 of each entry, plus the
  // round-off of the same products in another order (entries ~1: measured
  // 3.3e-16; 30 x that for the X recovered by QR on other compilers).
  const RowMatrix bound = expected.cwiseAbs() * std::ldexp(1.0, -24);
  EXPECT_LE(((P - expected).cwiseAbs() - bound).maxCoeff(), 1e-14)
      << "cut-off " << cutoff_hz << " Hz, shapes " << shapes << ", moved " << moved;
}

}  // namespace

TEST(ReducedBasisShift, EveryModeWithRitzVectors) {
  check_shift(7.5, true, true);
  check_shift(7.5, true, false);
}

TEST(ReducedBasisShift, LowerModesOnly) {
  check_shift(4.5, true, true);  // 4 of 7 modes: P (7 x 7) from G (10 x 10)
  check_shift(4.5, false, true);
  check_shift(4.5, false, false);
}

TEST(ReducedBasisShift, WithoutRitzVectors) {
  check_shift(7.5, false, true);
}
