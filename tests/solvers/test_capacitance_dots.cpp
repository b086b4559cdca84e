// The Woodbury capacitance's dot products in one pass (src/solvers/
// capacitance_dots.hpp): every product u_i . z_j and x . u_j equals the exact
// sum to the 4-lane sum's rounding bound, (n/4 + 2) eps sum |a_i b_i| (n = 1003
// entries a rank; asserted at 1e-13 sum |a_i b_i|, above the bound's 6e-14 on
// 2 ranks and 3e-14 on 1), with the vector kernel and the portable one; a
// changed row's transposed products u_j . z_r have the bits of row j formed
// whole (the capacitance is the same whichever rows changed), and the blocks
// of 256 entries do not move a lane (1003 is no multiple of 4 or 256). A
// symmetric row (z_j = A^-1 u_j, A symmetric) forms each pair's product
// once, u_a . z_b with a <= b: its entries have the bits of the upper
// triangle of the rows formed whole, those below of the other rows, and
// the entries that another row forms are left 0.
// pcsim-test-ranks: 1 2
#include <gtest/gtest.h>
#include <petscvec.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "../../src/solvers/capacitance_dots.hpp"
#include "pcsim/core/error.hpp"

namespace {

constexpr PetscInt kLocal = 1003;
constexpr std::size_t kTerms = 6;

Vec filled(double phase) {
  Vec v;
  PCSIM_PETSC(VecCreateMPI(PETSC_COMM_WORLD, kLocal, PETSC_DETERMINE, &v));
  PetscInt lo, hi;
  PCSIM_PETSC(VecGetOwnershipRange(v, &lo, &hi));
  PetscScalar* a;
  PCSIM_PETSC(VecGetArray(v, &a));
  for (PetscInt i = lo; i < hi; ++i) a[i - lo] = std::sin(phase + 0.37 * static_cast<double>(i));
  PCSIM_PETSC(VecRestoreArray(v, &a));
  return v;
}

// The exact product (long double here, to well below the bound) and
// sum |a_i b_i|, over the ranks.
void exact_dot(Vec a, Vec b, double& dot, double& size) {
  const PetscScalar *x, *y;
  PCSIM_PETSC(VecGetArrayRead(a, &x));
  PCSIM_PETSC(VecGetArrayRead(b, &y));
  long double sum = 0, abs_sum = 0;
  for (PetscInt i = 0; i < kLocal; ++i) {
    sum += static_cast<long double>(x[i]) * y[i];
    abs_sum += std::abs(static_cast<long double>(x[i]) * y[i]);
  }
  PCSIM_PETSC(VecRestoreArrayRead(b, &y));
  PCSIM_PETSC(VecRestoreArrayRead(a, &x));
  double local[2] = {static_cast<double>(sum), static_cast<double>(abs_sum)}, all[2];
  MPI_Allreduce(local, all, 2, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  dot = all[0];
  size = all[1];
}

struct Vectors {
  pcsim::solvers::CapacitanceDots in;
  Vectors() {
    for (std::size_t j = 0; j < kTerms; ++j) {
      in.us.push_back(filled(0.1 + static_cast<double>(j)));
      in.zs.push_back(filled(2.3 * static_cast<double>(j) - 1.0));
    }
    in.x = filled(7.0);
  }
  ~Vectors() {
    for (Vec& v : in.us) VecDestroy(&v);
    for (Vec& v : in.zs) VecDestroy(&v);
    VecDestroy(&in.x);
  }
};

// Rows 1 and 4 with their transposed products and x . u_j: each product
// within 'relative' sum |a_i b_i| of the exact one, and every product with
// entries (a 0 = 0 would prove nothing).
void expect_rows_near_exact(pcsim::solvers::CapacitanceDots& in, bool vector_kernel,
                            double relative) {
  in.rows = {1, 4};
  in.transposed = true;
  std::vector<double> uz, zu, ux;
  pcsim::solvers::capacitance_dots(in, uz, zu, ux, vector_kernel);
  ASSERT_EQ(uz.size(), 2 * kTerms);
  ASSERT_EQ(zu.size(), 2 * kTerms);
  ASSERT_EQ(ux.size(), kTerms);
  const auto near = [relative](Vec a, Vec b, double value) {
    double dot = 0, size = 0;
    exact_dot(a, b, dot, size);
    EXPECT_NEAR(value, dot, relative * size);
    EXPECT_GT(size, 0.1);
  };
  for (std::size_t r = 0; r < 2; ++r)
    for (std::size_t j = 0; j < kTerms; ++j) {
      const std::size_t i = in.rows[r];
      near(in.us[i], in.zs[j], uz[r * kTerms + j]);
      near(in.us[j], in.zs[i], zu[r * kTerms + j]);
    }
  for (std::size_t j = 0; j < kTerms; ++j) near(in.x, in.us[j], ux[j]);
}

TEST(CapacitanceDots, EachProductToTheLaneSumsBound) {
  Vectors v;
  for (bool vector_kernel : {true, false}) expect_rows_near_exact(v.in, vector_kernel, 1e-13);
}

TEST(CapacitanceDots, ChangedRowsHaveTheBitsOfRowsFormedWhole) {
  Vectors v;
  std::vector<double> whole, unused, ux;
  Vec x = v.in.x;  // no x . u_j here; given back for ~Vectors
  v.in.x = nullptr;
  for (std::size_t i = 0; i < kTerms; ++i) v.in.rows.push_back(i);
  pcsim::solvers::capacitance_dots(v.in, whole, unused, ux);  // whole(i, j) = u_i . z_j
  EXPECT_TRUE(unused.empty());
  EXPECT_TRUE(ux.empty());
  v.in.rows = {2, 5};
  v.in.transposed = true;
  std::vector<double> uz, zu;
  pcsim::solvers::capacitance_dots(v.in, uz, zu, ux);
  for (std::size_t r = 0; r < 2; ++r)
    for (std::size_t j = 0; j < kTerms; ++j) {
      const std::size_t i = v.in.rows[r];
      EXPECT_EQ(uz[r * kTerms + j], whole[i * kTerms + j]);
      EXPECT_EQ(zu[r * kTerms + j], whole[j * kTerms + i]);
    }
  v.in.x = x;
}

TEST(CapacitanceDots, SymmetricRowsFormEachPairOnce) {
  Vectors v;
  Vec x = v.in.x;  // no x . u_j here; given back for ~Vectors
  v.in.x = nullptr;
  for (bool vector_kernel : {true, false}) {
    std::vector<double> whole, unused, ux;
    v.in.symmetric = false;
    v.in.rows.clear();
    for (std::size_t i = 0; i < kTerms; ++i) v.in.rows.push_back(i);
    pcsim::solvers::capacitance_dots(v.in, whole, unused, ux, vector_kernel);
    v.in.symmetric = true;
    for (const std::vector<std::size_t>& rows :
         {v.in.rows, std::vector<std::size_t>{2, 5}, std::vector<std::size_t>{0}}) {
      v.in.rows = rows;
      std::vector<double> uz, zu;
      pcsim::solvers::capacitance_dots(v.in, uz, zu, ux, vector_kernel);
      EXPECT_TRUE(zu.empty());
      ASSERT_EQ(uz.size(), rows.size() * kTerms);
      for (std::size_t r = 0; r < rows.size(); ++r)
        for (std::size_t j = 0; j < kTerms; ++j) {
          const std::size_t i = rows[r];
          const bool other_row = j < i && std::find(rows.begin(), rows.end(), j) != rows.end();
          const double expected =
              other_row ? 0.0 : (j >= i ? whole[i * kTerms + j] : whole[j * kTerms + i]);
          EXPECT_EQ(uz[r * kTerms + j], expected) << "row " << i << ", term " << j;
        }
    }
  }
  v.in.x = x;
}

// Sparse u's (CapacitanceDots::sparse_us, the FE catenary's terms): each
// term's entries at a few global indices on every rank, at the ranks' first
// and last rows among them; the dense u's set to the same entries.
struct SparseTerms {
  std::vector<std::vector<PetscInt>> index;
  std::vector<std::vector<double>> weight;
  explicit SparseTerms(Vectors& v) {
    PetscInt size = 0;
    PCSIM_PETSC(VecGetSize(v.in.us[0], &size));
    for (std::size_t j = 0; j < kTerms; ++j) {
      const auto t = static_cast<PetscInt>(j);
      index.push_back({t, kLocal - 1, kLocal, size / 2 + 3 * t, size - 1 - t});
      std::sort(index.back().begin(), index.back().end());
      index.back().erase(std::unique(index.back().begin(), index.back().end()), index.back().end());
      weight.emplace_back();
      for (std::size_t p = 0; p < index.back().size(); ++p)
        weight.back().push_back(0.5 + static_cast<double>(j) - 0.25 * static_cast<double>(p));
      Vec u = v.in.us[j];
      PCSIM_PETSC(VecSet(u, 0.0));
      PetscInt lo, hi;
      PCSIM_PETSC(VecGetOwnershipRange(u, &lo, &hi));
      for (std::size_t p = 0; p < index.back().size(); ++p)
        if (index.back()[p] >= lo && index.back()[p] < hi)
          PCSIM_PETSC(VecSetValue(u, index.back()[p], weight.back()[p], INSERT_VALUES));
      PCSIM_PETSC(VecAssemblyBegin(u));
      PCSIM_PETSC(VecAssemblyEnd(u));
    }
  }
  void use(pcsim::solvers::CapacitanceDots& in) const {
    in.sparse_us.clear();
    for (std::size_t j = 0; j < kTerms; ++j)
      in.sparse_us.push_back({index[j].data(), weight[j].data(), index[j].size()});
  }
};

// Each sparse product sums at most 5 entries, then the ranks' parts: within
// 6 eps sum |a_i b_i| of the exact one (asserted at 1e-15, above that
// bound's 6.7e-16 with eps = 2^-53).
TEST(CapacitanceDots, SparseUsGiveEveryProductToTheirEntriesBound) {
  Vectors v;
  const SparseTerms terms(v);
  terms.use(v.in);
  expect_rows_near_exact(v.in, true, 1e-15);
}

// The sparse path keeps the dense one's layouts and bits between rows: a
// changed row's transposed products are those of the rows formed whole, and
// a symmetric row forms each pair once (u_a . z_b, a <= b; other rows' 0).
TEST(CapacitanceDots, SparseRowsKeepTheLayoutsOfTheDenseOnes) {
  Vectors v;
  const SparseTerms terms(v);
  terms.use(v.in);
  Vec x = v.in.x;  // no x . u_j here; given back for ~Vectors
  v.in.x = nullptr;
  std::vector<double> whole, unused, ux;
  for (std::size_t i = 0; i < kTerms; ++i) v.in.rows.push_back(i);
  pcsim::solvers::capacitance_dots(v.in, whole, unused, ux);
  const std::vector<std::size_t> rows{2, 5};
  v.in.rows = rows;
  for (bool symmetric : {false, true}) {
    v.in.symmetric = symmetric;
    v.in.transposed = !symmetric;
    std::vector<double> uz, zu;
    pcsim::solvers::capacitance_dots(v.in, uz, zu, ux);
    for (std::size_t r = 0; r < rows.size(); ++r)
      for (std::size_t j = 0; j < kTerms; ++j) {
        const std::size_t i = rows[r];
        if (!symmetric) {
          EXPECT_EQ(uz[r * kTerms + j], whole[i * kTerms + j]);
          EXPECT_EQ(zu[r * kTerms + j], whole[j * kTerms + i]);
          continue;
        }
        const bool other_row = j < i && std::find(rows.begin(), rows.end(), j) != rows.end();
        const double expected =
            other_row ? 0.0 : (j >= i ? whole[i * kTerms + j] : whole[j * kTerms + i]);
        EXPECT_EQ(uz[r * kTerms + j], expected) << "row " << i << ", term " << j;
      }
  }
  v.in.x = x;
}

}  // namespace
