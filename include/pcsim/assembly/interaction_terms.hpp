// Terms of the interaction: each pantograph (its model's equations of motion,
// thesis chapter 2, with the ramp-up force of 3.3.1) and the penalty contact
// between a pantograph and the contact wire (thesis 3.2, eqs. 3.9-3.13).
#pragma once

#include "pcsim/assembly/coupled_state.hpp"
#include "pcsim/assembly/term.hpp"

namespace pcsim::assembly {

// R_p = model residual (without contact) + (1 - ramp(t)) F0 e_c, on the last
// rank; dense tangent K + v C + a M of the model. A nonlinear model is a
// 'block' term on the cheap path: J0 holds its tangent at J0's state, and
// block_change() the difference of the current one (its own unknowns only),
// or the current one itself where the model gives it sparse (the flexible
// DSA-380: PantographModel::sparse_step_tangent).
class PantographTerm : public Term {
 public:
  explicit PantographTerm(std::size_t index, const PantographSlot& slot)
      : index_(index), slot_(slot) {}
  std::string name() const override { return "pantograph " + slot_.run.name; }
  TangentKind tangent_kind() const override {
    return slot_.model->is_linear() ? TangentKind::constant : TangentKind::block;
  }
  bool adds_by_set_values() const override { return true; }
  void add_residual(const CoupledState& state, Vec F) override;
  // The model's M q'' (a linear model's M is constant; the DSA-380's depends
  // on q, its residual stays affine in q'').
  AccelerationUse acceleration_use() const override {
    return slot_.model->is_linear() ? AccelerationUse::constant : AccelerationUse::varying;
  }
  void add_inertia(const CoupledState& state, Vec A, Vec F) const override;
  void add_tangent(const CoupledState& state, Shifts shifts, Mat J) override;
  void insert_pattern(Mat J) const override;
  void add_reference_tangent(const CoupledState& state, Shifts shifts, Mat J) override;
  void block_change(const CoupledState& state, Shifts shifts,
                    std::vector<BlockChange>& blocks) override;
  // T + V of the model - Q_ext . q (constant external forces as potentials)
  // + (1 - ramp) F0 q_c.
  double energy(const CoupledState& state) const override;
  TermPower power(const CoupledState& state) const override;

 private:
  // values = K + v C + a M at the loaded state, row-major (last rank), less
  // reference_ when 'change'.
  void block_tangent(const CoupledState& state, Shifts shifts, bool change,
                     std::vector<double>& values) const;

  std::size_t index_;
  const PantographSlot& slot_;
  std::vector<double> reference_;  // block_tangent() at J0's state (last rank)
  mutable Eigen::MatrixXd tangent_k_, tangent_c_, tangent_m_;  // block_tangent()'s, kept
  mutable Eigen::MatrixXd mass_;  // a linear model's M (last rank, at the first add_inertia)
  mutable Eigen::SparseMatrix<double> sparse_mass_;  // a model's sparse M (sparse_mass())
};

// Penalty contact of one pantograph with one contact wire at the moving point
// x_c = x_0 + v t (chi fixed within a step, as the thesis does): gap
// dz = z_wire - z_head (3.9), force Fc = kH max(-dz, 0) (3.10), residual
// -Fc dz/dU on the wire and +Fc on the head, tangent kH u u^T with
// u = [dz/dU; -1] in contact. On the cheap path J0 holds no contact: the
// whole tangent is the rank-one term (coefficient 0 out of contact). A line
// with several contact wires (overlaps) has one such term per pantograph and
// wire; the force on the head is their sum. A reduced catenary's residual
// flexibility r at x acts in series with the penalty spring: kH is replaced
// by kH / (1 + kH r) (r = 0 for FE).
class PenaltyContact : public Term {
 public:
  // wire: contact wire number (0..CatenaryModel::contact_wire_count()-1).
  PenaltyContact(std::size_t index, const PantographSlot& slot, double stiffness, int wire = 0)
      : index_(index), slot_(slot), kH_(stiffness), wire_(wire) {}
  std::string name() const override {
    return "penalty contact " + slot_.run.name +
           (wire_ > 0 ? " wire " + std::to_string(wire_) : "");
  }
  int wire() const { return wire_; }
  TangentKind tangent_kind() const override { return TangentKind::low_rank; }
  bool adds_by_set_values() const override { return true; }
  void add_residual(const CoupledState& state, Vec F) override;
  void add_tangent(const CoupledState& state, Shifts shifts, Mat J) override;
  void add_reference_tangent(const CoupledState&, Shifts, Mat) override {}
  bool low_rank_change(const CoupledState& state, std::vector<RankOne>& terms) override;
  // Whether the contact is closed (its owner rank's 1, summed).
  void append_low_rank_sums(const CoupledState& state, std::vector<double>& local) const override;
  void take_low_rank_sums(const double* sums) override;
  double energy(const CoupledState& state) const override;    // 1/2 kH dz^2 in contact
  TermPower power(const CoupledState& state) const override;  // the moving contact's work

  struct Evaluation {
    const WirePoint* wire = nullptr;  // at x_c: the model's (CatenaryModel::wire_point)
    double x = 0;                     // contact point along the track
    double head = 0;                  // head height
    double gap = 0;                   // dz (owner rank)
    double force = 0;                 // Fc >= 0 (owner rank)
    double stiffness = 0;             // kH in series with the wire's residual flexibility
  };
  // At the loaded state; gap and force only on the rank that owns the point.
  Evaluation evaluate(const CoupledState& state) const;

 private:
  std::size_t index_;
  const PantographSlot& slot_;
  double kH_;
  int wire_;
  std::vector<PetscInt> remote_index_;  // add_residual's entries of other ranks
  std::vector<double> remote_value_;
  SharedEntries<PetscInt> term_index_;  // the last u's indices (the wire's and the head's)
  bool term_index_contiguous_ = false;  // ... its wire part index[0], index[0] + 1, ...
  double summed_in_contact_ = 0;
};

}  // namespace pcsim::assembly
