// The reduced basis's column blocks (order_columns_by_block, and the Ritz
// vectors group by group of shapes in assemble_basis): a structure of two
// parts that share no row, with identical parts (the Ritz values of one part
// equal the other's: one Rayleigh-Ritz over every shape mixes them), against
// the generalized eigenvalues of the whole problem computed apart.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "pcsim/catenary/mesh.hpp"
#include "pcsim/catenary/reduced_basis.hpp"

using namespace pcsim::catenary;

namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

std::vector<double> flat(const RowMatrix& a) {
  return std::vector<double>(a.data(), a.data() + a.size());
}

// Two identical parts: rows 0-2 and 3-5, modes alternating between them
// (part of mode k: k % 2) at 1..6 Hz, two shapes each (shapes 0, 1 and 2, 3).
constexpr long kRows = 6, kModes = 6, kShapes = 4;

long part_of_row(long r) {
  return r < 3 ? 0 : 1;
}
long part_of_mode(long k) {
  return k % 2;
}
long part_of_shape(long s) {
  return s < 2 ? 0 : 1;
}

ModalData two_part_data() {
  std::srand(11);
  ModalData d;
  d.cutoff_hz = 6.5;
  for (long k = 0; k < kModes; ++k) d.omega2.push_back(std::pow(2 * M_PI * (k + 1), 2));
  for (long r = 0; r < kRows; ++r) d.row_keys.push_back(3 * r + 2);
  const RowMatrix part_rows = RowMatrix::Random(3, 3), part_shapes = RowMatrix::Random(3, 2);
  const RowMatrix part_C = 0.1 * RowMatrix::Random(3, 2), A = RowMatrix::Random(2, 2);
  RowMatrix modes = RowMatrix::Zero(kRows, kModes), shapes = RowMatrix::Zero(kRows, kShapes);
  RowMatrix C = RowMatrix::Zero(kModes, kShapes);
  for (long r = 0; r < kRows; ++r)
    for (long k = 0; k < kModes; ++k)
      if (part_of_row(r) == part_of_mode(k)) modes(r, k) = part_rows(r % 3, k / 2);
  for (long r = 0; r < kRows; ++r)
    for (long s = 0; s < kShapes; ++s)
      if (part_of_row(r) == part_of_shape(s)) shapes(r, s) = part_shapes(r % 3, s % 2);
  for (long k = 0; k < kModes; ++k)
    for (long s = 0; s < kShapes; ++s)
      if (part_of_mode(k) == part_of_shape(s)) C(k, s) = part_C(k / 2, s % 2);
  const Eigen::VectorXd w2 = Eigen::Map<const Eigen::VectorXd>(d.omega2.data(), kModes);
  RowMatrix mass = C.transpose() * C, flexibility = C.transpose() * w2.asDiagonal() * C;
  for (long p = 0; p < 2; ++p) {  // each part's M-complement of full rank
    mass.block(2 * p, 2 * p, 2, 2) += A * A.transpose() + RowMatrix::Identity(2, 2);
    flexibility.block(2 * p, 2 * p, 2, 2) += 1e4 * RowMatrix::Identity(2, 2) + A * A.transpose();
  }
  d.mode_rows = flat(modes);
  d.shape_rows = flat(shapes);
  d.mode_shape_mass = flat(C);
  d.shape_mass = flat(mass);
  d.shape_flexibility = flat(flexibility);
  return d;
}

ModalSettings settings() {
  ModalSettings s;
  s.max_frequency_hz = 6.5;
  s.dropper_shapes = true;
  s.contact_flexibility = false;
  return s;
}

}  // namespace

TEST(ReducedBasisBlocks, TwoPartsEachOnItsOwnColumns) {
  const ModalData d = two_part_data();
  const ReducedBasis b = assemble_basis(d, CatenaryMesh{}, settings());
  const long c = static_cast<long>(b.size());
  ASSERT_EQ(c, kModes + kShapes);  // every mode and a Ritz vector per shape
  ASSERT_EQ(b.column_blocks, (std::vector<long>{0, 5, 10}));
  const Eigen::Map<const RowMatrix> rows(b.rows.data(), kRows, c);
  for (long r = 0; r < kRows; ++r) {  // a part's rows are zero outside its block
    const long lo = b.column_blocks[part_of_row(r)], hi = b.column_blocks[part_of_row(r) + 1];
    for (long k = 0; k < c; ++k)
      if (k < lo || k >= hi) EXPECT_EQ(rows(r, k), 0.0) << "row " << r << ", column " << k;
  }
  // Each block: its part's modes ascending (1, 3, 5 Hz; 2, 4, 6 Hz), then its Ritz vectors.
  for (long p = 0; p < 2; ++p)
    for (long i = 0; i < 3; ++i)
      EXPECT_EQ(b.omega2[5 * p + i], d.omega2[2 * i + p]) << "part " << p << ", mode " << i;
  // The Ritz values: those of Kp x = w Mp x over every shape, computed apart
  // (each twice, the parts being identical). Entries ~1e4 rounded in other
  // orders: measured 6.7e-16 relative; 15 x that for other compilers' orders.
  const Eigen::Map<const RowMatrix> C(d.mode_shape_mass.data(), kModes, kShapes);
  const Eigen::VectorXd w2 = Eigen::Map<const Eigen::VectorXd>(d.omega2.data(), kModes);
  const Eigen::MatrixXd Mp =
      Eigen::Map<const RowMatrix>(d.shape_mass.data(), kShapes, kShapes) - C.transpose() * C;
  const Eigen::MatrixXd Kp =
      Eigen::Map<const RowMatrix>(d.shape_flexibility.data(), kShapes, kShapes) -
      C.transpose() * w2.asDiagonal() * C;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> whole(Kp, Mp);
  std::vector<double> ritz = {b.omega2[3], b.omega2[4], b.omega2[8], b.omega2[9]};
  std::sort(ritz.begin(), ritz.end());
  for (long j = 0; j < kShapes; ++j)
    EXPECT_NEAR(ritz[j], whole.eigenvalues()[j], 1e-14 * whole.eigenvalues()[j]) << j;
  EXPECT_EQ(b.omega2[3], b.omega2[8]);  // identical parts, the same arithmetic
  EXPECT_EQ(b.omega2[4], b.omega2[9]);
}

TEST(ReducedBasisBlocks, ColumnsReorderedWithTheirData) {
  ReducedBasis b;
  b.omega2 = {1, 2, 3, 4};
  b.wind_damping = {0.1, 0.2, 0.3, 0.4};
  b.row_keys = {2, 5, 8};
  b.rows = {1, 0, 2, 0,   // columns 0 and 2 ...
            3, 0, 4, 0,   // ...
            0, 5, 0, 6};  // columns 1 and 3
  order_columns_by_block(b);
  EXPECT_EQ(b.column_blocks, (std::vector<long>{0, 2, 4}));
  EXPECT_EQ(b.omega2, (std::vector<double>{1, 3, 2, 4}));
  EXPECT_EQ(b.wind_damping, (std::vector<double>{0.1, 0.3, 0.2, 0.4}));
  EXPECT_EQ(b.rows, (std::vector<double>{1, 2, 0, 0, 3, 4, 0, 0, 0, 0, 5, 6}));
}

TEST(ReducedBasisBlocks, OneBlockOrAShiftLeftAsTheyAre) {
  ReducedBasis joined;
  joined.omega2 = {1, 2, 3};
  joined.row_keys = {2, 5};
  joined.rows = {1, 0, 2,   // columns 0 and 2, ...
                 0, 3, 4};  // 1 and 2: one block
  order_columns_by_block(joined);
  EXPECT_EQ(joined.column_blocks, (std::vector<long>{0, 3}));
  EXPECT_EQ(joined.rows, (std::vector<double>{1, 0, 2, 0, 3, 4}));
  ReducedBasis shifted;  // a moving window's: its shift is over the columns as they are
  shifted.omega2 = {1, 2};
  shifted.row_keys = {2, 5};
  shifted.rows = {0, 1, 2, 0};
  shifted.shift = {1, 0, 0, 1};
  order_columns_by_block(shifted);
  EXPECT_EQ(shifted.column_blocks, (std::vector<long>{0, 2}));
  EXPECT_EQ(shifted.rows, (std::vector<double>{0, 1, 2, 0}));
}

// assemble_basis(ModalData&&) forms the basis's rows in the data's own
// storage where the data left room for them (the modal data builder and the
// cache's reader do) and the basis is at least as wide as the data: a first
// run's basis then holds one copy of its rows where it peaks, not two. The
// basis is the same, bit for bit, as the one assembled from a copy.
TEST(ReducedBasisBlocks, MovedDataFormTheBasisInTheirOwnRows) {
  // 6.5 Hz: every mode and a Ritz vector per shape (10 columns); 3.5 Hz: the
  // three lowest modes (7 >= 6 columns, the kept ones moved within each
  // row); 1.5 Hz: one mode (5 < 6 columns: copied).
  for (double cutoff : {6.5, 3.5, 1.5})
    for (bool room : {true, false}) {
      ModalSettings s = settings();
      s.max_frequency_hz = cutoff;
      const ModalData copy = two_part_data();
      const ReducedBasis expected = assemble_basis(copy, CatenaryMesh{}, s);
      ModalData data = two_part_data();
      if (room) data.mode_rows.reserve(data.mode_rows.size() + data.shape_rows.size());
      const double* storage = data.mode_rows.data();
      const ReducedBasis b = assemble_basis(std::move(data), CatenaryMesh{}, s);
      EXPECT_EQ(b.rows, expected.rows) << cutoff << " Hz, room " << room;
      EXPECT_EQ(b.omega2, expected.omega2) << cutoff << " Hz, room " << room;
      EXPECT_EQ(b.column_blocks, expected.column_blocks) << cutoff << " Hz, room " << room;
      const bool in_place = room && b.size() >= static_cast<std::size_t>(kModes);
      EXPECT_EQ(b.rows.data() == storage, in_place) << cutoff << " Hz, room " << room;
    }
}
