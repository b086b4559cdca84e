#include "pcsim/contact/interaction.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "pcsim/catenary/elements.hpp"
#include "pcsim/catenary/statics.hpp"
#include "pcsim/contact/contact_kernel.hpp"
#include "pcsim/error.hpp"
#include "pcsim/solvers/direct.hpp"
#include "pcsim/solvers/hht.hpp"

namespace pcsim::contact {

using assembly::CatenarySystem;
using catenary::BarKind;
using catenary::CatenaryMesh;

// ------------------------------------------------------------ locator ----

ContactWireLocator::ContactWireLocator(const CatenaryMesh& mesh,
                                       const std::vector<double>& node_values)
    : mesh_(mesh) {
  if (mesh.contact_wire < 0)
    throw InputError(mesh.source_file, "wires", "the design has no contact wire");
  elements_ = mesh.wires[mesh.contact_wire].elements;
  for (int e : elements_) {
    std::array<double, 12> q{};
    for (int a = 0; a < 2; ++a)
      for (int c = 0; c < 6; ++c) q[6 * a + c] = node_values[6 * mesh.cables[e].nodes[a] + c];
    q_.push_back(q);
    node_x_.push_back(q[0]);
  }
  node_x_.push_back(q_.back()[6]);
  x_begin_ = node_x_.front();
  x_end_ = node_x_.back();
  for (std::size_t i = 1; i < node_x_.size(); ++i)
    if (!(node_x_[i] > node_x_[i - 1]))
      throw InputError(mesh.source_file, "wires",
                       "contact-wire nodes must advance along x (element " +
                           std::to_string(elements_[i - 1]) + ")");
}

bool ContactWireLocator::locate(double x, int& element, double& chi) const {
  if (x < x_begin_ || x > x_end_) return false;
  // Pantographs move steadily: start from the last element found.
  int i = std::clamp(last_, 0, static_cast<int>(elements_.size()) - 1);
  if (!(node_x_[i] <= x && x <= node_x_[i + 1])) {
    auto it = std::upper_bound(node_x_.begin(), node_x_.end(), x);
    i = std::clamp(static_cast<int>(it - node_x_.begin()) - 1, 0,
                   static_cast<int>(elements_.size()) - 1);
  }
  last_ = i;
  element = elements_[i];
  const auto& q = q_[i];
  const Vector12d q12 = Eigen::Map<const Vector12d>(q.data());
  chi = locate_contact_point(q12, mesh_.cables[element].ref_length, x).chi;
  return true;
}

// ------------------------------------------------------------ problem ----

InteractionProblem::InteractionProblem(MPI_Comm comm, CatenaryMesh mesh,
                                       std::vector<double> static_node_values,
                                       std::vector<PantographRun> pantographs,
                                       InteractionEffects effects, double contact_stiffness)
    : static_values_(std::move(static_node_values)),
      pantographs_(std::move(pantographs)),
      effects_(effects),
      kH_(contact_stiffness) {
  if (!effects_.dropper_slack)
    for (auto& bar : mesh.bars) bar.slack = catenary::SlackCriterion::none;
  for (const auto& p : pantographs_) n_panto_dofs_ += p.model->dof_count();
  system_ = std::make_unique<CatenarySystem>(comm, std::move(mesh), n_panto_dofs_);
  PetscInt offset = 0;
  for (const auto& p : pantographs_) {
    panto_first_.push_back(system_->layout().extra_global(offset));
    offset += p.model->dof_count();
  }
  head_offset_.assign(pantographs_.size(), 0.0);
  for (std::size_t b = 0; b < system_->mesh().bars.size(); ++b) {
    if (system_->mesh().bars[b].slack != catenary::SlackCriterion::none)
      slack_bars_.push_back(static_cast<int>(b));
    if (system_->mesh().bars[b].kind == BarKind::dropper) droppers_.push_back(static_cast<int>(b));
  }
  panto_u_.assign(n_panto_dofs_, 0.0);
  panto_v_.assign(n_panto_dofs_, 0.0);
  panto_a_.assign(n_panto_dofs_, 0.0);
  locator_ = std::make_unique<ContactWireLocator>(system_->mesh(), static_values_);
  bool all_linear = true;
  for (const auto& p : pantographs_) all_linear = all_linear && p.model->is_linear();
  cheap_path_ = !effects_.catenary_nonlinear && all_linear;

  // Constant matrices, all with the pattern of the Jacobian.
  Mat pattern = create_matrix();
  PCSIM_PETSC(MatDuplicate(pattern, MAT_DO_NOT_COPY_VALUES, &M_));
  system_->assemble_mass(M_);
  U0_ = system_->create_vector();
  catenary::set_state_from_node_values(*system_, static_values_, U0_);
  work_ = system_->create_vector();
  work2_ = system_->create_vector();
  system_->load_state(U0_);
  auto tangent_of = [&](unsigned terms) {
    Mat K;
    PCSIM_PETSC(MatDuplicate(pattern, MAT_DO_NOT_COPY_VALUES, &K));
    system_->assemble_static(work_, K, terms);
    PCSIM_PETSC(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY));
    PCSIM_PETSC(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY));
    return K;
  };
  const unsigned cables_and_loads = CatenarySystem::kCables | CatenarySystem::kLoads;
  if (!effects_.catenary_nonlinear) {
    // Linearised cables: f(U) ~ b0 + K0 (U - U0), b0 = cable forces + loads at U0.
    K0_ = tangent_of(cables_and_loads);
    b0_ = system_->create_vector();
    system_->assemble_static(b0_, nullptr, cables_and_loads);
  }
  if (effects_.rayleigh_damping) {
    // C = alpha M + beta K at the static configuration (thesis eq. 3.1). The
    // alpha M part is applied with M; of beta K only what K0 does not hold is
    // kept: the bars (linearised cables) or everything (nonlinear cables).
    rayleigh_alpha_ = system_->mesh().rayleigh_alpha;
    rayleigh_beta_ = system_->mesh().rayleigh_beta;
    if (effects_.catenary_nonlinear) {
      C_ = tangent_of(CatenarySystem::kAllTerms);
    } else {
      C_ = system_->layout().create_matrix();  // bar entries only: small
      system_->assemble_static(work_, C_, CatenarySystem::kBars);
      PCSIM_PETSC(MatAssemblyBegin(C_, MAT_FINAL_ASSEMBLY));
      PCSIM_PETSC(MatAssemblyEnd(C_, MAT_FINAL_ASSEMBLY));
    }
    PCSIM_PETSC(MatScale(C_, rayleigh_beta_));
  }
  PCSIM_PETSC(MatDestroy(&pattern));
}

InteractionProblem::~InteractionProblem() {
  clear_low_rank();
  for (auto& term : contact_terms_) {
    VecDestroy(&term.u);
    VecDestroy(&term.z);
  }
  KSPDestroy(&inner_ksp_);
  MatDestroy(&M_);
  MatDestroy(&C_);
  MatDestroy(&K0_);
  VecDestroy(&U0_);
  VecDestroy(&b0_);
  VecDestroy(&work_);
  VecDestroy(&work2_);
}

Mat InteractionProblem::create_matrix() const {
  const auto& L = system_->layout();
  const auto& mesh = system_->mesh();
  const auto& contact_nodes = mesh.wires[mesh.contact_wire].nodes;
  std::vector<std::vector<int>> couplings(n_panto_dofs_);
  for (std::size_t p = 0; p < pantographs_.size(); ++p)
    couplings[panto_first_[p] - L.catenary_dofs() + pantographs_[p].model->contact_dof()] =
        contact_nodes;
  Mat A = L.create_matrix(couplings, true);
  system_->insert_element_pattern(A);
  if (L.rank() == L.size() - 1) {
    // Dense block of each pantograph.
    for (std::size_t p = 0; p < pantographs_.size(); ++p) {
      const int n = pantographs_[p].model->dof_count();
      std::vector<PetscInt> idx(n);
      for (int i = 0; i < n; ++i) idx[i] = panto_first_[p] + i;
      std::vector<double> zeros(n * n, 0.0);
      PCSIM_PETSC(MatSetValues(A, n, idx.data(), n, idx.data(), zeros.data(), ADD_VALUES));
    }
  }
  // Head <-> contact-wire couplings (every DOF of every contact-wire node, as
  // the contact element block is 13 x 13): inserted once, so that the
  // pattern does not change as pantographs move.
  for (std::size_t p = 0; p < pantographs_.size(); ++p) {
    const PetscInt head = panto_first_[p] + pantographs_[p].model->contact_dof();
    for (int n : contact_nodes) {
      if (L.owner(n) != L.rank()) continue;
      for (int c = 0; c < 6; ++c) {
        const PetscInt g = L.global_dof(n, c);
        if (g < 0) continue;
        PCSIM_PETSC(MatSetValue(A, g, head, 0.0, ADD_VALUES));
        PCSIM_PETSC(MatSetValue(A, head, g, 0.0, ADD_VALUES));
      }
    }
  }
  PCSIM_PETSC(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  return A;
}

void InteractionProblem::load_pantograph_state(Vec U, Vec V, Vec A) {
  const auto& L = system_->layout();
  std::vector<double> buffer(3 * n_panto_dofs_, 0.0);
  if (L.rank() == L.size() - 1) {
    Vec vecs[3] = {U, V, A};
    for (int k = 0; k < 3; ++k) {
      if (!vecs[k]) continue;
      const PetscScalar* a;
      PCSIM_PETSC(VecGetArrayRead(vecs[k], &a));
      for (PetscInt i = 0; i < n_panto_dofs_; ++i)
        buffer[k * n_panto_dofs_ + i] = a[L.extra_global(i) - L.first_owned()];
      PCSIM_PETSC(VecRestoreArrayRead(vecs[k], &a));
    }
  }
  if (L.size() > 1)
    MPI_Bcast(buffer.data(), static_cast<int>(buffer.size()), MPI_DOUBLE, L.size() - 1, L.comm());
  std::copy(buffer.begin(), buffer.begin() + n_panto_dofs_, panto_u_.begin());
  std::copy(buffer.begin() + n_panto_dofs_, buffer.begin() + 2 * n_panto_dofs_, panto_v_.begin());
  std::copy(buffer.begin() + 2 * n_panto_dofs_, buffer.end(), panto_a_.begin());
}

InteractionProblem::PantographState InteractionProblem::pantograph_state(std::size_t p) const {
  const int n = pantographs_[p].model->dof_count();
  const PetscInt first = panto_first_[p] - system_->layout().catenary_dofs();
  return {Eigen::Map<const Eigen::VectorXd>(&panto_u_[first], n),
          Eigen::Map<const Eigen::VectorXd>(&panto_v_[first], n),
          Eigen::Map<const Eigen::VectorXd>(&panto_a_[first], n)};
}

double InteractionProblem::ramp_factor(const PantographRun& p, double t) const {
  if (p.static_start || p.ramp_distance <= 0) return 1.0;
  return std::clamp(p.speed * t / p.ramp_distance, 0.0, 1.0);
}

// Penalty contact of every pantograph (thesis 3.9-3.13), assembled by the
// rank that owns the contact element.
InteractionProblem::ContactPoint InteractionProblem::contact_point(std::size_t p, double t) const {
  const auto& L = system_->layout();
  const auto& mesh = system_->mesh();
  const auto& run = pantographs_[p];
  ContactPoint point;
  point.x = run.start_x + run.speed * t;
  point.on_wire = locator_->locate(point.x, point.element, point.chi);
  if (!point.on_wire || L.owner(mesh.cables[point.element].nodes[0]) != L.rank()) return point;
  point.evaluated = true;
  catenary::Vec12 q;
  system_->cable_values(point.element, q.data());
  const PetscInt first = panto_first_[p] - L.catenary_dofs();
  point.head_height =
      panto_u_[first + run.model->contact_dof()] + run.model->contact_offset() + head_offset_[p];
  point.terms = evaluate_penalty_contact(q, point.head_height, point.chi,
                                         mesh.cables[point.element].ref_length, kH_);
  return point;
}

void InteractionProblem::add_contact(double t, Vec F, Mat J) {
  for (std::size_t p = 0; p < pantographs_.size(); ++p) {
    const ContactPoint point = contact_point(p, t);
    if (!point.evaluated) continue;
    const auto& terms = point.terms;
    if (terms.force <= 0) continue;
    PetscInt idx[13];
    system_->cable_indices(point.element, idx);
    idx[12] = panto_first_[p] + pantographs_[p].model->contact_dof();
    if (F)
      for (int i = 0; i < 13; ++i)  // VecSetValues does not skip constrained (-1) DOFs
        if (idx[i] >= 0) PCSIM_PETSC(VecSetValue(F, idx[i], terms.residual[i], ADD_VALUES));
    if (J) {
      Eigen::Matrix<double, 13, 13, Eigen::RowMajor> K = terms.tangent;
      PCSIM_PETSC(MatSetValues(J, 13, idx, 13, idx, K.data(), ADD_VALUES));
    }
  }
}

void InteractionProblem::residual(double t, Vec U, Vec V, Vec A, Vec F) {
  const auto& L = system_->layout();
  system_->load_state(U);
  load_pantograph_state(U, V, A);
  // Linear terms with two large products, using C = alpha M + beta K:
  //   K0 (U - U0 + beta V) + M (A + alpha V) + C_rest V.
  if (effects_.catenary_nonlinear) {
    system_->assemble_static(F, nullptr, CatenarySystem::kAllTerms);
  } else {
    system_->assemble_static(F, nullptr, CatenarySystem::kBars);
    PCSIM_PETSC(VecWAXPY(work_, -1.0, U0_, U));
    if (C_) PCSIM_PETSC(VecAXPY(work_, rayleigh_beta_, V));
    PCSIM_PETSC(MatMultAdd(K0_, work_, F, F));
    PCSIM_PETSC(VecAXPY(F, 1.0, b0_));
  }
  if (C_) {
    PCSIM_PETSC(VecWAXPY(work2_, rayleigh_alpha_, V, A));
    PCSIM_PETSC(MatMultAdd(M_, work2_, F, F));
    PCSIM_PETSC(MatMultAdd(C_, V, F, F));
  } else {
    PCSIM_PETSC(MatMultAdd(M_, A, F, F));
  }
  if (L.rank() == L.size() - 1) {
    for (std::size_t p = 0; p < pantographs_.size(); ++p) {
      const auto& run = pantographs_[p];
      const int n = run.model->dof_count();
      const auto state = pantograph_state(p);
      Eigen::VectorXd R(n);
      run.model->residual(t, state.q, state.qd, state.qdd, R);
      // Ramp-up (thesis 3.3.1): the head carries (1 - ramp) F0 downwards.
      R[run.model->contact_dof()] += (1.0 - ramp_factor(run, t)) * run.static_force;
      std::vector<PetscInt> idx(n);
      for (int i = 0; i < n; ++i) idx[i] = panto_first_[p] + i;
      PCSIM_PETSC(VecSetValues(F, n, idx.data(), R.data(), ADD_VALUES));
    }
  }
  add_contact(t, F, nullptr);
  PCSIM_PETSC(VecAssemblyBegin(F));
  PCSIM_PETSC(VecAssemblyEnd(F));
}

void InteractionProblem::jacobian(double t, Vec U, Vec V, Vec A, double shift_v, double shift_a,
                                  Mat J) {
  if (cheap_path_ && shift_v == cached_shift_v_ && shift_a == cached_shift_a_) {
    // J0 is kept; contact and switched droppers follow the state through
    // the low-rank terms.
    system_->load_state(U);
    load_pantograph_state(U, V, A);
    if (update_low_rank(t)) return;
  }
  const auto& L = system_->layout();
  system_->load_state(U);
  load_pantograph_state(U, V, A);
  PCSIM_PETSC(MatZeroEntries(J));
  system_->assemble_static(
      work2_, J, effects_.catenary_nonlinear ? CatenarySystem::kAllTerms : CatenarySystem::kBars);
  if (L.rank() == L.size() - 1) {
    for (std::size_t p = 0; p < pantographs_.size(); ++p) {
      const auto& run = pantographs_[p];
      const int n = run.model->dof_count();
      const auto state = pantograph_state(p);
      Eigen::MatrixXd Kq(n, n), Cq(n, n), Mq(n, n);
      run.model->tangents(t, state.q, state.qd, state.qdd, Kq, Cq, Mq);
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> Jp =
          Kq + shift_v * Cq + shift_a * Mq;
      std::vector<PetscInt> idx(n);
      for (int i = 0; i < n; ++i) idx[i] = panto_first_[p] + i;
      PCSIM_PETSC(MatSetValues(J, n, idx.data(), n, idx.data(), Jp.data(), ADD_VALUES));
    }
  }
  if (!cheap_path_) add_contact(t, nullptr, J);
  PCSIM_PETSC(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  // J = K + shift_v C + shift_a M with C = alpha M + beta K0 + C_rest.
  const double beta = C_ ? rayleigh_beta_ : 0.0, alpha = C_ ? rayleigh_alpha_ : 0.0;
  if (!effects_.catenary_nonlinear)
    PCSIM_PETSC(MatAXPY(J, 1.0 + shift_v * beta, K0_, SAME_NONZERO_PATTERN));
  PCSIM_PETSC(MatAXPY(J, shift_a + shift_v * alpha, M_, SAME_NONZERO_PATTERN));
  if (C_)
    PCSIM_PETSC(
        MatAXPY(J, shift_v, C_,
                effects_.catenary_nonlinear ? SAME_NONZERO_PATTERN : SUBSET_NONZERO_PATTERN));
  cached_shift_v_ = shift_v;
  cached_shift_a_ = shift_a;
  if (cheap_path_) {
    // New J0: its low-rank terms are rebuilt after the factorisation.
    j0_bar_states_ = bar_states();
    j0_bar_tangents_.assign(slack_bars_.size(), Eigen::Matrix3d::Zero());
    for (std::size_t i = 0; i < slack_bars_.size(); ++i)
      if (L.owner(system_->mesh().bars[slack_bars_[i]].nodes[0]) == L.rank())
        j0_bar_tangents_[i] = bar_tangent_block(slack_bars_[i]);
    inner_factored_ = false;
    clear_low_rank();
    update_low_rank(t);
  }
}

// Whether each slack-capable bar is stiff (taut) at the loaded state, on
// every rank. The cheap path refactors J0 when this changes.
std::vector<char> InteractionProblem::bar_states() const {
  const auto& L = system_->layout();
  const auto& mesh = system_->mesh();
  std::vector<char> states(slack_bars_.size(), 0);
  for (std::size_t i = 0; i < slack_bars_.size(); ++i) {
    const int b = slack_bars_[i];
    if (L.owner(mesh.bars[b].nodes[0]) != L.rank()) continue;
    catenary::Vec6 q;
    system_->bar_values(b, q.data());
    double dN_dl = 0;
    catenary::bar_axial_force(catenary::bar_parameters(mesh.bars[b]), q, &dN_dl);
    states[i] = dN_dl > 0 ? 1 : 0;
  }
  if (L.size() > 1)
    MPI_Allreduce(MPI_IN_PLACE, states.data(), static_cast<int>(states.size()), MPI_CHAR, MPI_MAX,
                  L.comm());
  return states;
}

Eigen::Matrix3d InteractionProblem::bar_tangent_block(int bar) const {
  catenary::Vec6 q, f;
  catenary::Mat6 K;
  system_->bar_values(bar, q.data());
  catenary::bar_internal_force(catenary::bar_parameters(system_->mesh().bars[bar]), q, f, &K);
  return K.topLeftCorner<3, 3>();
}

void InteractionProblem::clear_low_rank() {
  for (auto& [g, v] : unit_solutions_) VecDestroy(&v);
  unit_solutions_.clear();
  for (auto& [b, terms] : bar_terms_)
    for (auto& term : terms) {
      VecDestroy(&term.u);
      VecDestroy(&term.z);
    }
  bar_terms_.clear();
  bar_term_state_.clear();
  contact_element_.assign(pantographs_.size(), -1);
  contact_chi_.assign(pantographs_.size(), -1.0);
  capacitance_dirty_ = true;
}

// J0^-1 e_g, solved once per J0 and cached.
Vec InteractionProblem::unit_solution(PetscInt g) {
  auto it = unit_solutions_.find(g);
  if (it != unit_solutions_.end()) return it->second;
  Vec e = create_vector(), z = create_vector();
  PCSIM_PETSC(VecSet(e, 0.0));
  PetscInt lo, hi;
  PCSIM_PETSC(VecGetOwnershipRange(e, &lo, &hi));
  if (g >= lo && g < hi) PCSIM_PETSC(VecSetValue(e, g, 1.0, INSERT_VALUES));
  PCSIM_PETSC(VecAssemblyBegin(e));
  PCSIM_PETSC(VecAssemblyEnd(e));
  PCSIM_PETSC(KSPSolve(inner_ksp_, e, z));
  PCSIM_PETSC(VecDestroy(&e));
  unit_solutions_[g] = z;
  return z;
}

// Contact of pantograph p: u_p = [S_z(chi); -1] on the contact element's DOFs
// and the head DOF, coefficient kH while in contact. Switched dropper b:
// u_b = [-e; e] on its position DOFs, coefficient +k (taut now, slack in J0)
// or -k (slack now, taut in J0). Called at every Newton iteration.
bool InteractionProblem::update_low_rank(double t) {
  const auto& L = system_->layout();
  const auto& mesh = system_->mesh();
  const std::size_t np = pantographs_.size();
  if (contact_terms_.empty()) {
    contact_terms_.resize(np);
    for (auto& term : contact_terms_) {
      term.u = create_vector();
      term.z = create_vector();
    }
    contact_element_.assign(np, -1);
    contact_chi_.assign(np, -1.0);
  }
  // Switched droppers.
  const std::vector<char> states = bar_states();
  std::vector<int> switched;
  for (std::size_t i = 0; i < slack_bars_.size(); ++i)
    if (states[i] != j0_bar_states_[i]) switched.push_back(static_cast<int>(i));
  if (switched.size() > 12) return false;  // refactor J0 instead
  for (auto it = bar_terms_.begin(); it != bar_terms_.end();) {
    if (std::find(switched.begin(), switched.end(), it->first) == switched.end() ||
        bar_term_state_[it->first] != states[it->first]) {
      for (auto& term : it->second) {
        VecDestroy(&term.u);
        VecDestroy(&term.z);
      }
      bar_term_state_.erase(it->first);
      it = bar_terms_.erase(it);
      capacitance_dirty_ = true;
    } else {
      ++it;
    }
  }
  for (int i : switched) {
    if (bar_terms_.count(i)) continue;
    // Change of the bar's tangent since J0, frozen at the switch (as a
    // refactorisation there would be): B (x) dK3 = sum_j lambda_j w_j w_j^T,
    // w_j = [v_j; -v_j] for the eigenpairs (lambda_j, v_j) of dK3.
    const int b = slack_bars_[i];
    std::array<double, 12> eig{};  // 3 eigenvalues, 3 eigenvectors
    if (L.owner(mesh.bars[b].nodes[0]) == L.rank()) {
      const Eigen::Matrix3d dK = bar_tangent_block(b) - j0_bar_tangents_[i];
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
    system_->bar_indices(b, idx);
    auto& terms = bar_terms_[i];
    bar_term_state_[i] = states[i];
    capacitance_dirty_ = true;
    for (int j = 0; j < 3; ++j) {
      if (std::abs(eig[j]) <= 1e-12 * scale) continue;
      LowRankTerm term;
      term.coefficient = eig[j];
      term.u = create_vector();
      term.z = create_vector();
      PCSIM_PETSC(VecSet(term.u, 0.0));
      if (L.rank() == 0)
        for (int c = 0; c < 3; ++c) {
          const double v = eig[3 + 3 * j + c];
          if (idx[c] >= 0) PCSIM_PETSC(VecSetValue(term.u, idx[c], v, INSERT_VALUES));
          if (idx[3 + c] >= 0) PCSIM_PETSC(VecSetValue(term.u, idx[3 + c], -v, INSERT_VALUES));
        }
      PCSIM_PETSC(VecAssemblyBegin(term.u));
      PCSIM_PETSC(VecAssemblyEnd(term.u));
      if (inner_factored_) PCSIM_PETSC(KSPSolve(inner_ksp_, term.u, term.z));
      terms.push_back(term);
    }
  }
  // Contact: element, chi and contact state are known on the element's owner.
  std::vector<double> info(3 * np, 0.0);
  for (std::size_t p = 0; p < np; ++p) {
    const ContactPoint point = contact_point(p, t);
    if (!point.on_wire) {
      if (L.rank() == 0) info[3 * p] = -1;
      continue;
    }
    if (!point.evaluated) continue;
    info[3 * p] = point.element;
    info[3 * p + 1] = point.chi;
    info[3 * p + 2] = point.terms.force > 0 ? 1.0 : 0.0;
  }
  if (L.size() > 1)
    MPI_Allreduce(MPI_IN_PLACE, info.data(), static_cast<int>(info.size()), MPI_DOUBLE, MPI_SUM,
                  L.comm());
  for (std::size_t p = 0; p < np; ++p) {
    const int element = static_cast<int>(std::lround(info[3 * p]));
    const double coefficient = element >= 0 && info[3 * p + 2] > 0.5 ? kH_ : 0.0;
    if (coefficient != contact_terms_[p].coefficient) capacitance_dirty_ = true;
    contact_terms_[p].coefficient = coefficient;
    if (element < 0 || (element == contact_element_[p] && info[3 * p + 1] == contact_chi_[p]))
      continue;
    capacitance_dirty_ = true;
    contact_element_[p] = element;
    contact_chi_[p] = info[3 * p + 1];
    // u_p and, from cached unit solves, z_p = sum_k S_k J0^-1 e_k - J0^-1 e_head.
    const Vector12d S = shape_row(contact_chi_[p], mesh.cables[element].ref_length, 2);
    PetscInt idx[12];
    system_->cable_indices(element, idx);
    std::vector<PetscInt> dofs;
    std::vector<PetscScalar> weights;
    for (int i = 0; i < 12; ++i)
      if (idx[i] >= 0 && S[i] != 0.0) {
        dofs.push_back(idx[i]);
        weights.push_back(S[i]);
      }
    dofs.push_back(panto_first_[p] + pantographs_[p].model->contact_dof());
    weights.push_back(-1.0);
    PCSIM_PETSC(VecSet(contact_terms_[p].u, 0.0));
    if (L.rank() == 0)  // every index is known everywhere: one rank sets them
      PCSIM_PETSC(VecSetValues(contact_terms_[p].u, static_cast<PetscInt>(dofs.size()), dofs.data(),
                               weights.data(), INSERT_VALUES));
    PCSIM_PETSC(VecAssemblyBegin(contact_terms_[p].u));
    PCSIM_PETSC(VecAssemblyEnd(contact_terms_[p].u));
    if (inner_factored_) {
      // Keep only the unit solutions of the current contact elements' DOFs.
      std::vector<PetscInt> keep = dofs;
      for (std::size_t other = 0; other < np; ++other) {
        if (other == p || contact_element_[other] < 0) continue;
        PetscInt other_idx[12];
        system_->cable_indices(contact_element_[other], other_idx);
        keep.insert(keep.end(), other_idx, other_idx + 12);
        keep.push_back(panto_first_[other] + pantographs_[other].model->contact_dof());
      }
      for (auto it = unit_solutions_.begin(); it != unit_solutions_.end();) {
        if (std::find(keep.begin(), keep.end(), it->first) == keep.end()) {
          VecDestroy(&it->second);
          it = unit_solutions_.erase(it);
        } else {
          ++it;
        }
      }
      std::vector<Vec> columns;
      for (PetscInt g : dofs) columns.push_back(unit_solution(g));
      PCSIM_PETSC(VecSet(contact_terms_[p].z, 0.0));
      PCSIM_PETSC(VecMAXPY(contact_terms_[p].z, static_cast<PetscInt>(columns.size()),
                           weights.data(), columns.data()));
    }
  }
  return true;
}

PetscErrorCode InteractionProblem::woodbury_setup(PC pc) {
  PCSIM_CALLBACK_BEGIN
  InteractionProblem* self;
  PCSIM_PETSC(PCShellGetContext(pc, &self));
  Mat A, P;
  PCSIM_PETSC(PCGetOperators(pc, &A, &P));
  PCSIM_PETSC(KSPSetOperators(self->inner_ksp_, A, P));
  PCSIM_PETSC(KSPSetUp(self->inner_ksp_));
  self->inner_factored_ = true;
  // The factorisation changed: every z must be recomputed.
  for (auto& [b, terms] : self->bar_terms_)
    for (auto& term : terms) PCSIM_PETSC(KSPSolve(self->inner_ksp_, term.u, term.z));
  for (std::size_t p = 0; p < self->contact_terms_.size(); ++p)
    if (self->contact_element_[p] >= 0)
      PCSIM_PETSC(KSPSolve(self->inner_ksp_, self->contact_terms_[p].u, self->contact_terms_[p].z));
  self->capacitance_dirty_ = true;
  PCSIM_CALLBACK_END
}

// x = (J0 + U C U^T)^-1 r = y - Z (C^-1 + U^T Z)^-1 U^T y,  y = J0^-1 r.
PetscErrorCode InteractionProblem::woodbury_apply(PC pc, Vec r, Vec x) {
  PCSIM_CALLBACK_BEGIN
  InteractionProblem* self;
  PCSIM_PETSC(PCShellGetContext(pc, &self));
  PCSIM_PETSC(KSPSolve(self->inner_ksp_, r, x));
  if (self->capacitance_dirty_) {
    self->active_terms_.clear();
    for (auto& term : self->contact_terms_)
      if (term.coefficient != 0) self->active_terms_.push_back(&term);
    for (auto& [b, terms] : self->bar_terms_)
      for (auto& term : terms) self->active_terms_.push_back(&term);
    const std::size_t k = self->active_terms_.size();
    self->capacitance_.resize(k, k);
    std::vector<Vec> zs(k);
    for (std::size_t j = 0; j < k; ++j) zs[j] = self->active_terms_[j]->z;
    std::vector<PetscScalar> row(k);
    for (std::size_t i = 0; i < k; ++i) {
      if (k > 0)
        PCSIM_PETSC(
            VecMDot(self->active_terms_[i]->u, static_cast<PetscInt>(k), zs.data(), row.data()));
      for (std::size_t j = 0; j < k; ++j)
        self->capacitance_(i, j) =
            row[j] + (i == j ? 1.0 / self->active_terms_[i]->coefficient : 0.0);
    }
    self->capacitance_dirty_ = false;
  }
  const std::size_t k = self->active_terms_.size();
  if (k == 0) return 0;
  std::vector<Vec> us(k), zs(k);
  for (std::size_t j = 0; j < k; ++j) {
    us[j] = self->active_terms_[j]->u;
    zs[j] = self->active_terms_[j]->z;
  }
  std::vector<PetscScalar> w(k);
  PCSIM_PETSC(VecMDotBegin(x, static_cast<PetscInt>(k), us.data(), w.data()));
  PCSIM_PETSC(VecMDotEnd(x, static_cast<PetscInt>(k), us.data(), w.data()));
  // U^T y with y = x: VecMDot conjugates the second argument; real scalars.
  Eigen::VectorXd s =
      self->capacitance_.lu().solve(Eigen::Map<Eigen::VectorXd>(w.data(), static_cast<long>(k)));
  for (auto& v : s) v = -v;
  PCSIM_PETSC(VecMAXPY(x, static_cast<PetscInt>(k), s.data(), zs.data()));
  PCSIM_CALLBACK_END
}

void InteractionProblem::initial_state(Vec U0, Vec V0) {
  const auto& L = system_->layout();
  const auto& mesh = system_->mesh();
  PCSIM_PETSC(VecSet(V0, 0.0));
  std::vector<double> catenary_values = static_values_;
  // Static start: the catenary under the first pantograph's static force.
  if (!pantographs_.empty() && pantographs_[0].static_start) {
    const auto& run = pantographs_[0];
    int element;
    double chi;
    if (!locator_->locate(run.start_x, element, chi))
      throw InputError("", "pantographs[0].start_x",
                       "the pantograph starts outside the contact wire");
    CatenarySystem loaded(L.comm(), mesh);
    loaded.point_loads().push_back({element, chi, Eigen::Vector3d(0, 0, run.static_force)});
    Vec x = loaded.create_vector();
    catenary::set_state_from_node_values(loaded, static_values_, x);
    auto result = catenary::solve_static(loaded, x, false, "start_");
    catenary_values = result.node_values;
    PCSIM_PETSC(VecDestroy(&x));
  }
  catenary::set_state_from_node_values(*system_, catenary_values, U0);
  // Pantographs in static equilibrium: touching the wire (ramp, zero contact
  // force at t = 0) or pressing it with F0 (static start).
  std::vector<double> q0_all(n_panto_dofs_, 0.0);
  for (std::size_t p = 0; p < pantographs_.size(); ++p) {
    auto& run = pantographs_[p];
    int element;
    double chi;
    if (!locator_->locate(run.start_x, element, chi))
      throw InputError("", "pantographs[" + std::to_string(p) + "].start_x",
                       "the pantograph starts outside the contact wire");
    catenary::Vec12 q;
    for (int a = 0; a < 2; ++a)
      for (int c = 0; c < 6; ++c)
        q[6 * a + c] = catenary_values[6 * mesh.cables[element].nodes[a] + c];
    const double wire_z = catenary::cable_point(mesh.cables[element].ref_length, q, chi).r[2];
    const double penetration = run.static_start ? run.static_force / kH_ : 0.0;
    const double contact_height = wire_z + penetration;
    Eigen::VectorXd q0 = run.model->static_equilibrium(
        run.static_force, run.working_height > 0 ? run.working_height : contact_height);
    // Base of the pantograph: its contact point sits at the wire (thesis 3.3.1).
    head_offset_[p] = contact_height - (q0[run.model->contact_dof()] + run.model->contact_offset());
    const PetscInt first = panto_first_[p] - L.catenary_dofs();
    for (int i = 0; i < run.model->dof_count(); ++i) q0_all[first + i] = q0[i];
  }
  if (L.rank() == L.size() - 1) {
    for (PetscInt i = 0; i < n_panto_dofs_; ++i)
      PCSIM_PETSC(VecSetValue(U0, L.extra_global(i), q0_all[i], INSERT_VALUES));
  }
  PCSIM_PETSC(VecAssemblyBegin(U0));
  PCSIM_PETSC(VecAssemblyEnd(U0));
  // Static start: the state above is a guess (catenary under a point load,
  // pantograph in its own equilibrium). The start is the equilibrium of the
  // dynamic model itself, F(0, U, 0, 0) = 0, so that nothing drifts at t = 0.
  if (!pantographs_.empty() && pantographs_[0].static_start) solve_coupled_static(U0);
}

namespace {
struct CoupledStatic {
  InteractionProblem* problem;
  Vec zero;
};
PetscErrorCode coupled_static_residual(SNES, Vec U, Vec F, void* ptr) {
  PCSIM_CALLBACK_BEGIN
  auto* c = static_cast<CoupledStatic*>(ptr);
  c->problem->residual(0.0, U, c->zero, c->zero, F);
  PCSIM_CALLBACK_END
}
PetscErrorCode coupled_static_jacobian(SNES, Vec U, Mat J, Mat P, void* ptr) {
  PCSIM_CALLBACK_BEGIN
  auto* c = static_cast<CoupledStatic*>(ptr);
  c->problem->jacobian(0.0, U, c->zero, c->zero, 0.0, 0.0, P);
  PCSIM_CALLBACK_END
}
}  // namespace

void InteractionProblem::solve_coupled_static(Vec U0) {
  CoupledStatic ctx{this, nullptr};
  ctx.zero = create_vector();
  PCSIM_PETSC(VecSet(ctx.zero, 0.0));
  Vec F = create_vector();
  Mat J = create_matrix();
  const bool cheap = cheap_path_;
  cheap_path_ = false;  // exact Newton for the start
  SNES snes;
  PCSIM_PETSC(SNESCreate(system_->comm(), &snes));
  PCSIM_PETSC(SNESSetOptionsPrefix(snes, "start_"));
  PCSIM_PETSC(SNESSetFunction(snes, F, coupled_static_residual, &ctx));
  PCSIM_PETSC(SNESSetJacobian(snes, J, J, coupled_static_jacobian, &ctx));
  // The start is an equilibrium to round-off: 1e-6 N on small meshes, ~6e-5 N
  // on the EN 50318 one, where Newton then stops on its step (stol).
  PCSIM_PETSC(SNESSetTolerances(snes, 1e-5, 1e-12, 1e-12, 50, 100000));
  SNESLineSearch line_search;
  PCSIM_PETSC(SNESGetLineSearch(snes, &line_search));
  PCSIM_PETSC(SNESLineSearchSetType(line_search, SNESLINESEARCHBASIC));
  KSP ksp;
  PCSIM_PETSC(SNESGetKSP(snes, &ksp));
  solvers::use_direct_lu(ksp, MATSOLVERMUMPS);
  PCSIM_PETSC(SNESSetFromOptions(snes));
  PCSIM_PETSC(SNESSolve(snes, nullptr, U0));
  SNESConvergedReason reason;
  PCSIM_PETSC(SNESGetConvergedReason(snes, &reason));
  PCSIM_PETSC(SNESGetIterationNumber(snes, &start_iterations_));
  PCSIM_PETSC(SNESDestroy(&snes));
  PCSIM_PETSC(MatDestroy(&J));
  PCSIM_PETSC(VecDestroy(&F));
  PCSIM_PETSC(VecDestroy(&ctx.zero));
  cheap_path_ = cheap;
  cached_shift_v_ = cached_shift_a_ = -1;
  if (reason <= 0)
    throw SolverError(std::string("static start (coupled equilibrium) did not converge: ") +
                      SNESConvergedReasons[reason]);
}

StepRecord InteractionProblem::record(double t, Vec U) {
  const auto& L = system_->layout();
  const auto& mesh = system_->mesh();
  system_->load_state(U);
  load_pantograph_state(U, nullptr, nullptr);
  const std::size_t np = pantographs_.size();
  const std::size_t ns = mesh.support_nodes.size();
  const auto& droppers = droppers_;
  // Layout of the reduction buffer: per pantograph [Fc, x, z_wire], supports, droppers.
  std::vector<double> buffer(3 * np + ns + droppers.size(), 0.0);
  for (std::size_t p = 0; p < np; ++p) {
    const ContactPoint point = contact_point(p, t);
    if (L.rank() == 0) buffer[3 * p + 1] = point.x;
    if (!point.evaluated) continue;
    buffer[3 * p] = point.terms.force;
    buffer[3 * p + 2] = point.terms.gap + point.head_height;
  }
  for (std::size_t s = 0; s < ns; ++s) {
    const int n = mesh.support_nodes[s];
    if (L.owner(n) == L.rank()) buffer[3 * np + s] = system_->node_values(n)[2];
  }
  for (std::size_t d = 0; d < droppers.size(); ++d)
    if (L.owner(mesh.bars[droppers[d]].nodes[0]) == L.rank())
      buffer[3 * np + ns + d] = system_->bar_force(droppers[d]);
  if (L.size() > 1)
    MPI_Reduce(L.rank() == 0 ? MPI_IN_PLACE : buffer.data(), buffer.data(),
               static_cast<int>(buffer.size()), MPI_DOUBLE, MPI_SUM, 0, L.comm());
  StepRecord rec;
  rec.t = t;
  if (L.rank() != 0) return rec;
  for (std::size_t p = 0; p < np; ++p) {
    rec.contact_force.push_back(buffer[3 * p]);
    rec.contact_x.push_back(buffer[3 * p + 1]);
    rec.wire_z.push_back(buffer[3 * p + 2]);
    const PetscInt first = panto_first_[p] - L.catenary_dofs();
    rec.q.emplace_back(panto_u_.begin() + first,
                       panto_u_.begin() + first + pantographs_[p].model->dof_count());
  }
  rec.support_z.assign(buffer.begin() + 3 * np, buffer.begin() + 3 * np + ns);
  rec.dropper_force.assign(buffer.begin() + 3 * np + ns, buffer.end());
  return rec;
}

// ----------------------------------------------------------------- TS ----

namespace {

PetscErrorCode ts_residual(TS, PetscReal t, Vec U, Vec V, Vec A, Vec F, void* ctx) {
  PCSIM_CALLBACK_BEGIN
  static_cast<InteractionProblem*>(ctx)->residual(t, U, V, A, F);
  PCSIM_CALLBACK_END
}

PetscErrorCode ts_jacobian(TS, PetscReal t, Vec U, Vec V, Vec A, PetscReal shift_v,
                           PetscReal shift_a, Mat J, Mat P, void* ctx) {
  PCSIM_CALLBACK_BEGIN
  static_cast<InteractionProblem*>(ctx)->jacobian(t, U, V, A, shift_v, shift_a, P);
  if (J != P) {
    PCSIM_PETSC(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
    PCSIM_PETSC(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  }
  PCSIM_CALLBACK_END
}

}  // namespace

TS InteractionProblem::create_ts(double dt, double duration) {
  solvers::register_hht_ts();
  TS ts;
  PCSIM_PETSC(TSCreate(system_->comm(), &ts));
  PCSIM_PETSC(TSSetType(ts, solvers::kTSHHT));
  Vec F = create_vector();
  Mat J = create_matrix();
  PCSIM_PETSC(TSSetI2Function(ts, F, ts_residual, this));
  PCSIM_PETSC(TSSetI2Jacobian(ts, J, J, ts_jacobian, this));
  PCSIM_PETSC(VecDestroy(&F));
  PCSIM_PETSC(MatDestroy(&J));
  PCSIM_PETSC(TSSetTimeStep(ts, dt));
  PCSIM_PETSC(TSSetMaxTime(ts, duration));
  PCSIM_PETSC(TSSetMaxSteps(ts, 100000000));
  PCSIM_PETSC(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  SNES snes;
  KSP ksp;
  PC pc;
  PCSIM_PETSC(TSGetSNES(ts, &snes));
  // Residuals are forces [N]. The step matrix is dominated by M/(beta dt^2)
  // (~2e6 N/m per wire node at dt = 1 ms), so a residual r leaves position
  // errors ~r/2e6 m and contact-force errors ~kH r/2e6 = 0.025 r N. Measured on
  // the EN 50318 case: atol 5e-2 N changes the contact force by at most 6e-3 N
  // against atol 1e-2 N (statistics by <= 0.01 N) and saves 40 % of the
  // Newton iterations. -snes_atol tightens it.
  PCSIM_PETSC(SNESSetTolerances(snes, 5e-2, 1e-9, 0.0, 25, 100000));
  SNESLineSearch line_search;
  PCSIM_PETSC(SNESGetLineSearch(snes, &line_search));
  PCSIM_PETSC(SNESLineSearchSetType(line_search, SNESLINESEARCHBASIC));
  PCSIM_PETSC(SNESGetKSP(snes, &ksp));
  PCSIM_PETSC(KSPSetType(ksp, KSPPREONLY));
  PCSIM_PETSC(KSPGetPC(ksp, &pc));
  // The step matrix (M/(beta dt^2) dominant) needs no pivoting: on one rank
  // PETSc's own sparse LU with minimum-degree ordering has the cheapest
  // solves (measured 4x faster than MUMPS on the EN 50318 mesh); MUMPS in parallel.
  auto set_direct_solver = [&](PC direct, const char* prefix) {
    PCSIM_PETSC(PCSetType(direct, PCLU));
    if (system_->layout().size() == 1) {
      PCSIM_PETSC(PCFactorSetMatSolverType(direct, MATSOLVERPETSC));
      PCSIM_PETSC(PCFactorSetMatOrderingType(direct, MATORDERINGQMD));
    } else {
      PCSIM_PETSC(PCFactorSetMatSolverType(direct, MATSOLVERMUMPS));
      // METIS ordering: 2.4x faster solves than MUMPS's default choice (PORD)
      // on the EN 50318 mesh on 2 ranks. A user's option wins.
      const std::string option = std::string("-") + prefix + "mat_mumps_icntl_7";
      PetscBool set = PETSC_FALSE;
      PCSIM_PETSC(PetscOptionsHasName(nullptr, nullptr, option.c_str(), &set));
      if (!set) PCSIM_PETSC(PetscOptionsSetValue(nullptr, option.c_str(), "5"));
    }
  };
  if (cheap_path_) {
    // J0 factored once; contact added by Woodbury (see the header).
    PCSIM_PETSC(KSPCreate(system_->comm(), &inner_ksp_));
    PCSIM_PETSC(KSPSetOptionsPrefix(inner_ksp_, "cheap_"));
    PCSIM_PETSC(KSPSetType(inner_ksp_, KSPPREONLY));
    PC inner_pc;
    PCSIM_PETSC(KSPGetPC(inner_ksp_, &inner_pc));
    set_direct_solver(inner_pc, "cheap_");
    PCSIM_PETSC(KSPSetFromOptions(inner_ksp_));
    PCSIM_PETSC(PCSetType(pc, PCSHELL));
    PCSIM_PETSC(PCShellSetContext(pc, this));
    PCSIM_PETSC(PCShellSetSetUp(pc, woodbury_setup));
    PCSIM_PETSC(PCShellSetApply(pc, woodbury_apply));
    PCSIM_PETSC(PCShellSetName(pc, "pcsim cheap path: J0 factored once + Woodbury contact"));
  } else {
    set_direct_solver(pc, "");
  }
  PCSIM_PETSC(TSSetFromOptions(ts));
  return ts;
}

// ------------------------------------------------------------- energy ----
// Energy for balance tests (see the header for what is included). The
// potentials are those whose gradients residual() assembles: b0 + K0 dU
// (linearised cables and loads), the bar forces, the pantograph forces without
// damping, and the penalty force kH (-gap) at fixed chi (thesis 3.9-3.10).

double InteractionProblem::energy(double t, Vec U, Vec V) {
  if (effects_.catenary_nonlinear)
    throw SolverError("InteractionProblem::energy needs the linearised catenary");
  const auto& L = system_->layout();
  const auto& mesh = system_->mesh();
  PetscScalar vmv = 0, uku = 0, b0u = 0;
  PCSIM_PETSC(MatMult(M_, V, work2_));
  PCSIM_PETSC(VecDot(V, work2_, &vmv));
  PCSIM_PETSC(VecWAXPY(work_, -1.0, U0_, U));
  PCSIM_PETSC(MatMult(K0_, work_, work2_));
  PCSIM_PETSC(VecDot(work_, work2_, &uku));
  PCSIM_PETSC(VecDot(b0_, work_, &b0u));
  const double global_part = 0.5 * vmv + b0u + 0.5 * uku;

  system_->load_state(U);
  load_pantograph_state(U, V, nullptr);
  double local = 0;
  catenary::Vec6 q6;
  for (int b : L.local_bars()) {
    system_->bar_values(b, q6.data());
    local += catenary::bar_strain_energy(catenary::bar_parameters(mesh.bars[b]), q6);
  }
  for (std::size_t p = 0; p < pantographs_.size(); ++p) {
    const auto& run = pantographs_[p];
    const int n = run.model->dof_count();
    const int c = run.model->contact_dof();
    const PetscInt first = panto_first_[p] - L.catenary_dofs();
    const Eigen::VectorXd q = Eigen::Map<Eigen::VectorXd>(&panto_u_[first], n);
    const Eigen::VectorXd qd = Eigen::Map<Eigen::VectorXd>(&panto_v_[first], n);
    if (L.rank() == L.size() - 1) {
      double external_potential = 0;
      for (int i = 0; i < n; ++i) {
        const Eigen::VectorXd unit = Eigen::VectorXd::Unit(n, i);
        external_potential -= run.model->power(t, q, unit).external * q[i];
      }
      local += run.model->kinetic_energy(q, qd) + run.model->potential_energy(q) +
               external_potential + (1.0 - ramp_factor(run, t)) * run.static_force * q[c];
    }
    int element;
    double chi;
    if (!locator_->locate(run.start_x + run.speed * t, element, chi)) continue;
    if (L.owner(mesh.cables[element].nodes[0]) != L.rank()) continue;
    catenary::Vec12 qe;
    system_->cable_values(element, qe.data());
    const double head_height = q[c] + run.model->contact_offset() + head_offset_[p];
    const auto terms =
        evaluate_penalty_contact(qe, head_height, chi, mesh.cables[element].ref_length, kH_);
    if (terms.force > 0) local += 0.5 * kH_ * terms.gap * terms.gap;
  }
  double local_sum = 0;
  MPI_Allreduce(&local, &local_sum, 1, MPI_DOUBLE, MPI_SUM, L.comm());
  return global_part + local_sum;
}

}  // namespace pcsim::contact
