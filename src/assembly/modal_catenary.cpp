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
                             std::vector<double> static_node_values,
                             std::shared_ptr<const catenary::ReducedBasis> basis,
                             const catenary::ModalSettings& settings, PetscInt extra_dofs)
    : comm_(comm),
      mesh_(std::move(mesh)),
      static_values_(std::move(static_node_values)),
      basis_(std::move(basis)),
      settings_(settings),
      m_(basis_ ? static_cast<PetscInt>(basis_->size()) : 0),
      extra_(extra_dofs) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
  if (!basis_) throw SolverError("modal catenary: no basis");
  if (basis_->rows.size() != basis_->row_keys.size() * basis_->size())
    throw SolverError("modal catenary: the basis rows do not match its size");
  for (int w : mesh_.contact_wire_list())
    locators_.push_back(std::make_unique<contact::ContactWireLocator>(mesh_, static_values_, w));
  cached_.resize(locators_.size());
  const long keys_end = basis_->row_keys.empty() ? 0 : basis_->row_keys.back() + 1;  // ascending
  row_index_.assign(std::max<long>(6L * mesh_.nodes.size(), keys_end), -1);
  for (std::size_t i = 0; i < basis_->row_keys.size(); ++i) row_index_[basis_->row_keys[i]] = i;
  omega_ = Eigen::Map<const Eigen::VectorXd>(basis_->omega2.data(), m_).cwiseSqrt();
  wire_position_.assign(mesh_.nodes.size(), -1);
  const auto nodes = catenary::contact_wire_nodes(mesh_);
  for (std::size_t i = 0; i < nodes.size(); ++i) wire_position_[nodes[i]] = static_cast<int>(i);
  find_wire_node_columns(nodes);
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
  return Eigen::Map<const Eigen::RowVectorXd>(basis_->rows.data() + r * m_, m_);
}

long ModalCatenary::first_nonzero_block(const double* row, long m,
                                        const std::vector<long>& starts) {
  long first = 0;
  while (first < m && row[first] == 0) ++first;
  if (first == m) return -1;
  return std::upper_bound(starts.begin(), starts.end(), first) - starts.begin() - 1;
}

// The blocks of each contact-wire node's z and z' rows (their first
// nonzeros; a zero row spans no block), joined into one range of columns.
void ModalCatenary::find_wire_node_columns(const std::vector<int>& wire_nodes) {
  const auto& starts = basis_->column_blocks;
  if (starts.size() <= 2 || starts.front() != 0 || starts.back() != m_) return;
  wire_node_columns_.assign(mesh_.nodes.size(), {0, m_});
  for (int n : wire_nodes) {
    long lo = m_, hi = 0;
    for (int c : {2, 5}) {
      const long g = first_nonzero_block(row(n, c).data(), m_, starts);
      if (g < 0) continue;
      lo = std::min(lo, starts[g]);
      hi = std::max(hi, starts[g + 1]);
    }
    wire_node_columns_[n] = lo < hi ? std::make_pair(lo, hi) : std::make_pair(0L, 0L);
  }
}

// The columns of a contact-wire element's blocks (every column with one block).
std::pair<long, long> ModalCatenary::element_columns(int node0, int node1) const {
  if (wire_node_columns_.empty()) return {0, m_};
  const auto a = wire_node_columns_[node0], b = wire_node_columns_[node1];
  if (a.first >= a.second) return b;
  if (b.first >= b.second) return a;
  return {std::min(a.first, b.first), std::max(a.second, b.second)};
}

catenary::Vec6 ModalCatenary::static_bar_dofs(int b) const {
  catenary::Vec6 q0;
  for (int end = 0; end < 2; ++end)
    for (int c = 0; c < 3; ++c) q0[3 * end + c] = static_value(mesh_.bars[b].nodes[end], c);
  return q0;
}

Eigen::RowVectorXd ModalCatenary::relative_row(int b, const Eigen::Vector3d& direction) const {
  const auto& nodes = mesh_.bars[b].nodes;
  Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(m_);
  for (int c = 0; c < 3; ++c) r += direction[c] * (row(nodes[1], c) - row(nodes[0], c));
  return r;
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
    const catenary::Vec6 q0 = static_bar_dofs(tracked[d]);
    const Eigen::Vector3d e = (q0.tail<3>() - q0.head<3>()).normalized();
    B_.row(d) = relative_row(tracked[d], e);
    double s = 0;
    if (bar.slack == catenary::SlackCriterion::force)
      s = bar.equilibrium_length - bar.unstressed_length;
    stretch_.push_back(s);
    bnorm_.push_back(B_.row(d).norm());
    bnorm_omega_.push_back(B_.row(d).cwiseQuotient(omega_.transpose()).norm());
    if (bar.kind == catenary::BarKind::dropper) droppers_.push_back(static_cast<int>(d));
  }
  elongation_ = stretch_;
  build_row_blocks();
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

// The weights of contact wire 'wire' at station x: z = z0 + w . eta with
// w = S_z(chi) Phi_e (thesis 3.13), the static slope parts and where x lies (wire_slope).
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
  p.z = p.residual_flexibility = p.residual_flexibility_slope = 0;
  c.element = -1;
  c.z_chi_made = false;
  p.reuse_columns = false;
  p.contiguous = true;
  c.z0 = c.z_chi0 = c.y0 = 0;
  c.x_chi = 1;
  if (!p.on_wire) {
    p.index.clear();
    p.weight.clear();
  } else {  // index and weight keep their size: rewritten, not zeroed first
    const auto& el = mesh_.cables[element];
    const auto h = catenary::hermite(chi, el.ref_length);
    const auto& s = h.s;
    const auto& ds = h.ds;
    const int node[4] = {el.nodes[0], el.nodes[0], el.nodes[1], el.nodes[1]};
    const int comp[4] = {2, 5, 2, 5};  // z, z' at each end (thesis 3.13)
    const auto [lo, hi] = element_columns(el.nodes[0], el.nodes[1]);
    const long n = hi - lo;
    const auto r0 = row(node[0], comp[0]).segment(lo, n), r1 = row(node[1], comp[1]).segment(lo, n);
    const auto r2 = row(node[2], comp[2]).segment(lo, n), r3 = row(node[3], comp[3]).segment(lo, n);
    p.weight.resize(n);
    Eigen::Map<Eigen::RowVectorXd>(p.weight.data(), n) =
        s[0] * r0 + s[1] * r1 + s[2] * r2 + s[3] * r3;
    if (p.index.size() != static_cast<std::size_t>(n) || (n > 0 && p.index[0] != lo)) {
      p.index.resize(n);  // lo .. hi - 1, kept from x to x in the same blocks
      std::iota(p.index.begin(), p.index.end(), static_cast<PetscInt>(lo));
    }
    c.element = element;
    c.chi = chi;
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
    const auto at = [&](int n) { return basis_->contact_flexibility[wire_position_[n]]; };
    const double xi = chi / el.ref_length;
    if (!basis_->contact_flexibility.empty()) {
      p.residual_flexibility = (1 - xi) * at(el.nodes[0]) + xi * at(el.nodes[1]);
      p.residual_flexibility_slope =
          (at(el.nodes[1]) - at(el.nodes[0])) / (el.ref_length * c.x_chi);
    }
  }
  c.x = x;
  return c;
}

// The height (and lateral position) at the loaded eta, computed once per x and eta.
const WirePoint& ModalCatenary::wire_point(double x, int wire) const {
  CachedPoint& c = cached_point(x, wire);
  WirePoint& p = c.point;
  if (p.on_wire && on_owner() && c.eta_version != eta_version_) {
    p.owned = true;
    p.y = c.y_eta.size() > 0 ? c.y0 + c.y_eta.dot(eta_) : c.y0;
    const auto n = static_cast<long>(p.weight.size());
    p.z = c.z0 + Eigen::Map<const Eigen::VectorXd>(p.weight.data(), n)
                     .dot(eta_.segment(n > 0 ? p.index[0] : 0, n));
    c.eta_version = eta_version_;
  }
  return p;
}

// dz/dx with x(chi) static (the contact point moves along the track); its
// row over the modes made on the first call at this x (a run that balances
// no energy never makes it: a pass over four basis rows per step and
// pantograph).
double ModalCatenary::wire_slope(double x, int wire) const {
  CachedPoint& c = cached_point(x, wire);
  if (!c.point.on_wire || !on_owner()) return 0;
  if (!c.z_chi_made) {
    const auto& el = mesh_.cables[c.element];
    const auto ds = catenary::hermite(c.chi, el.ref_length).ds;
    c.z_chi = ds[0] * row(el.nodes[0], 2) + ds[1] * row(el.nodes[0], 5) +
              ds[2] * row(el.nodes[1], 2) + ds[3] * row(el.nodes[1], 5);
    c.z_chi_made = true;
  }
  double slope = (c.z_chi0 + c.z_chi.dot(eta_)) / c.x_chi;
  if (!mesh_.contact_gap_offsets.empty()) slope += mesh_.contact_gap_offsets[wire].slope_at(x);
  return slope;
}

// eta = Omega^-2 sum_p w(x_p) F_p: the modal statics under the forces (slack
// ignored). eta = D^-1 f with D = Omega^2, f = sum_p phi(x_p)^T F_p; with
// active pins (a moving window's end that is the line's: k u u^T each) by
// Woodbury: eta = y - D^-1 U (I / k + U^T D^-1 U)^-1 U^T y, y = D^-1 f.
bool ModalCatenary::closed_form_point_loads(const std::vector<PointForce>& loads, Vec U) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(m_);
  for (const auto& load : loads) {
    const WirePoint& p = wire_point(load.x, load.wire);
    if (!p.on_wire) return false;
    const auto n = static_cast<long>(p.weight.size());
    if (on_owner() && n > 0)
      f.segment(p.index[0], n) +=
          Eigen::Map<const Eigen::VectorXd>(p.weight.data(), n) * load.force;
  }
  PCSIM_PETSC(VecSet(U, 0.0));
  if (!on_owner()) return true;
  const Eigen::Map<const Eigen::VectorXd> omega2(basis_->omega2.data(), m_);
  Eigen::VectorXd y = f.cwiseQuotient(omega2);
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
