// The coupled second-order system of a dynamic run (thesis 3.2-3.3): the
// catenary model's unknowns followed by every pantograph's (on the last rank),
//   F(t, U, V, A) = sum over the terms the scene switched on = 0,
// with tangent dF/dU + v dF/dV + a dF/dA. A loop over terms: the system knows
// no physics of its own. The linear parts of all terms are merged by matrix
// (one product per constant matrix per residual).
#pragma once

#include <petscmat.h>

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <vector>

#include "pcsim/assembly/catenary_model.hpp"
#include "pcsim/assembly/coupled_state.hpp"
#include "pcsim/assembly/subset_axpy.hpp"
#include "pcsim/assembly/term.hpp"
#include "pcsim/contact/records.hpp"

namespace pcsim::assembly {

class PenaltyContact;

class CoupledSystem {
 public:
  // The pantographs' unknowns must be the catenary model's extras, in order.
  CoupledSystem(std::unique_ptr<CatenaryModel> catenary, std::vector<PantographSlot> pantographs,
                const contact::InteractionEffects& effects, double contact_stiffness);
  ~CoupledSystem();
  CoupledSystem(const CoupledSystem&) = delete;
  CoupledSystem& operator=(const CoupledSystem&) = delete;

  MPI_Comm comm() const { return catenary_->comm(); }
  CatenaryModel& catenary() { return *catenary_; }
  const CatenaryModel& catenary() const { return *catenary_; }
  std::vector<PantographSlot>& pantographs() { return pantographs_; }
  const std::vector<std::unique_ptr<Term>>& terms() const { return terms_; }
  PetscInt global_size() const;
  double contact_stiffness() const { return contact_stiffness_; }
  // Adds a load term after construction (before the solver is made): one
  // with no linear parts and a zero tangent (e.g. PrescribedHeadForces), so
  // that the Jacobian's pattern and merged parts stay as they are. Returns it.
  Term& add_load_term(std::unique_ptr<Term> term);
  // True when no term is 'varying': J0 + low-rank changes is exact (cheap path).
  bool cheap_path_possible() const;

  Vec create_vector() const { return catenary_->create_vector(); }
  Mat create_matrix() const;  // the fixed pattern of the Jacobian (a copy)
  // The pattern of J0 on the cheap path: create_matrix() unless the catenary
  // model's reference tangents touch fewer entries (CatenaryModel).
  Mat create_reference_matrix() const;

  void residual(double t, Vec U, Vec V, Vec A, Vec F);
  // The residual after an exact Newton update on the cheap path, without the
  // linear parts' products. With F = F_lin + F_rest (F_lin: the linear parts,
  // F_rest: every term's add_residual) and J0 = L + T (L: the linear parts'
  // tangent, T: the terms' reference tangents), an update Y that solved
  // (J0 + D) Y = R exactly (D: the low-rank and block changes) moves the
  // linear parts by -L Y = -(R - T Y - D Y), so that
  //   R(X - Y) = F_rest(X - Y) - F_rest(X) + T Y + D Y   (to round-off).
  // enable_residual_update() makes residual() keep F_rest and
  // reference_jacobian() keep T; false when the system has no linear parts
  // (nothing to save). residual_update() sets F = F_rest(new) - F_rest(old) +
  // T Y (the caller adds D Y); false, F untouched, when F_rest(old) or T is
  // not at hand.
  bool enable_residual_update();
  bool residual_update(double t, Vec U, Vec V, Vec A, Vec Y, Vec F);
  // F is affine in A (term.hpp): MA = M A, M = dF/dA at the state (t, U, V),
  // a constant matrix with the pantographs' configuration-dependent masses.
  void inertia_product(double t, Vec U, Vec V, Vec A, Vec MA);
  // The exact tangent, assembled into J.
  void jacobian(double t, Vec U, Vec V, Vec A, Shifts shifts, Mat J);
  // Cheap path: J0 (every term's reference tangent), assembled; then the
  // terms' low-rank changes against it at the same or a later state, and,
  // if blocks is given, the 'block' terms' changes (shifts: J0's). The
  // latter returns false when a term asks for a new J0.
  void reference_jacobian(double t, Vec U, Vec V, Vec A, Shifts shifts, Mat J0);
  bool low_rank_change(double t, Vec U, Vec V, Vec A, std::vector<RankOne>& terms,
                       Shifts shifts = {}, std::vector<BlockChange>* blocks = nullptr);

  // Every term's Term::checkpoint(), in order; restore_terms() gives them
  // back (after the reference Jacobian has been rebuilt).
  std::vector<std::vector<double>> checkpoint_terms() const;
  void restore_terms(const std::vector<std::vector<double>>& states);

  // Sum of the terms' energies E(t, U, V) and powers (collective).
  double energy(double t, Vec U, Vec V);
  TermPower power(double t, Vec U, Vec V);
  // Measured quantities at state U (collective; filled on rank 0). Dropper
  // forces only if asked (a reduced catenary pays a product for them).
  // batched: a catenary that batches its records (batches_records) keeps the
  // state; take_records() hands the states kept so far over with their
  // computation (one product; it reads no state of the system, so it may run
  // on another thread), and finish_records() fills the support heights and
  // dropper forces of those records, in order, from its result (collective).
  contact::StepRecord record(double t, Vec U, bool batched = false);
  bool batches_records() const { return catenary_->batches_records(); }
  bool records_batch_pays() const { return catenary_->records_batch_pays(); }
  std::function<CatenaryModel::RecordQuantities()> take_records();
  void finish_records(std::vector<contact::StepRecord*>& records,
                      CatenaryModel::RecordQuantities quantities);
  void set_record_dropper_forces(bool on) { record_dropper_forces_ = on; }

 private:
  void sum_low_rank_values();  // Term::append_low_rank_sums over the ranks, one reduction
  struct MergedPart {
    Mat matrix;
    double cu, cv, ca;
    MatStructure structure;
  };
  void load(double t, Vec U, Vec V, Vec A);
  void form_part_arguments(Vec U, Vec V, Vec A);
  void set_linear_parts(Vec U, Vec V, Vec A, Vec F);
  void add_term_residuals(Vec F);  // every term's add_residual at the loaded state, assembled
  void assemble_tangent(Shifts shifts, Mat J, bool reference);
  Mat build_pattern(bool reference) const;

  std::unique_ptr<CatenaryModel> catenary_;
  std::vector<PantographSlot> pantographs_;
  CoupledState state_;
  std::vector<std::unique_ptr<Term>> terms_;
  std::vector<std::vector<PenaltyContact*>> contacts_;  // per pantograph, per wire (records)
  std::vector<MergedPart> parts_;
  std::vector<SubsetAxpy> part_axpy_;  // J += c A_k for the parts with a pattern of their own
  double contact_stiffness_;
  std::vector<bool> wire_coupled_;
  std::vector<Vec> part_arguments_;  // each part's cu (U - U_ref) + cv V + ca A
  Vec reference_ = nullptr, work_ = nullptr;
  // Residual update: F_rest at the last residual (rest_valid_) and a work
  // vector for the next; T of the last reference Jacobian.
  bool keep_rest_ = false, rest_valid_ = false;
  Vec rest_ = nullptr, rest_next_ = nullptr;
  Mat reference_rest_ = nullptr;
  // What load() loaded last (its vectors and their object states at the time).
  struct LoadStamp {
    bool valid = false;
    double t = 0;
    std::array<PetscObjectId, 3> ids{};  // 0: no vector
    std::array<PetscObjectState, 3> states{};
  };
  LoadStamp loaded_;
  bool record_dropper_forces_ = true;
};

}  // namespace pcsim::assembly
