// Bar forces and dropper slackening (thesis 3.1.2) as a term; see
// catenary_terms.hpp for the cheap-path treatment of switching bars.
#include <mpi.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "pcsim/assembly/catenary_terms.hpp"
#include "pcsim/assembly/coupled_state.hpp"
#include "pcsim/catenary/elements.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::assembly {

// Without slack every bar is taut (CatenarySystem::kTautBars): none switches.
BarForces::BarForces(FECatenary& catenary, bool slack)
    : catenary_(catenary),
      slack_(slack),
      parts_(slack ? CatenarySystem::kBars : CatenarySystem::kBars | CatenarySystem::kTautBars) {
  const auto& bars = catenary_.mesh().bars;
  for (std::size_t b = 0; b < bars.size(); ++b)
    if (slack && bars[b].slack != catenary::SlackCriterion::none)
      slack_bars_.push_back(static_cast<int>(b));
}

void BarForces::add_residual(const CoupledState&, Vec F) {
  catenary_.system().add_forces(F, nullptr, parts_);
}

void BarForces::add_tangent(const CoupledState&, Shifts, Mat J) {
  catenary_.system().add_forces(nullptr, J, parts_);
}

double BarForces::energy(const CoupledState&) const {
  double local = catenary_.system().local_potential_energy(parts_), total = 0;
  MPI_Allreduce(&local, &total, 1, MPI_DOUBLE, MPI_SUM, catenary_.comm());
  return total;
}

// Whether each slack-capable bar is stiff (taut) at the loaded state, on
// the rank that owns its first node (0 elsewhere).
std::vector<char> BarForces::local_bar_states() const {
  const auto& L = catenary_.system().layout();
  const auto& bars = catenary_.mesh().bars;
  std::vector<char> states(slack_bars_.size(), 0);
  for (std::size_t i = 0; i < slack_bars_.size(); ++i) {
    const int b = slack_bars_[i];
    if (L.owner(bars[b].nodes[0]) != L.rank()) continue;
    catenary::Vec6 q;
    catenary_.system().bar_values(b, q.data());
    double dN_dl = 0;
    catenary::bar_axial_force(catenary::bar_parameters(bars[b]), q, &dN_dl);
    states[i] = dN_dl > 0 ? 1 : 0;
  }
  return states;
}

// The same on every rank.
std::vector<char> BarForces::bar_states() const {
  const auto& L = catenary_.system().layout();
  std::vector<char> states = local_bar_states();
  if (L.size() > 1)
    MPI_Allreduce(MPI_IN_PLACE, states.data(), static_cast<int>(states.size()), MPI_CHAR, MPI_MAX,
                  L.comm());
  return states;
}

Eigen::Matrix3d BarForces::tangent_block(int bar) const {
  catenary::Vec6 q, f;
  catenary::Mat6 K;
  catenary_.system().bar_values(bar, q.data());
  catenary::bar_internal_force(catenary::bar_parameters(catenary_.mesh().bars[bar]), q, f, &K);
  return K.topLeftCorner<3, 3>();
}

void BarForces::add_reference_tangent(const CoupledState& state, Shifts shifts, Mat J) {
  add_tangent(state, shifts, J);
  const auto& L = catenary_.system().layout();
  reference_states_ = bar_states();
  reference_blocks_.assign(slack_bars_.size(), Eigen::Matrix3d::Zero());
  for (std::size_t i = 0; i < slack_bars_.size(); ++i)
    if (L.owner(catenary_.mesh().bars[slack_bars_[i]].nodes[0]) == L.rank())
      reference_blocks_[i] = tangent_block(slack_bars_[i]);
  frozen_.clear();
}

// Change of bar i's tangent since J0, frozen now: B (x) dK3 = sum_j lambda_j
// w_j w_j^T, w_j = [v_j; -v_j] for the eigenpairs (lambda_j, v_j) of dK3.
std::vector<RankOne> BarForces::switch_terms(std::size_t i) const {
  const auto& L = catenary_.system().layout();
  const int b = slack_bars_[i];
  std::array<double, 12> eig{};  // 3 eigenvalues, 3 eigenvectors
  if (L.owner(catenary_.mesh().bars[b].nodes[0]) == L.rank()) {
    const Eigen::Matrix3d dK = tangent_block(b) - reference_blocks_[i];
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(dK);
    for (int j = 0; j < 3; ++j) {
      eig[j] = solver.eigenvalues()[j];
      for (int c = 0; c < 3; ++c) eig[3 + 3 * j + c] = solver.eigenvectors()(c, j);
    }
  }
  if (L.size() > 1) MPI_Allreduce(MPI_IN_PLACE, eig.data(), 12, MPI_DOUBLE, MPI_SUM, L.comm());
  double scale = 0;
  for (int j = 0; j < 3; ++j) scale = std::max(scale, std::abs(eig[j]));
  PetscInt idx[6];
  catenary_.system().bar_indices(b, idx);
  std::vector<RankOne> terms;
  for (int j = 0; j < 3; ++j) {
    if (std::abs(eig[j]) <= 1e-12 * scale) continue;
    RankOne term;
    term.key = static_cast<int>(3 * i + j);
    term.coefficient = eig[j];
    std::vector<PetscInt> index;
    std::vector<double> weight;
    for (int c = 0; c < 3; ++c) {
      const double v = eig[3 + 3 * j + c];
      if (idx[c] >= 0) index.push_back(idx[c]), weight.push_back(v);
      if (idx[3 + c] >= 0) index.push_back(idx[3 + c]), weight.push_back(-v);
    }
    term.index = std::move(index);
    term.weight = std::move(weight);
    terms.push_back(std::move(term));
  }
  return terms;
}

// Each bar's state from its owner alone: the sum over the ranks is the state.
void BarForces::append_low_rank_sums(const CoupledState&, std::vector<double>& local) const {
  for (char s : local_bar_states()) local.push_back(s);
}

void BarForces::take_low_rank_sums(const double* sums) {
  summed_states_.resize(slack_bars_.size());
  for (std::size_t i = 0; i < slack_bars_.size(); ++i) summed_states_[i] = sums[i] > 0.5 ? 1 : 0;
}

bool BarForces::low_rank_change(const CoupledState&, std::vector<RankOne>& terms) {
  const std::vector<char>& states = summed_states_;  // take_low_rank_sums(), just before
  std::vector<std::size_t> switched;
  for (std::size_t i = 0; i < slack_bars_.size(); ++i)
    if (states[i] != reference_states_[i]) switched.push_back(i);
  if (switched.size() > kMaxSwitched) return false;  // a new J0 is cheaper
  for (auto it = frozen_.begin(); it != frozen_.end();) {
    const bool still = std::find(switched.begin(), switched.end(), it->first) != switched.end();
    it = still && it->second.state == states[it->first] ? std::next(it) : frozen_.erase(it);
  }
  for (std::size_t i : switched)
    if (!frozen_.count(i)) frozen_[i] = {states[i], switch_terms(i)};
  for (const auto& [i, frozen] : frozen_)
    terms.insert(terms.end(), frozen.terms.begin(), frozen.terms.end());
  return true;
}

}  // namespace pcsim::assembly

namespace pcsim::assembly {

// [switched bars; per bar: index, state, terms; per term: key, coefficient,
// reuse_columns, size, indices, weights] (indices are exact in doubles).
std::vector<double> BarForces::checkpoint() const {
  std::vector<double> out = {static_cast<double>(frozen_.size())};
  for (const auto& [i, frozen] : frozen_) {
    out.insert(out.end(), {static_cast<double>(i), static_cast<double>(frozen.state),
                           static_cast<double>(frozen.terms.size())});
    for (const auto& t : frozen.terms) {
      out.insert(out.end(), {static_cast<double>(t.key), t.coefficient, t.reuse_columns ? 1.0 : 0.0,
                             static_cast<double>(t.index.size())});
      for (PetscInt g : t.index) out.push_back(static_cast<double>(g));
      out.insert(out.end(), t.weight.begin(), t.weight.end());
    }
  }
  return out;
}

void BarForces::restore(const std::vector<double>& state) {
  std::size_t pos = 0;
  auto next = [&]() {
    if (pos >= state.size()) throw SolverError("bar forces: truncated checkpoint state");
    return state[pos++];
  };
  frozen_.clear();
  const auto bars = static_cast<std::size_t>(next());
  for (std::size_t b = 0; b < bars; ++b) {
    const auto i = static_cast<std::size_t>(next());
    if (i >= slack_bars_.size()) throw SolverError("bar forces: checkpoint names no slack bar");
    Frozen& frozen = frozen_[i];
    frozen.state = static_cast<char>(next());
    const auto terms = static_cast<std::size_t>(next());
    for (std::size_t k = 0; k < terms; ++k) {
      RankOne t;
      t.key = static_cast<int>(next());
      t.coefficient = next();
      t.reuse_columns = next() != 0;
      const auto n = static_cast<std::size_t>(next());
      std::vector<PetscInt> index;
      std::vector<double> weight;
      for (std::size_t j = 0; j < n; ++j) index.push_back(static_cast<PetscInt>(next()));
      for (std::size_t j = 0; j < n; ++j) weight.push_back(next());
      t.index = std::move(index);
      t.weight = std::move(weight);
      frozen.terms.push_back(std::move(t));
    }
  }
  if (pos != state.size()) throw SolverError("bar forces: checkpoint state too long");
}

}  // namespace pcsim::assembly
