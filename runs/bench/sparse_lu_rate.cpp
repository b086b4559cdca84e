// The flexible DSA-380's block factorised three ways (docs/benchmarks.md,
// "The flexible DSA-380's block as a sparse value"): Eigen's SparseLU (COLAMD),
// KLU's klu_factor (src/solvers/klu_lu.cpp: what the cheap path runs) and
// klu_refactor (the pivot order of an earlier factorisation kept: the cheap
// path keeps that of the block's J0 value, src/solvers/klu_lu.hpp), and their solves, on the
// model's sparse step tangent K + 2000 C + 4e6 M at its static equilibrium (meshes/pantographs/
// dsa380_flexible.yaml, 120 N at 1.2 m, uplift characteristic on). Mean of
// 2000 each. Build pcsim first (build/), then from the repository root:
//   g++ -O2 -DNDEBUG -std=c++17 -Iinclude -I/usr/include/eigen3 -I/usr/include/suitesparse \
//     $(pkg-config --cflags PETSc ompi-cxx) runs/bench/sparse_lu_rate.cpp \
//     build/libpcsim_scene.a build/libpcsim_pantograph.a build/libpcsim_catenary.a \
//     build/libpcsim_core.a -lyaml-cpp -lklu $(pkg-config --libs PETSc ompi-cxx) \
//     -o /tmp/sparse_lu_rate
//   /tmp/sparse_lu_rate
#include <klu.h>

#include <Eigen/SparseLU>
#include <chrono>
#include <cstdio>

#include "pcsim/pantograph/flexible_dsa380.hpp"
#include "pcsim/scene/flexible_dsa380_reader.hpp"

namespace {

using Clock = std::chrono::steady_clock;
constexpr int kRepetitions = 2000;

template <class F>
double mean_us(F&& f) {
  const auto start = Clock::now();
  for (int i = 0; i < kRepetitions; ++i) f();
  return std::chrono::duration<double, std::micro>(Clock::now() - start).count() / kRepetitions;
}

}  // namespace

int main() {
  using namespace pcsim::pantograph;
  const auto params =
      pcsim::scene::read_flexible_dsa380_file("meshes/pantographs/dsa380_flexible.yaml");
  Dsa380Effects effects;
  effects.uplift_characteristic = true;
  FlexibleDsa380Pantograph model(params, effects, 83.3);
  const Eigen::VectorXd q = model.static_equilibrium(120, 1.2);
  const int n = model.dof_count();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  Eigen::SparseMatrix<double> J;
  model.sparse_step_tangent(0, q, zero, zero, 2000, 4e6, J);
  std::printf("block: %d unknowns, %ld entries\n", n, static_cast<long>(J.nonZeros()));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1, 1);
  Eigen::VectorXd x_eigen, x_klu = b;

  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  lu.analyzePattern(J);
  const double eigen_factor = mean_us([&] { lu.factorize(J); });
  const double eigen_solve = mean_us([&] { x_eigen = lu.solve(b); });

  klu_common common;
  klu_defaults(&common);
  int* p = J.outerIndexPtr();
  int* i = J.innerIndexPtr();
  double* v = J.valuePtr();
  klu_symbolic* symbolic = klu_analyze(n, p, i, &common);
  klu_numeric* numeric = klu_factor(p, i, v, symbolic, &common);
  const double klu_fresh = mean_us([&] {
    klu_free_numeric(&numeric, &common);
    numeric = klu_factor(p, i, v, symbolic, &common);
  });
  const double klu_again = mean_us([&] { klu_refactor(p, i, v, symbolic, numeric, &common); });
  const double klu_solved = mean_us([&] {
    x_klu = b;
    klu_solve(symbolic, numeric, n, 1, x_klu.data(), &common);
  });
  std::printf("Eigen SparseLU: factorize %.1f us, solve %.1f us\n", eigen_factor, eigen_solve);
  std::printf("KLU: klu_factor %.1f us, klu_refactor %.1f us, solve %.1f us\n", klu_fresh,
              klu_again, klu_solved);
  std::printf("solutions differ by %.1e (relative)\n", (x_klu - x_eigen).norm() / x_eigen.norm());
  klu_free_numeric(&numeric, &common);
  klu_free_symbolic(&symbolic, &common);
}
