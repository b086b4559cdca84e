#include "pcsim/assembly/modal_terms.hpp"

#include <mpi.h>

#include <algorithm>

#include "pcsim/assembly/coupled_state.hpp"
#include "pcsim/catenary/elements.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::assembly {

namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The modal part of a vector (every rank: it lives on the last one).
Eigen::VectorXd modal_part(const ModalCatenary& catenary, Vec v) {
  const PetscInt m = catenary.catenary_dofs();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(m);
  if (catenary.on_owner()) {
    const PetscScalar* a;
    PCSIM_PETSC(VecGetArrayRead(v, &a));
    std::copy(a, a + m, x.data());
    PCSIM_PETSC(VecRestoreArrayRead(v, &a));
  }
  MPI_Allreduce(MPI_IN_PLACE, x.data(), static_cast<int>(m), MPI_DOUBLE, MPI_SUM, catenary.comm());
  return x;
}

Eigen::Map<const Eigen::VectorXd> omega2(const ModalCatenary& catenary) {
  return {catenary.basis().omega2.data(), catenary.catenary_dofs()};
}

// Adds a dense modal block (m x m) to J on the owner.
void add_modal_block(const ModalCatenary& catenary, const RowMatrix& block, Mat J) {
  if (!catenary.on_owner()) return;
  const PetscInt m = catenary.catenary_dofs();
  std::vector<PetscInt> modes(m);
  for (PetscInt k = 0; k < m; ++k) modes[k] = k;
  PCSIM_PETSC(MatSetValues(J, m, modes.data(), m, modes.data(), block.data(), ADD_VALUES));
}

}  // namespace

// F_k += cu_k eta_k + cv_k eta_k' + ca_k eta_k'' on the owner (the modes
// lead its rows).
void ModalDiagonalTerm::add_residual(const CoupledState& state, Vec F) {
  if (!catenary_.on_owner()) return;
  const PetscInt m = catenary_.catenary_dofs();
  PetscScalar* f;
  PCSIM_PETSC(VecGetArray(F, &f));
  const auto add = [&](const std::vector<double>& c, Vec x) {
    if (c.empty() || !x) return;
    const PetscScalar* a;
    PCSIM_PETSC(VecGetArrayRead(x, &a));
    for (PetscInt k = 0; k < m; ++k) f[k] += c[k] * a[k];
    PCSIM_PETSC(VecRestoreArrayRead(x, &a));
  };
  add(cu_, state.U);
  add(cv_, state.V);
  add(ca_, state.A);
  PCSIM_PETSC(VecRestoreArray(F, &f));
}

void ModalDiagonalTerm::add_tangent(const CoupledState&, Shifts shifts, Mat J) {
  if (!catenary_.on_owner()) return;
  for (PetscInt k = 0; k < catenary_.catenary_dofs(); ++k) {
    const double value = (cu_.empty() ? 0.0 : cu_[k]) + (cv_.empty() ? 0.0 : shifts.v * cv_[k]) +
                         (ca_.empty() ? 0.0 : shifts.a * ca_[k]);
    PCSIM_PETSC(MatSetValue(J, k, k, value, ADD_VALUES));
  }
}

ModalStiffness::ModalStiffness(ModalCatenary& catenary)
    : ModalDiagonalTerm(catenary, catenary.basis().omega2, {}, {}) {}

double ModalStiffness::energy(const CoupledState&) const {
  const auto& eta = catenary_.eta();
  return 0.5 * eta.dot(omega2(catenary_).cwiseProduct(eta));
}

ModalInertia::ModalInertia(ModalCatenary& catenary)
    : ModalDiagonalTerm(catenary, {}, {}, std::vector<double>(catenary.basis().size(), 1.0)) {}

double ModalInertia::energy(const CoupledState& state) const {
  if (!state.V) return 0;
  return 0.5 * modal_part(catenary_, state.V).squaredNorm();
}

namespace {
std::vector<double> rayleigh(const ModalCatenary& catenary, double alpha, double beta) {
  std::vector<double> c;
  for (double w2 : catenary.basis().omega2) c.push_back(alpha + beta * w2);
  return c;
}
}  // namespace

ModalDamping::ModalDamping(ModalCatenary& catenary, double alpha, double beta)
    : ModalDiagonalTerm(catenary, {}, rayleigh(catenary, alpha, beta), {}) {}

TermPower ModalDamping::power(const CoupledState& state) const {
  TermPower p;
  if (!state.V) return p;
  const Eigen::VectorXd v = modal_part(catenary_, state.V);
  p.dissipative = -v.dot(Eigen::Map<const Eigen::VectorXd>(cv_.data(), v.size()).cwiseProduct(v));
  return p;
}

// ------------------------------------------------------ dropper slack ----

ModalDropperSlack::ModalDropperSlack(ModalCatenary& catenary) : catenary_(catenary) {
  modes_.resize(catenary.catenary_dofs());
  for (std::size_t k = 0; k < modes_.size(); ++k) modes_[k] = static_cast<PetscInt>(k);
}

void ModalDropperSlack::add_residual(const CoupledState&, Vec F) {
  if (!catenary_.on_owner() || catenary_.slack_now().empty()) return;
  PetscScalar* a;
  PCSIM_PETSC(VecGetArray(F, &a));
  Eigen::Map<Eigen::VectorXd> f(a, catenary_.catenary_dofs());
  for (std::size_t d : catenary_.slack_now())
    f -= catenary_.bar_stiffness(d) * catenary_.elongation(d) *
         catenary_.elongation_rows().row(static_cast<long>(d)).transpose();
  PCSIM_PETSC(VecRestoreArray(F, &a));
}

void ModalDropperSlack::add_tangent(const CoupledState&, Shifts, Mat J) {
  if (catenary_.slack_now().empty()) return;
  const PetscInt m = catenary_.catenary_dofs();
  RowMatrix block = RowMatrix::Zero(m, m);
  for (std::size_t d : catenary_.slack_now()) {
    const auto b = catenary_.elongation_rows().row(static_cast<long>(d));
    block -= catenary_.bar_stiffness(d) * b.transpose() * b;
  }
  add_modal_block(catenary_, block, J);
}

bool ModalDropperSlack::low_rank_change(const CoupledState&, std::vector<RankOne>& terms) {
  const PetscInt m = catenary_.catenary_dofs();
  for (std::size_t d : catenary_.slack_now()) {
    RankOne term;
    term.key = static_cast<int>(d);
    term.index = modes_;
    const double* b = catenary_.elongation_rows().row(static_cast<long>(d)).data();
    term.weight.assign(b, b + m);
    term.coefficient = -catenary_.bar_stiffness(d);
    term.reuse_columns = false;
    terms.push_back(std::move(term));
  }
  return true;
}

double ModalDropperSlack::energy(const CoupledState&) const {
  double e = 0;
  for (std::size_t d : catenary_.slack_now())
    e -= 0.5 * catenary_.bar_stiffness(d) * catenary_.elongation(d) * catenary_.elongation(d);
  return e;
}

// ------------------------------------------------------- exact bars ----

ModalExactBars::ModalExactBars(ModalCatenary& catenary) : catenary_(catenary) {
  const auto& mesh = catenary.mesh();
  const PetscInt m = catenary.catenary_dofs();
  for (std::size_t b = 0; b < mesh.bars.size(); ++b) {
    Bar bar;
    bar.index = static_cast<int>(b);
    bar.P.resize(6, m);
    for (int end = 0; end < 2; ++end)
      for (int c = 0; c < 3; ++c) bar.P.row(3 * end + c) = catenary.row(mesh.bars[b].nodes[end], c);
    catenary::Vec6 q0, f0;
    catenary::Mat6 K0;
    for (int end = 0; end < 2; ++end)
      for (int c = 0; c < 3; ++c)
        q0[3 * end + c] = catenary.static_value(mesh.bars[b].nodes[end], c);
    catenary::bar_internal_force(catenary::bar_parameters(mesh.bars[b]), q0, f0, &K0);
    bar.q0 = q0;
    bar.f0 = f0;
    bar.K0 = K0;
    bars_.push_back(std::move(bar));
  }
}

void ModalExactBars::add_residual(const CoupledState&, Vec F) {
  if (!catenary_.on_owner()) return;
  const auto& mesh = catenary_.mesh();
  PetscScalar* a;
  PCSIM_PETSC(VecGetArray(F, &a));
  Eigen::Map<Eigen::VectorXd> f(a, catenary_.catenary_dofs());
  for (const auto& bar : bars_) {
    const catenary::Vec6 dq = bar.P * catenary_.eta();
    catenary::Vec6 q = bar.q0 + dq, fq;
    catenary::bar_internal_force(catenary::bar_parameters(mesh.bars[bar.index]), q, fq, nullptr);
    const catenary::Vec6 r = fq - bar.f0 - bar.K0 * dq;
    f += bar.P.transpose() * r;
  }
  PCSIM_PETSC(VecRestoreArray(F, &a));
}

void ModalExactBars::add_tangent(const CoupledState&, Shifts, Mat J) {
  const auto& mesh = catenary_.mesh();
  const PetscInt m = catenary_.catenary_dofs();
  RowMatrix block = RowMatrix::Zero(m, m);
  for (const auto& bar : bars_) {
    catenary::Vec6 q = bar.q0 + bar.P * catenary_.eta(), fq;
    catenary::Mat6 K;
    catenary::bar_internal_force(catenary::bar_parameters(mesh.bars[bar.index]), q, fq, &K);
    block += bar.P.transpose() * (K - bar.K0) * bar.P;
  }
  add_modal_block(catenary_, block, J);
}

double ModalExactBars::energy(const CoupledState&) const {
  const auto& mesh = catenary_.mesh();
  double e = 0;
  for (const auto& bar : bars_) {
    const catenary::Vec6 dq = bar.P * catenary_.eta();
    const auto params = catenary::bar_parameters(mesh.bars[bar.index]);
    e += catenary::bar_strain_energy(params, bar.q0 + dq) -
         catenary::bar_strain_energy(params, bar.q0) - bar.f0.dot(dq) - 0.5 * dq.dot(bar.K0 * dq);
  }
  return e;
}

}  // namespace pcsim::assembly
