#include "pcsim/simulation/modal_basis.hpp"

#include <petsctime.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <memory>

#include "modal_basis_internal.hpp"
#include "pcsim/assembly/wind_terms.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/solvers/spectrum.hpp"

namespace pcsim::simulation {

using catenary::basis_row_key;
using catenary::ModalData;
using namespace modal_detail;

namespace {

// Row index of a key in the sorted keys (the key must be there).
std::size_t row_of(const std::vector<long>& keys, long key) {
  const auto it = std::lower_bound(keys.begin(), keys.end(), key);
  if (it == keys.end() || *it != key) throw SolverError("reduced basis: a needed row is missing");
  return static_cast<std::size_t>(it - keys.begin());
}

// Solves with K_T (one Cholesky factorisation, solvers::use_line_cholesky).
class StiffnessSolver {
 public:
  explicit StiffnessSolver(Mat K) {
    PC pc;
    PCSIM_PETSC(KSPCreate(PetscObjectComm(reinterpret_cast<PetscObject>(K)), &ksp_));
    PCSIM_PETSC(KSPSetOptionsPrefix(ksp_, "modal_static_"));
    PCSIM_PETSC(KSPSetOperators(ksp_, K, K));
    PCSIM_PETSC(KSPSetType(ksp_, KSPPREONLY));
    PCSIM_PETSC(KSPGetPC(ksp_, &pc));
    solvers::use_line_cholesky(pc);
    PCSIM_PETSC(KSPSetFromOptions(ksp_));
    PCSIM_PETSC(KSPSetUp(ksp_));
  }
  ~StiffnessSolver() { KSPDestroy(&ksp_); }
  StiffnessSolver(const StiffnessSolver&) = delete;
  StiffnessSolver& operator=(const StiffnessSolver&) = delete;
  void solve(Vec b, Vec y) const { PCSIM_PETSC(KSPSolve(ksp_, b, y)); }

 private:
  KSP ksp_ = nullptr;
};

// The droppers' static shapes psi_d = K^-1 b_d, b_d = [-e; e] on the ends'
// positions (e: the bar's direction at the static configuration), their M
// products and rows.
class DropperShapes {
 public:
  DropperShapes(const assembly::CatenarySystem& system, Vec x, const Operators& op,
                const StiffnessSolver& K, const RowGather& rows, const std::vector<long>& keys);
  ~DropperShapes() {
    if (psi_) VecDestroyVecs(static_cast<PetscInt>(count_), &psi_);
    if (Mpsi_) VecDestroyVecs(static_cast<PetscInt>(count_), &Mpsi_);
  }
  DropperShapes(const DropperShapes&) = delete;
  DropperShapes& operator=(const DropperShapes&) = delete;
  std::size_t count() const { return count_; }
  Vec vector(std::size_t d) const { return psi_[d]; }
  // phi^T M psi_d for every d.
  std::vector<double> mass_products(Vec phi) const;
  const Eigen::MatrixXd& rows() const { return rows_; }
  const Eigen::MatrixXd& psi_M_psi() const { return psi_M_psi_; }
  const Eigen::MatrixXd& flexibility() const { return flexibility_; }

 private:
  std::size_t count_ = 0;
  Vec* psi_ = nullptr;
  Vec* Mpsi_ = nullptr;
  Eigen::MatrixXd rows_;         // rows of psi (n_rows x count)
  Eigen::MatrixXd psi_M_psi_;    // psi^T M psi
  Eigen::MatrixXd flexibility_;  // b^T psi = b^T K^-1 b
};

DropperShapes::DropperShapes(const assembly::CatenarySystem& system, Vec x, const Operators& op,
                             const StiffnessSolver& K, const RowGather& rows,
                             const std::vector<long>& keys) {
  const auto& mesh = system.mesh();
  const auto& L = system.layout();
  const std::vector<double> values = system.all_node_values(x);
  std::vector<int> bars;
  for (std::size_t b = 0; b < mesh.bars.size(); ++b)
    if (mesh.bars[b].slack != catenary::SlackCriterion::none) bars.push_back(static_cast<int>(b));
  count_ = bars.size();
  if (count_ == 0) return;
  PCSIM_PETSC(VecDuplicateVecs(x, static_cast<PetscInt>(count_), &psi_));
  PCSIM_PETSC(VecDuplicateVecs(x, static_cast<PetscInt>(count_), &Mpsi_));
  Vec b;
  PCSIM_PETSC(VecDuplicate(x, &b));
  rows_.resize(static_cast<long>(rows.size()), static_cast<long>(count_));
  std::vector<Eigen::Vector3d> direction(count_);
  for (std::size_t d = 0; d < count_; ++d) {
    const auto& nodes = mesh.bars[bars[d]].nodes;
    Eigen::Vector3d e;
    for (int c = 0; c < 3; ++c) e[c] = values[6 * nodes[1] + c] - values[6 * nodes[0] + c];
    direction[d] = e.normalized();
    PCSIM_PETSC(VecSet(b, 0.0));
    if (L.rank() == 0)
      for (int end = 0; end < 2; ++end)
        for (int c = 0; c < 3; ++c) {
          const PetscInt g = L.global_dof(nodes[end], c);
          if (g >= 0) PCSIM_PETSC(VecSetValue(b, g, (end ? 1 : -1) * direction[d][c], ADD_VALUES));
        }
    PCSIM_PETSC(VecAssemblyBegin(b));
    PCSIM_PETSC(VecAssemblyEnd(b));
    K.solve(b, psi_[d]);
    PCSIM_PETSC(MatMult(op.M, psi_[d], Mpsi_[d]));
    rows.gather(psi_[d], rows_.col(static_cast<long>(d)).data());
  }
  PCSIM_PETSC(VecDestroy(&b));
  const long n = static_cast<long>(count_);
  psi_M_psi_.resize(n, n);
  for (long d = 0; d < n; ++d)
    PCSIM_PETSC(VecMDot(Mpsi_[d], n, psi_, psi_M_psi_.col(d).data()));  // symmetric
  // b_e^T psi_d: elongation of bar e under psi_d, from the rows at its ends.
  flexibility_.resize(n, n);
  for (long e = 0; e < n; ++e) {
    const auto& nodes = mesh.bars[bars[e]].nodes;
    for (long d = 0; d < n; ++d) {
      double dl = 0;
      for (int c = 0; c < 3; ++c)
        dl += direction[e][c] * (rows_(row_of(keys, basis_row_key(nodes[1], c)), d) -
                                 rows_(row_of(keys, basis_row_key(nodes[0], c)), d));
      flexibility_(e, d) = dl;
    }
  }
}

std::vector<double> DropperShapes::mass_products(Vec phi) const {
  std::vector<double> c(count_);
  if (count_ > 0) PCSIM_PETSC(VecMDot(phi, static_cast<PetscInt>(count_), Mpsi_, c.data()));
  return c;
}

// Under a mean wind, phi^T C phi of each mode (C: the wires' aerodynamic
// damping, assembly/wind_terms.hpp); nothing without wind.
class WindDamping {
 public:
  explicit WindDamping(const assembly::CatenarySystem& system) {
    if (system.mesh().conditions.wind.any()) C_ = assembly::aerodynamic_damping_matrix(system);
  }
  ~WindDamping() { MatDestroy(&C_); }
  WindDamping(const WindDamping&) = delete;
  WindDamping& operator=(const WindDamping&) = delete;
  void append(Vec phi, std::vector<double>& out) const {
    if (C_) out.push_back(assembly::quadratic_form(C_, phi));
  }

 private:
  Mat C_ = nullptr;
};

// g_i = (K^-1)_zz at every contact-wire node, contact_wire_nodes() (0 where z is fixed).
std::vector<double> contact_compliance(const assembly::CatenarySystem& system,
                                       const StiffnessSolver& K) {
  const auto& mesh = system.mesh();
  const auto& L = system.layout();
  std::vector<double> g;
  Vec e = system.create_vector(), y = system.create_vector();
  PetscInt lo, hi;
  PCSIM_PETSC(VecGetOwnershipRange(e, &lo, &hi));
  for (int node : catenary::contact_wire_nodes(mesh)) {
    const PetscInt dof = L.global_dof(node, 2);
    if (dof < 0) {
      g.push_back(0.0);
      continue;
    }
    PCSIM_PETSC(VecSet(e, 0.0));
    if (dof >= lo && dof < hi) PCSIM_PETSC(VecSetValue(e, dof, 1.0, INSERT_VALUES));
    PCSIM_PETSC(VecAssemblyBegin(e));
    PCSIM_PETSC(VecAssemblyEnd(e));
    K.solve(e, y);
    double compliance = 0;
    if (dof >= lo && dof < hi) PCSIM_PETSC(VecGetValues(y, 1, &dof, &compliance));
    MPI_Allreduce(MPI_IN_PLACE, &compliance, 1, MPI_DOUBLE, MPI_SUM, system.comm());
    g.push_back(compliance);
  }
  PCSIM_PETSC(VecDestroy(&e));
  PCSIM_PETSC(VecDestroy(&y));
  return g;
}

template <typename Matrix>
std::vector<double> row_major(const Matrix& A) {
  std::vector<double> out(static_cast<std::size_t>(A.size()));
  for (long i = 0; i < A.rows(); ++i)
    for (long j = 0; j < A.cols(); ++j) out[i * A.cols() + j] = A(i, j);
  return out;
}

}  // namespace

ModalData compute_modal_data(assembly::CatenarySystem& system, Vec x, double max_frequency_hz,
                             bool full_shapes, const ModalProgress& progress, Mat shift) {
  PetscLogDouble t0, t1;
  PetscTime(&t0);
  const auto& mesh = system.mesh();
  const bool complete = max_frequency_hz <= 0;
  ModalData data;
  data.cutoff_hz = max_frequency_hz;
  data.row_keys = catenary::reduced_basis_rows(mesh, full_shapes);
  Operators op(system, x);
  const auto& wind = mesh.conditions.wind;
  Mat loads = wind.any() && wind.turbulence.on ? assembly::turbulence_load_matrix(system) : nullptr;
  const RowGather rows(system, data.row_keys, loads);
  MatDestroy(&loads);  // (the gather holds it)
  WindDamping wind_damping(system);
  std::unique_ptr<StiffnessSolver> K;
  std::unique_ptr<DropperShapes> shapes;
  if (!complete) {
    K = std::make_unique<StiffnessSolver>(op.K);
    shapes = std::make_unique<DropperShapes>(system, x, op, *K, rows, data.row_keys);
  }
  std::vector<std::vector<double>> columns, mass_products;
  std::unique_ptr<ShiftProducts> shift_products;  // every vector, for the window's shift
  if (shift) shift_products = std::make_unique<ShiftProducts>(op.M, shift);
  auto sink = [&](double lambda, Vec phi) {
    data.omega2.push_back(lambda);
    if (shift_products) shift_products->append(phi);
    columns.emplace_back(rows.size());
    rows.gather(phi, columns.back().data());
    if (shapes) mass_products.push_back(shapes->mass_products(phi));
    wind_damping.append(phi, data.wind_damping);
  };
  const double omega_max = 2 * M_PI * max_frequency_hz;
  data.max_relative_residual = complete ? stream_all_modes_dense(op, sink)
                                        : stream_modes(op, omega_max * omega_max, sink, progress);
  const std::size_t n_rows = data.row_keys.size(), m = data.modes();
  data.mode_rows.resize(n_rows * m);
  for (std::size_t k = 0; k < m; ++k)
    for (std::size_t i = 0; i < n_rows; ++i) data.mode_rows[i * m + k] = columns[k][i];
  if (shapes && shapes->count() > 0) {
    const std::size_t nd = shapes->count();
    data.shape_rows = row_major(shapes->rows());
    data.mode_shape_mass.resize(m * nd);
    for (std::size_t k = 0; k < m; ++k)
      std::copy(mass_products[k].begin(), mass_products[k].end(),
                data.mode_shape_mass.begin() + k * nd);
    data.shape_mass = row_major(shapes->psi_M_psi());
    data.shape_flexibility = row_major(shapes->flexibility());
  }
  if (K && !mesh.contact_wire_list().empty())
    data.contact_compliance = contact_compliance(system, *K);
  if (shift_products) {
    if (shapes)
      for (std::size_t d = 0; d < shapes->count(); ++d) shift_products->append(shapes->vector(d));
    data.shift_products = shift_products->compute(x);
  }
  PetscTime(&t1);
  data.wall_time_s = t1 - t0;
  return data;
}

}  // namespace pcsim::simulation
