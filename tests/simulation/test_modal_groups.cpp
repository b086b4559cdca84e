// The reduced basis's modes of a structure in parts that share no element
// (src/simulation/modal_basis_groups.cpp, stream_modes in
// modal_basis_modes.cpp), on 1, 2 and 3 ranks. K and M: two fixed-fixed
// spring-mass chains of 240 and 210 DOFs (each a group of its own at a
// least group of 100 DOFs, the runs' 2000 scaled down), a chain of 30 and
// four single springs (small: pooled in one group), their DOFs shuffled
// over the global numbering. Checked against the chains' analytic
// spectrum, lambda_j = (2k/m)(1 - cos(j pi / (n + 1))):
//  - the groups: their DOFs, in the order of their first DOF;
//  - every eigenvalue below the cut-off, ascending, in chunks of about 60
//    of the larger chain's 100 modes below it (stream_modes's chunk_modes,
//    the runs' 800 scaled down), each vector M-normalised and zero outside
//    its group;
//  - the same eigenvalues as the whole structure at once
//    (-pcsim_debug_modes_whole), and a raised cut-off's modes.
// (The cut-off is 0.37 of the chains' spectrum. At 0.003 of it, with
// chains of 2400 and 2100 DOFs, SLEPc's slicing left relative errors of
// 1e-5 to 1e-2 in the lowest eigenvalues, the parts and the whole alike,
// residuals of 8e-4; a catenary's basis comes to 6e-11: test_modal_parts.sh.)
// pcsim-test-ranks: 1 2 3
#include <gtest/gtest.h>
#include <petscmat.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "../../src/simulation/modal_basis_internal.hpp"

namespace {

using pcsim::simulation::modal_detail::component_groups;
using pcsim::simulation::modal_detail::Operators;
using pcsim::simulation::modal_detail::stream_modes;

struct Chain {
  PetscInt dofs;
  double stiffness;  // of each spring (the masses are 1)
};
// The chains A, B, C and four single DOFs (a spring to ground each).
const std::vector<Chain> kChains = {{240, 1.0}, {210, 1.3}, {30, 0.7}};
const std::vector<double> kSingles = {0.2, 0.5, 1.0, 2.0};
// 100 of A's modes are below it, 75 of B's, 16 of C's, 3 singles.
const double kLambdaMax = 2.0 * (1.0 - std::cos(M_PI * 100.5 / 241.0));
constexpr double kChunk = 60;
constexpr long kMinGroup = 100;

class ModalGroupsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    PetscInt first = 0;
    for (const Chain& c : kChains) {
      parts_.emplace_back();
      for (PetscInt i = 0; i < c.dofs; ++i) parts_.back().push_back(first + i);
      first += c.dofs;
    }
    for (std::size_t s = 0; s < kSingles.size(); ++s) parts_.push_back({first++});
    global_.resize(static_cast<std::size_t>(first));  // position in the parts -> global DOF
    std::iota(global_.begin(), global_.end(), PetscInt{0});
    std::shuffle(global_.begin(), global_.end(), std::mt19937(7));  // the same on every rank
    group_.resize(global_.size());
    for (std::size_t p = 0; p < parts_.size(); ++p)
      for (PetscInt at : parts_[p]) group_[global_[at]] = std::min<std::size_t>(p, 2);
    for (Mat* A : {&K_, &M_})
      MatCreateAIJ(PETSC_COMM_WORLD, PETSC_DECIDE, PETSC_DECIDE, first, first, 3, nullptr, 3,
                   nullptr, A);
    PetscMPIInt rank;
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    if (rank == 0) set_entries();
    for (Mat A : {K_, M_}) {
      MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY);
      MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY);
      MatSetOption(A, MAT_SYMMETRIC, PETSC_TRUE);
    }
  }
  void TearDown() override {
    MatDestroy(&K_);
    MatDestroy(&M_);
  }
  void set_entries() {
    for (std::size_t c = 0; c < kChains.size(); ++c) {
      const double k = kChains[c].stiffness;
      const auto& dofs = parts_[c];
      for (std::size_t i = 0; i < dofs.size(); ++i) {
        const PetscInt g = global_[dofs[i]];
        MatSetValue(K_, g, g, 2 * k, ADD_VALUES);
        MatSetValue(M_, g, g, 1.0, ADD_VALUES);
        if (i + 1 == dofs.size()) continue;
        const PetscInt h = global_[dofs[i + 1]];
        MatSetValue(K_, g, h, -k, ADD_VALUES);
        MatSetValue(K_, h, g, -k, ADD_VALUES);
      }
    }
    for (std::size_t s = 0; s < kSingles.size(); ++s) {
      const PetscInt g = global_[parts_[kChains.size() + s][0]];
      MatSetValue(K_, g, g, kSingles[s], ADD_VALUES);
      MatSetValue(M_, g, g, 1.0, ADD_VALUES);
    }
  }
  std::vector<double> analytic_below(double lambda_max) const {
    std::vector<double> lambdas;
    for (const Chain& c : kChains)
      for (PetscInt j = 1; j <= c.dofs; ++j) {
        const double l = 2 * c.stiffness * (1 - std::cos(M_PI * j / (c.dofs + 1.0)));
        if (l <= lambda_max) lambdas.push_back(l);
      }
    for (double s : kSingles)
      if (s <= lambda_max) lambdas.push_back(s);
    std::sort(lambdas.begin(), lambdas.end());
    return lambdas;
  }
  // The group of global DOF g: 0 (A), 1 (B) or 2 (the pool of C and the singles).
  std::size_t group_of(PetscInt g) const { return group_[g]; }
  Mat K_ = nullptr, M_ = nullptr;
  std::vector<std::vector<PetscInt>> parts_;  // positions of each chain and single DOF
  std::vector<PetscInt> global_;
  std::vector<std::size_t> group_;  // of each global DOF
};

// Every rank's indices of a group, gathered and sorted.
std::vector<PetscInt> gathered(const std::vector<PetscInt>& owned) {
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  int count = static_cast<int>(owned.size());
  std::vector<int> counts(size), offsets(size, 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, PETSC_COMM_WORLD);
  std::partial_sum(counts.begin(), counts.end() - 1, offsets.begin() + 1);
  std::vector<PetscInt> all(static_cast<std::size_t>(offsets.back() + counts.back()));
  MPI_Allgatherv(owned.data(), count, MPIU_INT, all.data(), counts.data(), offsets.data(), MPIU_INT,
                 PETSC_COMM_WORLD);
  std::sort(all.begin(), all.end());
  return all;
}

TEST_F(ModalGroupsTest, EachLargePartAloneTheSmallOnesTogether) {
  const auto groups = component_groups(K_, kMinGroup);
  ASSERT_EQ(groups.size(), 3u);
  std::vector<std::vector<PetscInt>> expected(3);  // A, B, the pool of C and the singles
  for (std::size_t p = 0; p < parts_.size(); ++p)
    for (PetscInt at : parts_[p]) expected[std::min<std::size_t>(p, 2)].push_back(global_[at]);
  for (auto& e : expected) std::sort(e.begin(), e.end());
  std::sort(expected.begin(), expected.end(),
            [](const auto& a, const auto& b) { return a.front() < b.front(); });
  PetscInt lo, hi;
  MatGetOwnershipRange(K_, &lo, &hi);
  for (std::size_t g = 0; g < 3; ++g) {
    for (PetscInt i : groups[g]) EXPECT_TRUE(i >= lo && i < hi) << "group " << g;
    EXPECT_EQ(gathered(groups[g]), expected[g]) << "group " << g;
  }
}

TEST_F(ModalGroupsTest, TheAnalyticSpectrumInAscendingOrder) {
  const Operators op(K_, M_);
  const std::vector<double> expected = analytic_below(kLambdaMax);
  ASSERT_EQ(expected.size(), 100u + 75u + 16u + 3u);
  std::vector<double> lambdas;
  long worst_outside = 0;
  double worst_norm = 0;
  Vec Mphi;
  MatCreateVecs(M_, &Mphi, nullptr);
  const auto sink = [&](double lambda, Vec phi) {
    lambdas.push_back(lambda);
    MatMult(M_, phi, Mphi);
    PetscScalar mnorm;
    VecDot(phi, Mphi, &mnorm);
    worst_norm = std::max(worst_norm, std::abs(PetscRealPart(mnorm) - 1));
    // Nonzero entries outside the group of its largest one.
    PetscInt at;
    PetscReal largest;
    VecMax(phi, &at, &largest);
    const std::size_t group = group_of(at);
    PetscInt lo, hi;
    VecGetOwnershipRange(phi, &lo, &hi);
    const PetscScalar* a;
    VecGetArrayRead(phi, &a);
    long outside = 0;
    for (PetscInt g = lo; g < hi; ++g)
      if (a[g - lo] != 0.0 && group_of(g) != group) ++outside;
    VecRestoreArrayRead(phi, &a);
    MPI_Allreduce(MPI_IN_PLACE, &outside, 1, MPI_LONG, MPI_SUM, PETSC_COMM_WORLD);
    worst_outside = std::max(worst_outside, outside);
  };
  long last_done = -1, last_total = -1, calls = 0;
  int parts = 0;
  const auto progress = [&](long done, long total, int p) {
    last_done = done;
    last_total = total;
    parts = p;
    ++calls;
  };
  const double residual = stream_modes(op, 0.0, kLambdaMax, sink, progress, kChunk, kMinGroup);
  VecDestroy(&Mphi);
  ASSERT_EQ(lambdas.size(), expected.size());
  EXPECT_TRUE(std::is_sorted(lambdas.begin(), lambdas.end()));
  double worst = 0;
  for (std::size_t j = 0; j < expected.size(); ++j)
    worst = std::max(worst, std::abs(lambdas[j] - expected[j]) / expected[j]);
  // SLEPc's tolerance is 1e-12 (solvers::configure_slicing), relative to
  // the shifted operator: the worst relative error came out 8.1e-12,
  // 5.0e-12 and 3.5e-13 on 1, 2 and 3 ranks (MUMPS's orderings differ);
  // a margin of 12 over the worst.
  EXPECT_LT(worst, 1e-10);
  EXPECT_LT(worst_norm, 1e-14);  // normalised to M: 6.7e-16 measured
  // ||K phi - lambda M phi|| / (lambda ||M phi||): 2.0e-10, 3.1e-11 and
  // 1.0e-10 measured on 1, 2, 3 ranks; a margin of 5.
  EXPECT_LT(residual, 1e-9);
  EXPECT_EQ(worst_outside, 0);  // exact zeros: each mode copied into a zeroed vector
  EXPECT_EQ(parts, 3);
  EXPECT_EQ(calls, 3);  // the count, then each of two chunks
  EXPECT_EQ(last_done, last_total);
  EXPECT_EQ(last_total, static_cast<long>(expected.size()));
}

TEST_F(ModalGroupsTest, AsTheWholeStructureAtOnceAndAboveACutoff) {
  const Operators op(K_, M_);
  std::vector<double> apart, whole, above;
  const double raised_from = 0.5 * kLambdaMax;
  stream_modes(
      op, 0.0, kLambdaMax, [&](double l, Vec) { apart.push_back(l); }, {}, kChunk, kMinGroup);
  stream_modes(
      op, raised_from, kLambdaMax, [&](double l, Vec) { above.push_back(l); }, {}, kChunk,
      kMinGroup);
  PetscOptionsSetValue(nullptr, "-pcsim_debug_modes_whole", "true");
  stream_modes(
      op, 0.0, kLambdaMax, [&](double l, Vec) { whole.push_back(l); }, {}, kChunk, kMinGroup);
  PetscOptionsClearValue(nullptr, "-pcsim_debug_modes_whole");
  ASSERT_EQ(apart.size(), whole.size());
  double worst = 0;
  for (std::size_t j = 0; j < whole.size(); ++j)
    worst = std::max(worst, std::abs(apart[j] - whole[j]) / whole[j]);
  // Both to SLEPc's 1e-12: 7.8e-12, 5.0e-12 and 9.7e-13 apart on 1, 2, 3
  // ranks; a margin of 12.
  EXPECT_LT(worst, 1e-10);
  // A raised cut-off's modes: those above the old one, none twice.
  const auto first_above = std::upper_bound(apart.begin(), apart.end(), raised_from);
  ASSERT_EQ(above.size(), static_cast<std::size_t>(apart.end() - first_above));
  for (std::size_t j = 0; j < above.size(); ++j)
    EXPECT_NEAR(above[j], first_above[j], 1e-10 * above[j]);
}

}  // namespace
