#include "pcsim/assembly/modal_catenary.hpp"

#include <mpi.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numeric>

#include "pcsim/catenary/elements.hpp"
#include "pcsim/contact/contact_kernel.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::assembly {

using catenary::basis_row_key;

ModalCatenary::ModalCatenary(MPI_Comm comm, catenary::CatenaryMesh mesh,
                             std::vector<double> static_node_values, catenary::ReducedBasis basis,
                             const catenary::ModalSettings& settings, PetscInt extra_dofs)
    : comm_(comm),
      mesh_(std::move(mesh)),
      static_values_(std::move(static_node_values)),
      basis_(std::move(basis)),
      settings_(settings),
      m_(static_cast<PetscInt>(basis_.size())),
      extra_(extra_dofs) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
  if (basis_.rows.size() != basis_.row_keys.size() * basis_.size())
    throw SolverError("modal catenary: the basis rows do not match its size");
  for (int w : mesh_.contact_wire_list())
    locators_.push_back(std::make_unique<contact::ContactWireLocator>(mesh_, static_values_, w));
  cached_.resize(locators_.size());
  const long keys_end = basis_.row_keys.empty() ? 0 : basis_.row_keys.back() + 1;  // ascending
  row_index_.assign(std::max<long>(6L * mesh_.nodes.size(), keys_end), -1);
  for (std::size_t i = 0; i < basis_.row_keys.size(); ++i) row_index_[basis_.row_keys[i]] = i;
  omega_ = Eigen::Map<const Eigen::VectorXd>(basis_.omega2.data(), m_).cwiseSqrt();
  wire_position_.assign(mesh_.nodes.size(), -1);
  const auto nodes = catenary::contact_wire_nodes(mesh_);
  for (std::size_t i = 0; i < nodes.size(); ++i) wire_position_[nodes[i]] = static_cast<int>(i);
  build_dropper_rows();
  support_rows_.resize(static_cast<long>(mesh_.support_nodes.size()), m_);
  for (std::size_t s = 0; s < mesh_.support_nodes.size(); ++s)
    support_rows_.row(static_cast<long>(s)) = row(mesh_.support_nodes[s], 2);
  eta_ = Eigen::VectorXd::Zero(m_);
  exact_anchor();
  evaluations_ = 0;
}

ModalCatenary::~ModalCatenary() = default;

Eigen::Map<const Eigen::RowVectorXd> ModalCatenary::row(int node, int c) const {
  return key_row(basis_row_key(node, c));
}

Eigen::Map<const Eigen::RowVectorXd> ModalCatenary::key_row(long key) const {
  const long r = key < static_cast<long>(row_index_.size()) ? row_index_[key] : -1;
  if (r < 0) throw SolverError("modal catenary: a basis row was not kept");
  return Eigen::Map<const Eigen::RowVectorXd>(basis_.rows.data() + r * m_, m_);
}

// Bars tracked over the basis: the slack-capable ones and the droppers
// (records). b_d = e . (Phi_j - Phi_i), e the bar's static direction;
// s_d the static stretch over the slack threshold.
void ModalCatenary::build_dropper_rows() {
  const auto& bars = mesh_.bars;
  std::vector<int> tracked;
  for (std::size_t b = 0; b < bars.size(); ++b)
    if (bars[b].slack != catenary::SlackCriterion::none ||
        bars[b].kind == catenary::BarKind::dropper)
      tracked.push_back(static_cast<int>(b));
  slack_bars_ = tracked;
  B_.setZero(static_cast<long>(tracked.size()), m_);
  for (std::size_t d = 0; d < tracked.size(); ++d) {
    const auto& bar = bars[tracked[d]];
    Eigen::Vector3d e;
    for (int c = 0; c < 3; ++c)
      e[c] = static_values_[6 * bar.nodes[1] + c] - static_values_[6 * bar.nodes[0] + c];
    e.normalize();
    for (int c = 0; c < 3; ++c) B_.row(d) += e[c] * (row(bar.nodes[1], c) - row(bar.nodes[0], c));
    double s = 0;
    if (bar.slack == catenary::SlackCriterion::force)
      s = bar.equilibrium_length - bar.unstressed_length;
    stretch_.push_back(s);
    bnorm_.push_back(B_.row(d).norm());
    bnorm_omega_.push_back(B_.row(d).cwiseQuotient(omega_.transpose()).norm());
    if (bar.kind == catenary::BarKind::dropper) droppers_.push_back(static_cast<int>(d));
  }
  elongation_ = stretch_;
  for (double b : bnorm_) bnorm_max_ = std::max(bnorm_max_, b);
  B_single_ = B_.cast<float>();
}

// VECSTANDARD: sequential on one rank (no reductions over the
// communicator, no stash; measured ~10 % of a step of EN 50318 on one rank).
Vec ModalCatenary::create_vector() const {
  Vec v;
  PCSIM_PETSC(VecCreate(comm_, &v));
  PCSIM_PETSC(VecSetSizes(v, on_owner() ? m_ + extra_ : 0, PETSC_DETERMINE));
  PCSIM_PETSC(VecSetType(v, VECSTANDARD));
  return v;
}

// Modes: their diagonal, or every mode with every mode (dense: the exact
// tangents of contact and slack droppers, full path); extras: the dense
// pantograph block, and (dense) each wire-coupled extra with every mode. The
// reference pattern (not dense) has no coupling: no reference tangent
// couples a mode with another unknown, and J0 stays a diagonal plus the
// pantographs' blocks (a dense row and column of zeros made its ordering and
// factorisation cost ~20 % of a run's time, its solves 3 times more).
Mat ModalCatenary::allocate_matrix(const std::vector<bool>& wire_coupled, bool dense) const {
  const PetscInt n = on_owner() ? m_ + extra_ : 0;
  std::vector<PetscInt> coupled;
  for (std::size_t k = 0; k < wire_coupled.size(); ++k)
    if (wire_coupled[k] && dense) coupled.push_back(m_ + static_cast<PetscInt>(k));
  std::vector<PetscInt> nnz(n);
  for (PetscInt r = 0; r < n; ++r) {
    const bool wired = r >= m_ && wire_coupled[r - m_] && dense;
    nnz[r] = r < m_ ? (dense ? m_ : 1) + static_cast<PetscInt>(coupled.size())
                    : extra_ + (wired ? m_ : 0);
  }
  Mat A;
  PCSIM_PETSC(
      MatCreateAIJ(comm_, n, n, PETSC_DETERMINE, PETSC_DETERMINE, 0, nnz.data(), 0, nullptr, &A));
  if (!on_owner()) return A;
  std::vector<PetscInt> modes(m_);
  for (PetscInt k = 0; k < m_; ++k) modes[k] = k;
  const std::vector<double> zeros(std::max<PetscInt>(m_, extra_ * extra_), 0.0);
  for (PetscInt r = 0; r < m_; ++r) {
    if (dense)
      PCSIM_PETSC(MatSetValues(A, 1, &r, m_, modes.data(), zeros.data(), ADD_VALUES));
    else
      PCSIM_PETSC(MatSetValue(A, r, r, 0.0, ADD_VALUES));
  }
  std::vector<PetscInt> extras(extra_);
  for (PetscInt k = 0; k < extra_; ++k) extras[k] = m_ + k;
  PCSIM_PETSC(
      MatSetValues(A, extra_, extras.data(), extra_, extras.data(), zeros.data(), ADD_VALUES));
  for (PetscInt g : coupled) {
    PCSIM_PETSC(MatSetValues(A, 1, &g, m_, modes.data(), zeros.data(), ADD_VALUES));
    PCSIM_PETSC(MatSetValues(A, m_, modes.data(), 1, &g, zeros.data(), ADD_VALUES));
  }
  return A;
}

Mat ModalCatenary::create_matrix(const std::vector<bool>& wire_coupled) const {
  return allocate_matrix(wire_coupled, true);
}

Mat ModalCatenary::create_reference_matrix(const std::vector<bool>& wire_coupled) const {
  return allocate_matrix(wire_coupled, settings_.bars == catenary::ModalSettings::Bars::exact);
}

void ModalCatenary::reference_state(Vec U) const {
  PCSIM_PETSC(VecSet(U, 0.0));
}

// The same eta as loaded (a Jacobian or a record at the last residual's
// state) keeps the slack set, unless an anchor changed since: the set and
// the elongations are those a new evaluation would give, bit for bit.
void ModalCatenary::load_state(Vec U) {
  const auto bytes = sizeof(double) * static_cast<std::size_t>(m_);
  bool same = false;
  if (size_ == 1) {  // compared in place, copied only when changed
    const PetscScalar* a;
    PCSIM_PETSC(VecGetArrayRead(U, &a));
    same = std::memcmp(a, eta_.data(), bytes) == 0;
    if (!same) std::copy(a, a + m_, eta_.data());
    PCSIM_PETSC(VecRestoreArrayRead(U, &a));
  } else {
    incoming_.resize(m_);
    if (on_owner()) {
      const PetscScalar* a;
      PCSIM_PETSC(VecGetArrayRead(U, &a));
      std::copy(a, a + m_, incoming_.data());
      PCSIM_PETSC(VecRestoreArrayRead(U, &a));
    }
    MPI_Bcast(incoming_.data(), static_cast<int>(m_), MPI_DOUBLE, size_ - 1, comm_);
    same = std::memcmp(incoming_.data(), eta_.data(), bytes) == 0;
    if (!same) eta_.swap(incoming_);
  }
  ++loads_;
  if (same && slack_set_current_) return;
  if (!same) ++eta_version_;
  update_slack_set();
  slack_set_current_ = true;
}

// Every tracked bar exactly at the loaded state: the new anchor, and the
// last exact one (the records make one per step). The change between the
// last two exact ones is the line of the next bounds (line_candidates).
void ModalCatenary::exact_anchor() const {
  slack_set_current_ = false;  // a new anchor: the next load evaluates again
  anchor_ = eta_;
  anchor_version_ = eta_version_;
  anchor_elongation_.noalias() = B_ * eta_;
  anchor_elongation_ += Eigen::Map<const Eigen::VectorXd>(stretch_.data(), B_.rows());
  anchor_error_.setZero(B_.rows());
  line_valid_ = exact_count_ > 0;
  if (line_valid_) {
    line_ = eta_ - exact_eta_;
    line_elongation_ = anchor_elongation_ - exact_elongation_;
    line_norm2_ = line_.squaredNorm();
    line_valid_ = line_norm2_ > 0;
    previous_exact_norm_ = exact_norm_;
  }
  exact_eta_ = eta_;
  exact_norm_ = eta_.norm();
  exact_elongation_ = anchor_elongation_;
  ++exact_count_;
  evaluations_ += B_.rows();
}

// The droppers not certainly taut at the loaded state, from the line through
// the last two exact anchors eta_p, eta_e: with d = eta_e - eta_p,
// eta = eta_e + tau d + r (tau minimising |r|), dl = dl_e + tau (dl_e - dl_p)
// + b . r, and |b . r| <= min(|b| |r|, |Omega^-1 b| |Omega r|). The states of
// a time step lie near the line of the last step (r is the change of the
// change), so this bound leaves a few candidates where the one from the
// anchor alone (the change itself) leaves most. The rounding of the
// anchors' products (gamma_n |b| |eta|) and of this arithmetic is added to
// the bound. False if more than 'few' candidates remain.
bool ModalCatenary::line_candidates(std::size_t few) {
  constexpr double u = 1.1102230246251565e-16;  // 2^-53
  const double gamma = static_cast<double>(m_) * u / (1 - m_ * u);
  work_ = eta_ - exact_eta_;
  const double tau = work_.dot(line_) / line_norm2_;
  work_ -= tau * line_;  // r
  const double r = work_.norm(), r_omega = (work_.array() * omega_.array()).matrix().norm();
  const double line_norm = std::sqrt(line_norm2_);
  const double reach =
      gamma * (exact_norm_ * (1 + std::abs(tau)) + std::abs(tau) * previous_exact_norm_) +
      4 * u * (r + 2 * std::abs(tau) * line_norm);
  candidates_.clear();
  for (long d = 0; d < B_.rows(); ++d) {
    const double predicted = exact_elongation_[d] + tau * line_elongation_[d];
    const double rounding =
        bnorm_[d] * reach +
        4 * u * (std::abs(exact_elongation_[d]) + std::abs(tau * line_elongation_[d]));
    if (predicted - rounding <= std::min(bnorm_[d] * r, bnorm_omega_[d] * r_omega))
      candidates_.push_back(d);
    if (candidates_.size() > few) return false;
  }
  return true;
}

// dl = dl_e + fl(B (eta - eta_e)) in single precision from the last exact
// anchor, with its rounding bound (n + 2) u |b| |eta - eta_e| (Higham, with
// the conversions), u = 2^-24: it follows the distance from eta_e and does not
// add up over the updates. False, with no product, if it would exceed 'reset'.
bool ModalCatenary::single_precision_anchor(double reset) {
  constexpr double u = 5.9604644775390625e-08;
  const double gamma = (static_cast<double>(m_) + 2) * u / (1 - (m_ + 2) * u);
  work_ = eta_ - exact_eta_;
  const double distance = work_.norm();
  if (gamma * bnorm_max_ * distance > reset) return false;
  work_single_ = work_.cast<float>();
  change_single_.noalias() = B_single_ * work_single_;
  for (long d = 0; d < B_.rows(); ++d) {
    anchor_elongation_[d] = exact_elongation_[d] + change_single_[d];
    anchor_error_[d] = gamma * bnorm_[d] * distance;
  }
  anchor_ = eta_;
  anchor_version_ = eta_version_;
  ++single_products_;
  return true;
}

// The droppers not certainly taut at the loaded state (work_: eta - eta_a).
void ModalCatenary::find_candidates(double step, double step_omega) {
  candidates_.clear();
  for (long d = 0; d < B_.rows(); ++d)
    if (anchor_elongation_[d] - anchor_error_[d] <=
        std::min(bnorm_[d] * step, bnorm_omega_[d] * step_omega))
      candidates_.push_back(d);
}

// The bounded candidate set (see the header).
void ModalCatenary::update_slack_set() {
  constexpr std::size_t kFewCandidates = 4;  // more: one single-precision product for all
  constexpr double kErrorReset =
      1e-4;  // [m] rounding bound of a single-precision update (margins ~1 mm): exact anchor
  slack_now_.clear();
  if (!slack_active_) return;
  const long n = B_.rows();
  bool at_anchor = true;  // eta is the anchor
  if (settings_.dropper_check == catenary::ModalSettings::DropperCheck::all) {
    exact_anchor();
    candidates_.resize(n);
    for (long d = 0; d < n; ++d) candidates_[d] = d;
  } else {
    at_anchor = anchor_version_ == eta_version_;  // eta has not changed since the anchor
    if (at_anchor) {
      find_candidates(0, 0);
    } else if (!records_anchor_ || !line_valid_ || !line_candidates(kFewCandidates)) {
      // No line without records of the dropper forces (a moving window): it
      // would join the error resets' anchors, steps apart, and leave no fewer
      // candidates than the anchor alone (window scene: same counts, same results).
      work_ = eta_ - anchor_;
      const double step = work_.norm();
      const double step_omega = (work_.array() * omega_.array()).matrix().norm();
      find_candidates(step, step_omega);
      if (candidates_.size() > kFewCandidates) {
        if (!single_precision_anchor(kErrorReset)) exact_anchor();
        find_candidates(0, 0);
        at_anchor = true;
      }
    }
  }
  for (long d : candidates_) {
    double& dl = elongation_[d];
    if (at_anchor && anchor_error_[d] == 0) {
      dl = anchor_elongation_[d];
    } else {
      dl = stretch_[d] + B_.row(d).dot(eta_);
      ++evaluations_;
    }
    if (dl < 0 && mesh_.bars[slack_bars_[d]].slack != catenary::SlackCriterion::none)
      slack_now_.push_back(static_cast<std::size_t>(d));
  }
}

// The weights of contact wire 'wire' at station x: z = z0 + w . eta with
// w = S_z(chi) Phi_e (thesis 3.13), and the parts of the slope dz/dx.
ModalCatenary::CachedPoint& ModalCatenary::cached_point(double x, int wire) const {
  auto& entries = cached_[wire];
  CachedPoint* oldest = &entries[0];
  for (CachedPoint& e : entries) {
    if (e.x == x) {
      e.last_use = ++point_uses_;
      return e;
    }
    if (e.last_use < oldest->last_use) oldest = &e;
  }
  CachedPoint& c = *oldest;
  c.last_use = ++point_uses_;
  c.eta_version = -1;
  WirePoint& p = c.point;  // its vectors keep their storage from x to x
  int element;
  double chi;
  p.on_wire = locators_[wire]->locate(x, element, chi);
  p.owned = false;
  p.z = p.slope = p.residual_flexibility = p.residual_flexibility_slope = 0;
  p.reuse_columns = false;
  p.contiguous = true;
  c.z0 = c.z_chi0 = c.y0 = 0;
  c.x_chi = 1;
  if (!p.on_wire) {
    p.index.clear();
    p.weight.clear();
  } else {  // index and weight keep their size m: rewritten, not zeroed first
    const auto& el = mesh_.cables[element];
    const auto h = catenary::hermite(chi, el.ref_length);
    const auto& s = h.s;
    const auto& ds = h.ds;
    const int node[4] = {el.nodes[0], el.nodes[0], el.nodes[1], el.nodes[1]};
    const int comp[4] = {2, 5, 2, 5};  // z, z' at each end (thesis 3.13)
    const auto r0 = row(node[0], comp[0]), r1 = row(node[1], comp[1]);
    const auto r2 = row(node[2], comp[2]), r3 = row(node[3], comp[3]);
    p.weight.resize(m_);
    Eigen::Map<Eigen::RowVectorXd>(p.weight.data(), m_) =
        s[0] * r0 + s[1] * r1 + s[2] * r2 + s[3] * r3;
    c.z_chi = ds[0] * r0 + ds[1] * r1 + ds[2] * r2 + ds[3] * r3;
    c.y_eta.resize(0);
    const int lateral[4] = {1, 4, 1, 4};  // y, y' (kept under a wind): lateral motion
    bool kept = true;
    for (int k = 0; k < 4; ++k) kept = kept && row_index_[basis_row_key(node[k], lateral[k])] >= 0;
    if (kept)
      c.y_eta = s[0] * row(node[0], 1) + s[1] * row(node[1], 4) + s[2] * row(node[2], 1) +
                s[3] * row(node[3], 4);
    c.x_chi = 0;
    for (int k = 0; k < 4; ++k) {
      c.z0 += s[k] * static_values_[6 * node[k] + comp[k]];
      c.z_chi0 += ds[k] * static_values_[6 * node[k] + comp[k]];
      c.x_chi += ds[k] * static_values_[6 * node[k] + comp[k] - 2];  // x, x' (static)
      c.y0 += s[k] * static_values_[6 * node[k] + comp[k] - 1];      // y, y' (static)
    }
    if (!mesh_.contact_gap_offsets.empty()) c.z0 += mesh_.contact_gap_offsets[wire].at(x);
    p.index.resize(m_);
    std::iota(p.index.begin(), p.index.end(), 0);
    const auto at = [&](int n) { return basis_.contact_flexibility[wire_position_[n]]; };
    const double xi = chi / el.ref_length;
    if (!basis_.contact_flexibility.empty()) {
      p.residual_flexibility = (1 - xi) * at(el.nodes[0]) + xi * at(el.nodes[1]);
      p.residual_flexibility_slope =
          (at(el.nodes[1]) - at(el.nodes[0])) / (el.ref_length * c.x_chi);
    }
  }
  c.x = x;
  return c;
}

// The height and slope at the loaded eta, computed once per x and eta.
const WirePoint& ModalCatenary::wire_point(double x, int wire) const {
  CachedPoint& c = cached_point(x, wire);
  WirePoint& p = c.point;
  if (p.on_wire && on_owner() && c.eta_version != eta_version_) {
    p.owned = true;
    p.y = c.y_eta.size() > 0 ? c.y0 + c.y_eta.dot(eta_) : c.y0;
    p.z = c.z0 + Eigen::Map<const Eigen::VectorXd>(p.weight.data(), m_).dot(eta_);
    // dz/dx with x(chi) static (the contact point moves along the track).
    p.slope = (c.z_chi0 + c.z_chi.dot(eta_)) / c.x_chi;
    if (!mesh_.contact_gap_offsets.empty()) p.slope += mesh_.contact_gap_offsets[wire].slope_at(x);
    c.eta_version = eta_version_;
  }
  return p;
}

// eta = Omega^-2 w(x) F: the modal statics under the force (slack ignored).
// eta = D^-1 f with D = Omega^2, f = phi(x)^T F; with active pins (a
// moving window's end that is the line's: k u u^T each) by Woodbury:
// eta = y - D^-1 U (I / k + U^T D^-1 U)^-1 U^T y, y = D^-1 f.
bool ModalCatenary::closed_form_point_load(double x, int wire, double force, Vec U) const {
  const WirePoint& p = wire_point(x, wire);
  if (!p.on_wire) return false;
  PCSIM_PETSC(VecSet(U, 0.0));
  if (!on_owner()) return true;
  const Eigen::Map<const Eigen::VectorXd> omega2(basis_.omega2.data(), m_);
  Eigen::VectorXd y(m_);
  for (PetscInt k = 0; k < m_; ++k) y[k] = p.weight[k] * force / omega2[k];
  std::vector<const catenary::NodePin*> active;
  for (const auto& pin : mesh_.pins)
    if (pin.active) active.push_back(&pin);
  if (!active.empty()) {
    const long n = static_cast<long>(active.size());
    Eigen::MatrixXd Dinv_u(m_, n), small(n, n);
    for (long j = 0; j < n; ++j)
      Dinv_u.col(j) = row(active[j]->node, active[j]->dof).transpose().cwiseQuotient(omega2);
    for (long i = 0; i < n; ++i)
      for (long j = 0; j < n; ++j)
        small(i, j) = row(active[i]->node, active[i]->dof).dot(Dinv_u.col(j)) +
                      (i == j ? 1.0 / active[i]->stiffness : 0.0);
    Eigen::VectorXd uy(n);
    for (long i = 0; i < n; ++i) uy[i] = row(active[i]->node, active[i]->dof).dot(y);
    y -= Dinv_u * small.ldlt().solve(uy);
  }
  PetscScalar* a;
  PCSIM_PETSC(VecGetArray(U, &a));
  std::copy(y.data(), y.data() + m_, a);
  PCSIM_PETSC(VecRestoreArray(U, &a));
  return true;
}

// z_s = z0_s + S eta, S the supports' rows of the basis side by side (one
// product over contiguous rows instead of dots over rows spread in the basis).
std::vector<double> ModalCatenary::support_heights() const {
  std::vector<double> z(mesh_.support_nodes.size(), 0.0);
  if (!on_owner()) return z;
  Eigen::Map<Eigen::VectorXd> heights(z.data(), static_cast<long>(z.size()));
  heights.noalias() = support_rows_ * eta_;
  for (std::size_t s = 0; s < z.size(); ++s) z[s] += static_values_[6 * mesh_.support_nodes[s] + 2];
  return z;
}

// N = N_eq + k b.eta (linear bars), k max(s + b.eta, 0) (force), N_eq + k
// max(b.eta, 0) (length); the elongation's gradient b at the static state.
std::vector<double> ModalCatenary::dropper_forces() const {
  std::vector<double> forces(droppers_.size(), 0.0);
  exact_anchor();  // every rank: the records' states anchor the bounded set
  records_anchor_ = true;
  if (!on_owner()) return forces;
  for (std::size_t i = 0; i < droppers_.size(); ++i) {
    const auto d = static_cast<std::size_t>(droppers_[i]);
    const auto& bar = mesh_.bars[slack_bars_[d]];
    const double stretch = anchor_elongation_[static_cast<long>(d)] - stretch_[d];
    const bool slack = dropper_slack_;  // else every bar taut
    if (slack && bar.slack == catenary::SlackCriterion::force)
      forces[i] = bar.stiffness * std::max(stretch_[d] + stretch, 0.0);
    else if (slack && bar.slack == catenary::SlackCriterion::length)
      forces[i] = bar.equilibrium_force + bar.stiffness * std::max(stretch, 0.0);
    else
      forces[i] = bar.equilibrium_force + bar.stiffness * stretch;
  }
  return forces;
}

std::vector<double> ModalCatenary::node_positions_to_root(Vec U) const {
  if (!settings_.full_shapes)
    throw SolverError("modal catenary: field snapshots need the full mode shapes");
  Eigen::VectorXd eta(m_);
  if (on_owner()) {
    const PetscScalar* a;
    PCSIM_PETSC(VecGetArrayRead(U, &a));
    std::copy(a, a + m_, eta.data());
    PCSIM_PETSC(VecRestoreArrayRead(U, &a));
  }
  if (size_ > 1) MPI_Bcast(eta.data(), static_cast<int>(m_), MPI_DOUBLE, size_ - 1, comm_);
  if (rank_ != 0) return {};
  std::vector<double> positions = positions_from_node_values(static_values_);
  for (std::size_t n = 0; n < mesh_.nodes.size(); ++n)
    for (int c = 0; c < 3; ++c) positions[3 * n + c] += row(static_cast<int>(n), c).dot(eta);
  return positions;
}

}  // namespace pcsim::assembly
