#include "pcsim/simulation/moving_window.hpp"

#include <algorithm>

#include "pcsim/assembly/fe_catenary.hpp"
#include "pcsim/assembly/modal_catenary.hpp"
#include "pcsim/assembly/modal_wind.hpp"
#include "pcsim/assembly/wind_terms.hpp"
#include "pcsim/catenary/window.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/core/profiling.hpp"
#include "pcsim/core/vec_root.hpp"
#include "shift_pass.hpp"
#include "spinning_helper.hpp"

namespace pcsim::simulation {

MovingWindow::MovingWindow(const scene::RunWindow& window, assembly::CoupledSystem& system,
                           std::vector<double> line_support_x)
    : system_(system),
      span_length_(window.span_length),
      line_support_x_(std::move(line_support_x)) {
  fe_ = dynamic_cast<assembly::FECatenary*>(&system.catenary());
  modal_ = dynamic_cast<assembly::ModalCatenary*>(&system.catenary());
  if (!fe_ && !modal_) throw SolverError("moving window: needs the FE or the modal catenary");
  if (modal_ && modal_->basis().shift.size() != modal_->basis().size() * modal_->basis().size())
    throw SolverError("moving window: the modal basis has no shift (modal data without a window)");
  const auto& mesh = system.catenary().mesh();
  shift_at_x_ = mesh.support_x.front() + window.shift_spans() * span_length_;
  const auto& pantographs = system.pantographs();
  for (std::size_t i = 1; i < pantographs.size(); ++i)
    if (pantographs[i].run.start_x > pantographs[lead_].run.start_x) lead_ = i;
  max_shifts_ = window.max_shifts();
  window_supports_ = static_cast<int>(mesh.support_x.size());
  for (int node : mesh.support_nodes)
    window_static_z_.push_back(fe_ ? fe_->static_node_values()[catenary::kNodeDofs * node + 2]
                                   : modal_->static_value(node, 2));
  // A line support's static height: the window's support of the same parity
  // in the middle (the window's end supports are the line's only at its ends).
  const int mid = window_supports_ / 2;
  for (std::size_t k = 0; k < line_support_x_.size(); ++k) {
    const int kk = static_cast<int>(k);
    const int j = kk < mid ? kk : mid - (kk - mid) % 2;
    line_static_z_.push_back(window_static_z_[j]);
  }
  line_spans_ = window.line_spans;
  window_spans_ = window.spans();
  set_pins();
  if (fe_) fe_source(*fe_);
}

MovingWindow::~MovingWindow() = default;

// Only for a pass that takes time: P of at least 1024 vectors (8 MB, about
// 0.8 ms on one core at the 10.5 GB/s measured); a small window's pass is
// shorter than a thread's start.
void MovingWindow::use_spare_core(bool spare) {
  constexpr std::size_t kHelperMinVectors = 1024;
  int rank = 0;
  MPI_Comm_rank(system_.comm(), &rank);
  if (spare && modal_ && rank == 0 && modal_->basis().size() >= kHelperMinVectors)
    helper_ = std::make_unique<SpinningHelper>();
}

// The FE state's shift: every catenary DOF's source two spans ahead.
void MovingWindow::fe_source(const assembly::FECatenary& fe) {
  Vec U0 = system_.create_vector();
  fe.reference_state(U0);
  static_U_ = gather_to_root(U0);
  PCSIM_PETSC(VecDestroy(&U0));
  const auto& layout = fe.system().layout();
  if (layout.rank() != 0) return;
  const auto& mesh = fe.mesh();
  const auto partner = catenary::shifted_nodes(mesh, 2.0 * span_length_);
  source_.assign(static_cast<std::size_t>(layout.catenary_dofs()), -1);
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n)
    for (int c = 0; c < catenary::kNodeDofs; ++c) {
      const PetscInt g = layout.global_dof(static_cast<int>(n), c);
      if (g >= 0 && partner[n] >= 0) source_[g] = layout.global_dof(partner[n], c);
    }
}

void MovingWindow::after_step(double t, solvers::DynamicSolver& solver) {
  const auto& run = system_.pantographs()[lead_].run;
  if (shifts_ >= max_shifts_) return;
  const double x = run.contact_x(t);
  if (x >= shift_at_x_)
    shift(solver);
  else if (helper_)
    wake_helper_ahead(x);
}

// The helper starts when the shift is kHelperLead of wall time away (the
// steps left times the last step's wall time): beyond the second core's
// wake-up (up to 2.6 ms measured), and no longer spinning than that.
void MovingWindow::wake_helper_ahead(double x) {
  constexpr double kHelperLead = 4e-3;  // [s]
  const double now = wall_clock_s();
  if (x > last_x_ && last_wall_ > 0 &&
      (shift_at_x_ - x) / (x - last_x_) * (now - last_wall_) <= kHelperLead)
    helper_->start();
  last_x_ = x;
  last_wall_ = now;
}

// new(g) = U0(g) + (old(s) - U0(s)) for s = source(g): the displacement two
// spans ahead; static where there is none (the new front spans). Pantograph
// unknowns (after the catenary's) keep theirs; every pantograph's contact
// point moves back with the window.
void MovingWindow::shift(solvers::DynamicSolver& solver) {
  solvers::DynamicState s = solver.save_state();  // rank 0: U, V, A in the global order
  if (!s.U.empty()) {
    if (fe_)
      shift_fe(s);
    else
      shift_modal(s);
  }
  solver.replace_state(s.U, s.V, s.A);
  moved(1);  // J0 is rebuilt at the next step (replace_state)
}

// A restart's window: the checkpointed run's shifts (their count checked
// when the checkpoint was read), its state already the window's after them
// (RunCheckpoint::window_shifts).
void MovingWindow::resume(int shifts) {
  if (shifts < 0 || shifts > max_shifts_) throw SolverError("moving window: no such shift count");
  moved(shifts);
}

// What follows the window's count shifts of two spans: the pantographs' contact
// points (one subtraction a shift: the same bits as a run that shifted), the
// pins at the line's ends, the line's turbulence over the window.
void MovingWindow::moved(int count) {
  for (int k = 0; k < count; ++k)
    for (auto& pantograph : system_.pantographs()) pantograph.run.start_x -= 2.0 * span_length_;
  shifts_ += count;
  set_pins();
  if (count == 0) return;
  for (const auto& term : system_.terms()) {
    if (auto* wind = dynamic_cast<assembly::WindTurbulence*>(term.get())) wind->follow(offset());
    if (auto* wind = dynamic_cast<assembly::ModalWindTurbulence*>(term.get()))
      wind->follow(offset());
  }
}

void MovingWindow::shift_fe(solvers::DynamicState& s) const {
  const auto U = s.U, V = s.V, A = s.A;
  for (std::size_t g = 0; g < source_.size(); ++g) {
    const PetscInt from = source_[g];
    s.U[g] = static_U_[g] + (from >= 0 ? U[from] - static_U_[from] : 0.0);
    s.V[g] = from >= 0 ? V[from] : 0.0;
    s.A[g] = from >= 0 ? A[from] : 0.0;
  }
}

// The modal state's shift: eta' = P eta (the M-projection of the shifted
// field on the basis; catenary::ReducedBasis::shift), the same for the
// rates; the modal coordinates lead the global order. One pass over P's rows
// (single precision, shift_pass.hpp) for the three states; it is bound by
// memory (m^2 floats: 112 MB for 5286 vectors); with a core to spare the
// helper takes the back half of the rows.
void MovingWindow::shift_modal(solvers::DynamicState& s) const {
  const long m = static_cast<long>(modal_->basis().size());
  const float* P = modal_->basis().shift.data();
  const std::vector<double> U(s.U.begin(), s.U.begin() + m), V(s.V.begin(), s.V.begin() + m),
      A(s.A.begin(), s.A.begin() + m);
  const double* const from[3] = {U.data(), V.data(), A.data()};
  double* const to[3] = {s.U.data(), s.V.data(), s.A.data()};
  const auto rows = [&](long first, long last) { shift_rows(P, m, from, to, first, last); };
  if (!helper_) return rows(0, m);
  helper_->run([&] { rows(0, m / 2); }, [&] { rows(m / 2, m); });
}

// The window's ends that are the line's anchored ends are pinned: the rear
// before the first shift, the front once it has reached the line's end.
void MovingWindow::set_pins() {
  auto& mesh = fe_ ? fe_->system().mutable_mesh() : modal_->mutable_mesh();
  const double rear = mesh.support_x.front();
  const bool front_at_line_end = 2 * shifts_ + window_spans_ == line_spans_;
  for (auto& pin : mesh.pins)
    pin.active = mesh.nodes[pin.node].position.x() < rear + 1e-6 ? shifts_ == 0 : front_at_line_end;
}

void MovingWindow::to_line(contact::StepRecord& record) const {
  for (double& x : record.contact_x) x += offset();
  // Supports outside the window are at rest (uplift 0); inside, the line's
  // static height plus the window support's displacement.
  std::vector<double> z = line_static_z_;
  for (int j = 0; j < window_supports_ && j < static_cast<int>(record.support_z.size()); ++j) {
    const std::size_t k = static_cast<std::size_t>(j + 2 * shifts_);
    if (k < z.size()) z[k] += record.support_z[j] - window_static_z_[j];
  }
  record.support_z = std::move(z);
}

void MovingWindow::set_line_supports(output::RunLayout& layout) const {
  layout.support_x = line_support_x_;
  layout.support_static_z = line_static_z_;
}

}  // namespace pcsim::simulation
