#include "pcsim/assembly/modal_terms.hpp"

#include <mpi.h>

#include <algorithm>

#include "modal_rows.hpp"
#include "pcsim/assembly/coupled_state.hpp"
#include "pcsim/assembly/modal_wind.hpp"
#include "pcsim/catenary/elements.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::assembly {

namespace {

using modal_rows::add_modal_block;
using modal_rows::all_modes;
using modal_rows::RowMatrix;

// The modal part of a vector into x (every rank: it lives on the last one).
void modal_part(const ModalCatenary& catenary, Vec v, Eigen::VectorXd& x) {
  const PetscInt m = catenary.catenary_dofs();
  x.resize(m);
  if (catenary.on_owner()) {
    const PetscScalar* a;
    PCSIM_PETSC(VecGetArrayRead(v, &a));
    std::copy(a, a + m, x.data());
    PCSIM_PETSC(VecRestoreArrayRead(v, &a));
  } else {
    x.setZero();
  }
  MPI_Allreduce(MPI_IN_PLACE, x.data(), static_cast<int>(m), MPI_DOUBLE, MPI_SUM, catenary.comm());
}

Eigen::VectorXd modal_part(const ModalCatenary& catenary, Vec v) {
  Eigen::VectorXd x;
  modal_part(catenary, v, x);
  return x;
}

// The row made by make() under key, made on first use and kept (the basis
// never changes under a term).
template <class Make>
const SharedEntries<double>& kept_row(std::map<long, SharedEntries<double>>& rows, long key,
                                      Make make) {
  auto [it, added] = rows.try_emplace(key);
  if (added) {
    const auto row = make();
    it->second = std::vector<double>(row.data(), row.data() + row.size());
  }
  return it->second;
}

}  // namespace

ModalOscillators::ModalOscillators(ModalCatenary& catenary, bool damping, double alpha, double beta)
    : catenary_(catenary),
      stiffness_(Eigen::Map<const Eigen::ArrayXd>(catenary.basis().omega2.data(),
                                                  catenary.catenary_dofs())) {
  if (damping) damping_ = alpha + beta * stiffness_;
  const auto& wind = catenary.basis().wind_damping;  // the mean wind's, diagonal
  if (static_cast<long>(wind.size()) == stiffness_.size()) {
    const Eigen::Map<const Eigen::ArrayXd> c(wind.data(), stiffness_.size());
    if (damping_.size() > 0)
      damping_ += c;
    else
      damping_ = c;
  }
}

// F_k += omega_k^2 eta_k + eta_k'' + c_k eta_k' on the owner (the modes lead
// its rows), summed in that order.
void ModalOscillators::add_residual(const CoupledState& state, Vec F) {
  if (!catenary_.on_owner()) return;
  const PetscInt m = catenary_.catenary_dofs();
  const auto read = [](Vec x) {
    const PetscScalar* a = nullptr;
    if (x) PCSIM_PETSC(VecGetArrayRead(x, &a));
    return a;
  };
  const auto release = [](Vec x, const PetscScalar* a) {
    if (x) PCSIM_PETSC(VecRestoreArrayRead(x, &a));
  };
  using Map = Eigen::Map<const Eigen::ArrayXd>;
  PetscScalar* f;
  PCSIM_PETSC(VecGetArray(F, &f));
  Eigen::Map<Eigen::ArrayXd> fa(f, m);
  const PetscScalar *u = read(state.U), *v = read(state.V), *a = read(state.A);
  const bool damped = v && damping_.size() > 0;
  if (a && damped)  // one pass (the usual residual)
    fa = ((fa + stiffness_ * Map(u, m)) + Map(a, m)) + damping_ * Map(v, m);
  else if (a)
    fa = (fa + stiffness_ * Map(u, m)) + Map(a, m);
  else if (damped)
    fa = (fa + stiffness_ * Map(u, m)) + damping_ * Map(v, m);
  else
    fa += stiffness_ * Map(u, m);
  release(state.A, a);
  release(state.V, v);
  release(state.U, u);
  PCSIM_PETSC(VecRestoreArray(F, &f));
}

void ModalOscillators::add_inertia(const CoupledState&, Vec A, Vec F) const {
  if (!catenary_.on_owner()) return;
  const PetscInt m = catenary_.catenary_dofs();
  const PetscScalar* a;
  PetscScalar* f;
  PCSIM_PETSC(VecGetArrayRead(A, &a));
  PCSIM_PETSC(VecGetArray(F, &f));
  Eigen::Map<Eigen::ArrayXd>(f, m) += Eigen::Map<const Eigen::ArrayXd>(a, m);
  PCSIM_PETSC(VecRestoreArray(F, &f));
  PCSIM_PETSC(VecRestoreArrayRead(A, &a));
}

void ModalOscillators::add_tangent(const CoupledState&, Shifts shifts, Mat J) {
  if (!catenary_.on_owner()) return;
  for (PetscInt k = 0; k < catenary_.catenary_dofs(); ++k) {
    double value = stiffness_[k] + shifts.a;
    if (damping_.size() > 0) value += shifts.v * damping_[k];
    PCSIM_PETSC(MatSetValue(J, k, k, value, ADD_VALUES));
  }
}

double ModalOscillators::energy(const CoupledState& state) const {
  const auto& eta = catenary_.eta();
  double e = 0.5 * eta.dot((stiffness_ * eta.array()).matrix());
  if (state.V) e += 0.5 * modal_part(catenary_, state.V).squaredNorm();
  return e;
}

TermPower ModalOscillators::power(const CoupledState& state) const {
  TermPower p;
  if (!state.V || damping_.size() == 0) return p;
  const Eigen::VectorXd v = modal_part(catenary_, state.V);
  p.dissipative = -v.dot((damping_ * v.array()).matrix());
  return p;
}

// ------------------------------------------------------ dropper slack ----

ModalDropperSlack::ModalDropperSlack(ModalCatenary& catenary, bool force_free,
                                     const ModalExactDroppers* exact)
    : catenary_(catenary), exact_(exact), modes_(all_modes(catenary)) {
  const auto& bars = catenary.mesh().bars;
  for (int b : catenary.slack_bars()) {
    const auto& bar = bars[b];
    const catenary::Vec6 q0 = catenary.static_bar_dofs(b);
    const Eigen::Vector3d d = q0.tail<3>() - q0.head<3>();
    const double l0 = d.norm();
    double g = 0;
    if (force_free && bar.slack == catenary::SlackCriterion::force && l0 > 0)
      g = std::max(catenary::bar_axial_force(catenary::bar_parameters(bar, false), q0), 0.0) / l0;
    Eigen::Matrix<double, 3, 2> n = Eigen::Matrix<double, 3, 2>::Zero();
    if (g > 0) {
      const Eigen::Vector3d e = d / l0;
      n.col(0) = e.unitOrthogonal();
      n.col(1) = e.cross(n.col(0));
    }
    geometric_.push_back(g);
    normals_.push_back(n);
  }
  make_rows();
}

// Every tracked bar's rows, made here and not when it first goes slack: a
// row made in a step writes fresh pages, whose faults cost more than the
// step's products (docs/benchmarks.md, "What a modal run's slow steps are").
// b_d is a view of the catenary's own row (no copy); the t_j of the bars with
// g > 0 are kept in one matrix (2 x 8 B x m a bar).
void ModalDropperSlack::make_rows() {
  const auto& B = catenary_.elongation_rows();
  const auto m = static_cast<std::size_t>(catenary_.catenary_dofs());
  const std::size_t tracked = geometric_.size();
  std::vector<long> transverse(tracked, -1);
  long count = 0;
  for (std::size_t d = 0; d < tracked; ++d)
    if (geometric_[d] > 0) transverse[d] = count++;
  auto kept = std::make_shared<RowMatrix>(2 * count, static_cast<long>(m));
  rows_.resize(tracked);
  for (std::size_t d = 0; d < tracked; ++d) {
    rows_[d][0] = SharedEntries<double>(nullptr, B.row(static_cast<long>(d)).data(), m);
    if (transverse[d] < 0) continue;
    for (int j = 1; j <= 2; ++j) {
      auto row = kept->row(2 * transverse[d] + j - 1);
      row = catenary_.relative_row(catenary_.slack_bars()[d], normals_[d].col(j - 1));
      rows_[d][j] = SharedEntries<double>(kept, row.data(), m);
    }
  }
}

namespace {
Eigen::Map<const Eigen::RowVectorXd> as_row(const SharedEntries<double>& row) {
  return {row.data(), static_cast<long>(row.size())};
}
}  // namespace

const std::vector<std::size_t>& ModalDropperSlack::slack_here(const CoupledState& state) const {
  slack_here_.clear();
  for (std::size_t d : catenary_.slack_now())
    if (!exact_ || !exact_->covers(state, d)) slack_here_.push_back(d);
  return slack_here_;
}

void ModalDropperSlack::add_residual(const CoupledState& state, Vec F) {
  if (!catenary_.on_owner() || slack_here(state).empty()) return;
  PetscScalar* a;
  PCSIM_PETSC(VecGetArray(F, &a));
  Eigen::Map<Eigen::VectorXd> f(a, catenary_.catenary_dofs());
  for (std::size_t d : slack_here_) {
    f -= catenary_.bar_stiffness(d) * catenary_.elongation(d) *
         catenary_.elongation_rows().row(static_cast<long>(d)).transpose();
    if (geometric_[d] == 0) continue;
    for (int j = 1; j <= 2; ++j) {
      const auto t = as_row(rows_[d][j]);
      f -= geometric_[d] * t.dot(catenary_.eta()) * t.transpose();
    }
  }
  PCSIM_PETSC(VecRestoreArray(F, &a));
}

void ModalDropperSlack::add_tangent(const CoupledState& state, Shifts, Mat J) {
  if (slack_here(state).empty()) return;
  const PetscInt m = catenary_.catenary_dofs();
  RowMatrix block = RowMatrix::Zero(m, m);
  for (std::size_t d : slack_here_) {
    const auto b = catenary_.elongation_rows().row(static_cast<long>(d));
    block -= catenary_.bar_stiffness(d) * b.transpose() * b;
    if (geometric_[d] == 0) continue;
    for (int j = 1; j <= 2; ++j) {
      const auto t = as_row(rows_[d][j]);
      block -= geometric_[d] * t.transpose() * t;
    }
  }
  add_modal_block(catenary_, block, J);
}

bool ModalDropperSlack::low_rank_change(const CoupledState& state, std::vector<RankOne>& terms) {
  slack_here(state);
  const auto add = [&](long key, const SharedEntries<double>& weight, double coefficient) {
    RankOne term;
    term.key = static_cast<int>(key);
    term.index = modes_;
    term.weight = weight;
    term.coefficient = coefficient;
    term.reuse_columns = false;
    term.contiguous = true;
    terms.push_back(std::move(term));
  };
  for (std::size_t d : slack_here_) {
    const long key = 3L * static_cast<long>(d);
    add(key, rows_[d][0], -catenary_.bar_stiffness(d));
    if (geometric_[d] == 0) continue;
    for (int j = 1; j <= 2; ++j) add(key + j, rows_[d][j], -geometric_[d]);
  }
  return true;
}

double ModalDropperSlack::energy(const CoupledState& state) const {
  slack_here(state);
  double e = 0;
  for (std::size_t d : slack_here_) {
    e -= 0.5 * catenary_.bar_stiffness(d) * catenary_.elongation(d) * catenary_.elongation(d);
    for (int j = 1; j <= 2 && geometric_[d] > 0; ++j) {
      const double u = as_row(rows_[d][j]).dot(catenary_.eta());
      e -= 0.5 * geometric_[d] * u * u;
    }
  }
  return e;
}

// ------------------------------------------------- window end terms ----

namespace {

// A rank-one term c phi^T phi over every mode (dense u), phi the row of
// (node, dof) kept in rows.
RankOne modal_rank_one(const ModalCatenary& catenary, int key, const SharedEntries<PetscInt>& modes,
                       std::map<long, SharedEntries<double>>& rows, int node, int dof,
                       double coefficient) {
  RankOne term;
  term.key = key;
  term.index = modes;
  term.weight = kept_row(rows, 8L * node + dof, [&] { return catenary.row(node, dof); });
  term.coefficient = coefficient;
  term.contiguous = true;
  return term;
}

// Adds sum over the rows of coefficient(row) (phi . x) phi^T to F's modal part (owner).
template <class Items, class Coefficient>
void add_modal_rows(const ModalCatenary& catenary, const Items& items,
                    Eigen::Ref<const Eigen::VectorXd> x, Coefficient coefficient, Vec F) {
  if (!catenary.on_owner()) return;
  PetscScalar* a;
  PCSIM_PETSC(VecGetArray(F, &a));
  Eigen::Map<Eigen::VectorXd> f(a, catenary.catenary_dofs());
  for (const auto& item : items) {
    const double c = coefficient(item);
    if (c == 0) continue;  // an inactive pin adds nothing
    const auto phi = catenary.row(item.node, item.dof);
    f += c * phi.dot(x) * phi.transpose();
  }
  PCSIM_PETSC(VecRestoreArray(F, &a));
}

template <class Items, class Coefficient>
void add_modal_outer(const ModalCatenary& catenary, const Items& items, Coefficient coefficient,
                     Mat J) {
  const PetscInt m = catenary.catenary_dofs();
  RowMatrix block = RowMatrix::Zero(m, m);
  bool any = false;
  for (const auto& item : items) {
    const double c = coefficient(item);
    if (c == 0) continue;
    const auto phi = catenary.row(item.node, item.dof);
    block += c * phi.transpose() * phi;
    any = true;
  }
  if (any) add_modal_block(catenary, block, J);
}

}  // namespace

ModalNodeDashpots::ModalNodeDashpots(ModalCatenary& catenary)
    : catenary_(catenary), modes_(all_modes(catenary)) {}

void ModalNodeDashpots::add_residual(const CoupledState& state, Vec F) {
  if (!state.V) return;
  const auto coefficient = [](const auto& d) { return d.coefficient; };
  int size = 1;
  MPI_Comm_size(catenary_.comm(), &size);
  if (size > 1) {
    modal_part(catenary_, state.V, rates_);
    add_modal_rows(catenary_, catenary_.mesh().dashpots, rates_, coefficient, F);
    return;
  }
  const PetscScalar* v;  // one rank: V read in place
  PCSIM_PETSC(VecGetArrayRead(state.V, &v));
  add_modal_rows(catenary_, catenary_.mesh().dashpots,
                 Eigen::Map<const Eigen::VectorXd>(v, catenary_.catenary_dofs()), coefficient, F);
  PCSIM_PETSC(VecRestoreArrayRead(state.V, &v));
}

void ModalNodeDashpots::add_tangent(const CoupledState&, Shifts shifts, Mat J) {
  add_modal_outer(
      catenary_, catenary_.mesh().dashpots, [&](const auto& d) { return shifts.v * d.coefficient; },
      J);
}

bool ModalNodeDashpots::low_rank_change(const CoupledState&, std::vector<RankOne>& terms) {
  const auto& dashpots = catenary_.mesh().dashpots;
  for (std::size_t e = 0; e < dashpots.size(); ++e)
    terms.push_back(modal_rank_one(catenary_, static_cast<int>(e), modes_, rows_, dashpots[e].node,
                                   dashpots[e].dof, shift_v_ * dashpots[e].coefficient));
  return true;
}

TermPower ModalNodeDashpots::power(const CoupledState& state) const {
  TermPower p;
  if (!state.V) return p;
  const Eigen::VectorXd v = modal_part(catenary_, state.V);
  for (const auto& d : catenary_.mesh().dashpots) {
    const double rate = catenary_.row(d.node, d.dof).dot(v);
    p.dissipative -= d.coefficient * rate * rate;
  }
  return p;
}

ModalNodePins::ModalNodePins(ModalCatenary& catenary)
    : catenary_(catenary), modes_(all_modes(catenary)) {}

namespace {
double active_stiffness(const catenary::NodePin& pin) {
  return pin.active ? pin.stiffness : 0.0;
}
}  // namespace

void ModalNodePins::add_residual(const CoupledState&, Vec F) {
  add_modal_rows(catenary_, catenary_.mesh().pins, catenary_.eta(), active_stiffness, F);
}

void ModalNodePins::add_tangent(const CoupledState&, Shifts, Mat J) {
  add_modal_outer(catenary_, catenary_.mesh().pins, active_stiffness, J);
}

bool ModalNodePins::low_rank_change(const CoupledState&, std::vector<RankOne>& terms) {
  const auto& pins = catenary_.mesh().pins;
  for (std::size_t p = 0; p < pins.size(); ++p)
    if (pins[p].active)
      terms.push_back(modal_rank_one(catenary_, static_cast<int>(p), modes_, rows_, pins[p].node,
                                     pins[p].dof, pins[p].stiffness));
  return true;
}

double ModalNodePins::energy(const CoupledState&) const {
  double e = 0;
  for (const auto& pin : catenary_.mesh().pins) {
    const double u = catenary_.row(pin.node, pin.dof).dot(catenary_.eta());
    e += 0.5 * active_stiffness(pin) * u * u;
  }
  return e;
}

// ------------------------------------------------------- exact bars ----

ModalExactBars::ModalExactBars(ModalCatenary& catenary, bool slack) : catenary_(catenary) {
  const auto& mesh = catenary.mesh();
  const PetscInt m = catenary.catenary_dofs();
  for (std::size_t b = 0; b < mesh.bars.size(); ++b) {
    Bar bar;
    bar.index = static_cast<int>(b);
    bar.P.resize(6, m);
    for (int end = 0; end < 2; ++end)
      for (int c = 0; c < 3; ++c) bar.P.row(3 * end + c) = catenary.row(mesh.bars[b].nodes[end], c);
    const catenary::Vec6 q0 = catenary.static_bar_dofs(static_cast<int>(b));
    catenary::Vec6 f0;
    catenary::Mat6 K0;
    bar.params = catenary::bar_parameters(mesh.bars[b], slack);
    catenary::bar_internal_force(bar.params, q0, f0, &K0);
    bar.q0 = q0;
    bar.f0 = f0;
    bar.K0 = K0;
    bars_.push_back(std::move(bar));
  }
}

void ModalExactBars::add_residual(const CoupledState&, Vec F) {
  if (!catenary_.on_owner()) return;
  PetscScalar* a;
  PCSIM_PETSC(VecGetArray(F, &a));
  Eigen::Map<Eigen::VectorXd> f(a, catenary_.catenary_dofs());
  for (const auto& bar : bars_) {
    const catenary::Vec6 dq = bar.P * catenary_.eta();
    catenary::Vec6 q = bar.q0 + dq, fq;
    catenary::bar_internal_force(bar.params, q, fq, nullptr);
    const catenary::Vec6 r = fq - bar.f0 - bar.K0 * dq;
    f += bar.P.transpose() * r;
  }
  PCSIM_PETSC(VecRestoreArray(F, &a));
}

void ModalExactBars::add_tangent(const CoupledState&, Shifts, Mat J) {
  const PetscInt m = catenary_.catenary_dofs();
  RowMatrix block = RowMatrix::Zero(m, m);
  for (const auto& bar : bars_) {
    catenary::Vec6 q = bar.q0 + bar.P * catenary_.eta(), fq;
    catenary::Mat6 K;
    catenary::bar_internal_force(bar.params, q, fq, &K);
    block += bar.P.transpose() * (K - bar.K0) * bar.P;
  }
  add_modal_block(catenary_, block, J);
}

double ModalExactBars::energy(const CoupledState&) const {
  double e = 0;
  for (const auto& bar : bars_) {
    const catenary::Vec6 dq = bar.P * catenary_.eta();
    const auto& params = bar.params;
    e += catenary::bar_strain_energy(params, bar.q0 + dq) -
         catenary::bar_strain_energy(params, bar.q0) - bar.f0.dot(dq) - 0.5 * dq.dot(bar.K0 * dq);
  }
  return e;
}

// ------------------------------------------------- the model's terms ----

std::vector<std::unique_ptr<Term>> ModalCatenary::make_terms(const contact::InteractionEffects& e,
                                                             Mat pattern) {
  dropper_slack_ = e.dropper_slack;
  const bool exact = settings_.bars == catenary::ModalSettings::Bars::exact;
  slack_active_ = !exact && e.dropper_slack;
  slack_set_current_ = false;
  std::vector<std::unique_ptr<Term>> terms;
  terms.push_back(std::make_unique<ModalOscillators>(*this, e.rayleigh_damping,
                                                     mesh_.rayleigh_alpha, mesh_.rayleigh_beta));
  if (exact) terms.push_back(std::make_unique<ModalExactBars>(*this, e.dropper_slack));
  // Droppers near the pantographs exact: not the slack term's.
  const ModalExactDroppers* near = nullptr;
  if (!exact && settings_.exact_droppers_within > 0) {
    auto term = std::make_unique<ModalExactDroppers>(*this, settings_.exact_droppers_within,
                                                     e.dropper_slack);
    near = term.get();
    terms.push_back(std::move(term));
  }
  if (!exact && slack_active_)
    terms.push_back(std::make_unique<ModalDropperSlack>(
        *this, settings_.bars == catenary::ModalSettings::Bars::slack_exact, near));
  // A moving window's ends (released: dashpots, pins switched by the run).
  if (!mesh_.dashpots.empty()) terms.push_back(std::make_unique<ModalNodeDashpots>(*this));
  if (!mesh_.pins.empty()) terms.push_back(std::make_unique<ModalNodePins>(*this));
  if (mesh_.conditions.wind.any() && mesh_.conditions.wind.turbulence.on)
    terms.push_back(std::make_unique<ModalWindTurbulence>(*this));
  return terms;
}

}  // namespace pcsim::assembly
