// Droppers near the pantographs with their exact force on the modal level,
// taut or slack (ModalExactDroppers, modal_terms.hpp).
#include <algorithm>
#include <cmath>

#include "modal_rows.hpp"
#include "pcsim/assembly/coupled_state.hpp"
#include "pcsim/assembly/modal_terms.hpp"
#include "pcsim/catenary/elements.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::assembly {

namespace {

using FiveRows = Eigen::Matrix<double, 5, Eigen::Dynamic, Eigen::RowMajor>;

// The weights of the six rank-one terms w w^T (w over the rows b, t_1, t_2)
// that sum to the symmetric D: w = b, t_1, t_2 with the diagonal less the
// row's off-diagonal entries, and b + t_1, b + t_2, t_1 + t_2 with D's
// off-diagonal entries.
std::array<double, 6> split(const Eigen::Matrix3d& D) {
  return {D(0, 0) - D(0, 1) - D(0, 2),
          D(1, 1) - D(0, 1) - D(1, 2),
          D(2, 2) - D(0, 2) - D(1, 2),
          D(0, 1),
          D(0, 2),
          D(1, 2)};
}

}  // namespace

ModalExactDroppers::ModalExactDroppers(ModalCatenary& catenary, double reach, bool slack)
    : catenary_(catenary), reach_(reach), modes_(modal_rows::all_modes(catenary)) {
  const auto& bars = catenary.mesh().bars;
  const auto& tracked = catenary.slack_bars();
  for (std::size_t d = 0; d < tracked.size(); ++d) {
    const auto& bar = bars[tracked[d]];
    if (bar.kind != catenary::BarKind::dropper) continue;
    Dropper dropper;
    dropper.tracked = d;
    dropper.q0 = catenary.static_bar_dofs(tracked[d]);
    dropper.x = 0.5 * (dropper.q0[0] + dropper.q0[3]);
    dropper.params = catenary::bar_parameters(bar, slack);
    const Eigen::Vector3d e = (dropper.q0.tail<3>() - dropper.q0.head<3>()).normalized();
    dropper.frame.col(0) = e;
    dropper.frame.col(1) = e.unitOrthogonal();
    dropper.frame.col(2) = e.cross(dropper.frame.col(1));
    catenary::Vec6 f;
    catenary::Mat6 K;
    catenary::bar_internal_force(catenary::bar_parameters(bar, false), dropper.q0, f, &K);
    dropper.f0 = dropper.frame.transpose() * f.tail<3>();
    dropper.K0 = dropper.frame.transpose() * K.bottomRightCorner<3, 3>() * dropper.frame;
    droppers_.push_back(dropper);
  }
}

// From the first step on: the static start (t = 0) stays the linear model's
// closed-form equilibrium, whose coupled Newton on the modal level would be a
// dense LU (minutes at 8000 vectors).
bool ModalExactDroppers::within_reach(const CoupledState& state, const Dropper& dropper) const {
  if (state.t <= 0) return false;
  for (std::size_t p = 0; p < state.pantograph_count(); ++p)
    if (std::abs(dropper.x - state.pantograph(p).run.contact_x(state.t)) <= reach_) return true;
  return false;
}

bool ModalExactDroppers::covers(const CoupledState& state, std::size_t tracked) const {
  const auto it =
      std::lower_bound(droppers_.begin(), droppers_.end(), tracked,
                       [](const Dropper& dropper, std::size_t d) { return dropper.tracked < d; });
  return it != droppers_.end() && it->tracked == tracked && within_reach(state, *it);
}

void ModalExactDroppers::find_active(const CoupledState& state) {
  active_.clear();
  for (std::size_t i = 0; i < droppers_.size(); ++i)
    if (within_reach(state, droppers_[i])) active_.push_back(i);
  // A dropper that left the set gives its rows back.
  for (auto it = rows_.begin(); it != rows_.end();)
    it = std::binary_search(active_.begin(), active_.end(), it->first) ? std::next(it)
                                                                       : rows_.erase(it);
}

const ModalExactDroppers::Rows& ModalExactDroppers::rows(std::size_t i) {
  auto [it, added] = rows_.try_emplace(i);
  if (added) {
    const Dropper& dropper = droppers_[i];
    const int bar = catenary_.slack_bars()[dropper.tracked];
    auto made = std::make_shared<FiveRows>(5, catenary_.catenary_dofs());
    made->row(0) = catenary_.relative_row(bar, dropper.frame.col(1));
    made->row(1) = catenary_.relative_row(bar, dropper.frame.col(2));
    const auto b = catenary_.elongation_rows().row(static_cast<long>(dropper.tracked));
    made->row(2) = b + made->row(0);
    made->row(3) = b + made->row(1);
    made->row(4) = made->row(0) + made->row(1);
    it->second = std::move(made);
  }
  return it->second;
}

Eigen::Vector3d ModalExactDroppers::relative(std::size_t i) const {
  const auto& eta = catenary_.eta();
  const auto& t = *rows_.at(i);
  return {catenary_.elongation_rows().row(static_cast<long>(droppers_[i].tracked)).dot(eta),
          t.row(0).dot(eta), t.row(1).dot(eta)};
}

void ModalExactDroppers::force(std::size_t i, const Eigen::Vector3d& r, Eigen::Vector3d& f,
                               Eigen::Matrix3d* K) const {
  const Dropper& dropper = droppers_[i];
  catenary::Vec6 q = dropper.q0, fq;
  q.tail<3>() += dropper.frame * r;
  catenary::Mat6 Kq;
  catenary::bar_internal_force(dropper.params, q, fq, K ? &Kq : nullptr);
  f = dropper.frame.transpose() * fq.tail<3>();
  if (K) *K = dropper.frame.transpose() * Kq.bottomRightCorner<3, 3>() * dropper.frame;
}

void ModalExactDroppers::add_residual(const CoupledState& state, Vec F) {
  find_active(state);
  if (!catenary_.on_owner() || active_.empty()) return;
  PetscScalar* a;
  PCSIM_PETSC(VecGetArray(F, &a));
  Eigen::Map<Eigen::VectorXd> out(a, catenary_.catenary_dofs());
  for (std::size_t i : active_) {
    const auto& t = *rows(i);
    const Eigen::Vector3d r = relative(i);
    Eigen::Vector3d f;
    force(i, r, f, nullptr);
    const Eigen::Vector3d change = f - droppers_[i].f0 - droppers_[i].K0 * r;
    const auto b = catenary_.elongation_rows().row(static_cast<long>(droppers_[i].tracked));
    // One pass over the modes for the three rows.
    out += (change[0] * b + change[1] * t.row(0) + change[2] * t.row(1)).transpose();
  }
  PCSIM_PETSC(VecRestoreArray(F, &a));
}

void ModalExactDroppers::add_tangent(const CoupledState& state, Shifts, Mat J) {
  find_active(state);
  if (active_.empty()) return;
  const PetscInt m = catenary_.catenary_dofs();
  modal_rows::RowMatrix R(3, m), block = modal_rows::RowMatrix::Zero(m, m);
  for (std::size_t i : active_) {
    const auto& t = *rows(i);
    R.row(0) = catenary_.elongation_rows().row(static_cast<long>(droppers_[i].tracked));
    R.row(1) = t.row(0);
    R.row(2) = t.row(1);
    Eigen::Vector3d f;
    Eigen::Matrix3d K;
    force(i, relative(i), f, &K);
    block += R.transpose() * (K - droppers_[i].K0) * R;
  }
  modal_rows::add_modal_block(catenary_, block, J);
}

bool ModalExactDroppers::low_rank_change(const CoupledState& state, std::vector<RankOne>& terms) {
  find_active(state);
  const long m = catenary_.catenary_dofs();
  for (std::size_t i : active_) {
    const Rows& t = rows(i);
    Eigen::Vector3d f;
    Eigen::Matrix3d K;
    force(i, relative(i), f, &K);
    const std::array<double, 6> weights = split(K - droppers_[i].K0);
    for (int j = 0; j < 6; ++j) {
      // A weight of exactly zero (at the static state) is no term: 1/c in the capacitance.
      if (weights[j] == 0) continue;
      RankOne term;
      term.key = static_cast<int>(6 * droppers_[i].tracked + j);
      term.index = modes_;
      term.weight =
          j == 0
              ? SharedEntries<double>(
                    nullptr,
                    catenary_.elongation_rows().row(static_cast<long>(droppers_[i].tracked)).data(),
                    static_cast<std::size_t>(m))
              : SharedEntries<double>(t, t->row(j - 1).data(), static_cast<std::size_t>(m));
      term.coefficient = weights[j];
      term.contiguous = true;
      terms.push_back(std::move(term));
    }
  }
  return true;
}

double ModalExactDroppers::energy(const CoupledState& state) const {
  const int* tracked = catenary_.slack_bars().data();
  double e = 0;
  for (const Dropper& dropper : droppers_) {
    if (!within_reach(state, dropper)) continue;
    const int bar = tracked[dropper.tracked];
    const Eigen::Vector3d r{
        catenary_.elongation_rows().row(static_cast<long>(dropper.tracked)).dot(catenary_.eta()),
        catenary_.relative_row(bar, dropper.frame.col(1)).dot(catenary_.eta()),
        catenary_.relative_row(bar, dropper.frame.col(2)).dot(catenary_.eta())};
    catenary::Vec6 q = dropper.q0;
    q.tail<3>() += dropper.frame * r;
    e += catenary::bar_strain_energy(dropper.params, q) -
         catenary::bar_strain_energy(dropper.params, dropper.q0) - dropper.f0.dot(r) -
         0.5 * r.dot(dropper.K0 * r);
  }
  return e;
}

}  // namespace pcsim::assembly
