// The reduced-order catenary: the catenary linearised about its static
// configuration and projected on a reduced basis (catenary/reduced_basis.hpp),
//   U = U0 + Phi eta,  eta'' + (alpha + beta Omega^2) eta' + Omega^2 eta + corrections = f,
// as a CatenaryModel. Its unknowns eta all live on the last rank (with the
// pantographs'); load_state() gives them to every rank, so the model runs on
// any number of ranks (it is meant for one: real time).
//
// Terms (assembly/modal_terms.hpp): Omega^2 and I as linear parts (modal
// stiffness, inertia, Rayleigh damping alpha I + beta Omega^2), the dropper
// slack correction -k min(dl, 0) b_d (dl = s_d + b_d . eta, rank one per
// slack dropper) or every bar's exact nonlinear force minus its
// linearisation (settings.bars = exact: the all-modes check against FE), and
// the contact through wire_point(x, wire): z(x) = z0(x) + S_z(chi) Phi_e eta, a
// dense row over the modes of the element's column block (a line's tension
// sections: ReducedBasis::column_blocks), with the truncated flexibility of
// the contact point (every contact wire of a line with overlaps).
//
// Which droppers are evaluated at each state (dropper_check = bounded): the
// elongations dl_a of every dropper are known at an anchor state eta_a to
// within err_a (0 after an exact evaluation). At a state eta a dropper with
//   dl_a - err_a > min(|b| |eta - eta_a|, |Omega^-1 b| |Omega (eta - eta_a)|)
// (Cauchy-Schwarz with either weighting) is certainly taut; records made one
// at a time (dropper_forces()) anchor each recorded state and give a tighter
// bound from the line through the last two (modal_slack_set.cpp). If that
// leaves more than a few candidates (measured: the Cauchy-Schwarz bounds are ~1e3 times the
// true change of a step, the modes being global), every dl is updated by one
// single-precision product B (eta - eta_E) from the last exact anchor with
// its rounding bound (n + 2) u |b| |eta - eta_E| (u = 2^-24) and eta becomes
// the anchor; the droppers still not certainly taut are evaluated exactly.
// No accuracy is lost: the correction of a taut dropper is exactly 0. With
// dropper_check = all every dropper is evaluated exactly at every state.
// Where records one at a time do not pay, a run's records come in batches
// instead (keep_record_state, take_kept_records: modal_records.cpp).
#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <utility>
#include <vector>

#include "pcsim/assembly/catenary_model.hpp"
#include "pcsim/assembly/rounded_rows.hpp"
#include "pcsim/catenary/elements.hpp"
#include "pcsim/catenary/reduced_basis.hpp"
#include "pcsim/contact/wire_locator.hpp"

namespace pcsim::assembly {

class ModalCatenary : public CatenaryModel {
 public:
  using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

  ModalCatenary(MPI_Comm comm, catenary::CatenaryMesh mesh, std::vector<double> static_node_values,
                std::shared_ptr<const catenary::ReducedBasis> basis,
                const catenary::ModalSettings& settings, PetscInt extra_dofs);
  ~ModalCatenary() override;

  MPI_Comm comm() const override { return comm_; }
  const catenary::CatenaryMesh& mesh() const override { return mesh_; }
  catenary::CatenaryFidelity fidelity() const override { return catenary::CatenaryFidelity::modal; }
  PetscInt catenary_dofs() const override { return m_; }
  PetscInt extra_global(PetscInt k) const override { return m_ + k; }
  Vec create_vector() const override;
  Mat create_matrix(const std::vector<bool>& wire_coupled) const override;
  bool has_reference_pattern() const override { return true; }
  Mat create_reference_matrix(const std::vector<bool>& wire_coupled) const override;
  void reference_state(Vec U) const override;
  void load_state(Vec U) override;
  int contact_wire_count() const override { return static_cast<int>(locators_.size()); }
  const WirePoint& wire_point(double x, int wire) const override;
  double wire_slope(double x, int wire) const override;
  double wire_x_min(int wire) const override { return locators_[wire]->x_min(); }
  double wire_x_max(int wire) const override { return locators_[wire]->x_max(); }
  bool closed_form_point_loads(const std::vector<PointForce>& loads, Vec U) const override;
  std::vector<double> support_heights() const override;
  std::vector<double> dropper_forces() const override;
  bool batches_records() const override { return true; }
  bool records_batch_pays() const override;
  void keep_record_state() override;
  std::function<RecordQuantities()> take_kept_records(bool dropper_forces) override;
  std::vector<double> node_positions_to_root(Vec U) const override;
  std::vector<std::unique_ptr<Term>> make_terms(const contact::InteractionEffects& e,
                                                Mat pattern) override;

  // For the terms.
  const catenary::ReducedBasis& basis() const { return *basis_; }
  // A moving window's pins are switched between steps (catenary::NodePin::active).
  catenary::CatenaryMesh& mutable_mesh() { return mesh_; }
  const catenary::ModalSettings& settings() const { return settings_; }
  bool on_owner() const { return rank_ == size_ - 1; }
  const Eigen::VectorXd& eta() const { return eta_; }  // at the loaded state, every rank
  double static_value(int node, int c) const { return static_values_[6 * node + c]; }
  // Rows of the basis for (node, component) (a kept row).
  Eigen::Map<const Eigen::RowVectorXd> row(int node, int c) const;
  Eigen::Map<const Eigen::RowVectorXd> key_row(long key) const;  // any kept row
  // Mesh bar b's ends' static positions (q0 of catenary::bar_internal_force).
  catenary::Vec6 static_bar_dofs(int b) const;
  // The row giving direction . (u_j - u_i) of mesh bar b (ends i, j) over the basis.
  Eigen::RowVectorXd relative_row(int b, const Eigen::Vector3d& direction) const;
  // Slack-capable bars: elongation gradients b_d over the basis (rows),
  // static stretch s_d (dl = s_d + b_d . eta) and stiffness.
  const RowMatrix& elongation_rows() const { return B_; }
  const std::vector<int>& slack_bars() const { return slack_bars_; }  // tracked bars
  double stretch(std::size_t d) const { return stretch_[d]; }
  double bar_stiffness(std::size_t d) const { return mesh_.bars[slack_bars_[d]].stiffness; }
  // The slack bars at the loaded state (indices into slack_bars()) and
  // their elongations dl < 0.
  const std::vector<std::size_t>& slack_now() const { return slack_now_; }
  double elongation(std::size_t d) const { return elongation_[d]; }
  // Bars evaluated exactly so far, single- and half-precision updates of
  // all of them and states loaded (bounded set statistics).
  long dropper_evaluations() const { return evaluations_; }
  long single_precision_updates() const { return single_products_; }
  long half_precision_updates() const { return half_products_; }
  // States whose candidates were sought on the line of the bounds (modal_slack_set.cpp).
  long line_tries() const { return line_tries_; }
  long exact_anchors() const { return exact_count_; }
  long loads() const { return loads_; }

 private:
  void build_dropper_rows();
  void update_slack_set();
  Mat allocate_matrix(const std::vector<bool>& wire_coupled, bool dense) const;

  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  catenary::CatenaryMesh mesh_;
  std::vector<double> static_values_;
  // Shared with the process's kept bases (simulation/setup_memory.hpp): immutable.
  std::shared_ptr<const catenary::ReducedBasis> basis_;
  catenary::ModalSettings settings_;
  PetscInt m_ = 0, extra_ = 0;
  std::vector<std::unique_ptr<contact::ContactWireLocator>> locators_;  // per contact wire
  std::vector<long> row_index_;     // basis_row_key -> row, -1 if not kept (dense over keys)
  std::vector<int> droppers_;       // the droppers (records), as indices into slack_bars_
  std::vector<int> slack_bars_;     // bars tracked over the basis
  std::vector<int> wire_position_;  // node -> position in contact_wire_nodes(), -1
  // Per contact-wire node, the columns its z and z' rows span (lo, hi) in
  // the basis's column blocks: a contact point's weights cover its
  // element's only. Empty with one block.
  std::vector<std::pair<long, long>> wire_node_columns_;
  // The block (index into starts) of a basis-long row's first nonzero; -1 for a zero row.
  static long first_nonzero_block(const double* row, long m, const std::vector<long>& starts);
  void find_wire_node_columns(const std::vector<int>& wire_nodes);
  std::pair<long, long> element_columns(int node0, int node1) const;
  bool slack_active_ = false;                          // the slack correction is a term
  bool dropper_slack_ = true;                          // the scene's effect (make_terms)
  std::vector<double> stretch_, bnorm_, bnorm_omega_;  // s_d, |b_d|, |Omega^-1 b_d|
  RowMatrix B_;
  RowMatrix support_rows_;  // the contact-wire height rows of the supports
  Eigen::VectorXd omega_;
  // Loaded state and the bounded set's bookkeeping (the records make exact
  // anchors too, hence mutable).
  // B by the basis's column blocks (ReducedBasis::column_blocks: a line's
  // tension sections): a bar's row is zero outside its block, so each block's
  // bars take their rows over the block's columns only, and a block whose
  // coordinates have not changed takes none. Its rows in double, and rounded
  // (rounded_rows.hpp) in single precision for the records' anchors (their
  // 1 N bound), in half precision for the step's check.
  struct RowBlock {
    long lo = 0, n = 0;      // columns lo .. lo + n - 1
    std::vector<long> bars;  // tracked bars (indices d), ascending
    RowMatrix rows;          // bars x n
    RoundedRows single, half;
    double bnorm_max = 0, force_scale_max = 0;  // max |b_d|, max over droppers k_d |b_d|
  };
  std::vector<RowBlock> row_blocks_;
  std::vector<int> bar_block_;  // tracked bar -> its block
  std::size_t single_bytes_ = 0;
  mutable std::vector<double> block_step_, block_step_omega_;  // per block: |dx|, |Omega dx|
  mutable Eigen::VectorXd block_in_, block_out_;
  void build_row_blocks();
  // work_'s norms per block (find_candidates) into block_step_, block_step_omega_.
  void block_norms(bool omega) const;
  Eigen::VectorXd eta_, incoming_;
  mutable Eigen::VectorXd work_;
  long eta_version_ = 0;                    // counts the changes of eta_
  mutable long anchor_version_ = -1;        // the eta_version_ of the anchor
  mutable bool slack_set_current_ = false;  // slack_now_ is that of eta_ and the anchor
  mutable Eigen::VectorXd anchor_, anchor_elongation_, anchor_error_;
  // The last exact anchor (eta_E, dl_E, |eta_E|): the base of the
  // single-precision ones (modal_slack_set.cpp).
  mutable Eigen::VectorXd exact_eta_, exact_elongation_;
  mutable double exact_norm_ = 0;
  // The base of the check's half-precision anchors, per block: the exact
  // anchor, or a single-precision one from it (eta_S, dl_S) within g_s |b|
  // base_distance_ (|eta_S - eta_E| over the block; 0 where exact).
  mutable Eigen::VectorXd base_eta_, base_elongation_;
  mutable std::vector<double> base_distance_;
  mutable long exact_count_ = 0;
  // The line of the bounds through the last two record or exact anchors:
  // its newest point (eta_e, dl_e), line_ = eta_e - eta_p, line_elongation_ =
  // dl_e - dl_p, |line_|^2, and each point's error bound per unit |b|.
  mutable Eigen::VectorXd line_eta_, line_elongation_end_, line_, line_elongation_;
  mutable double line_norm2_ = 0, line_bound_end_ = 0, line_bound_start_ = 0;
  mutable long line_count_ = 0;
  mutable bool line_valid_ = false;
  // dropper_forces() anchors each recorded state; a record kept for a batch
  // (keep_record_state) does not, and the line is left unused.
  mutable bool records_anchor_ = false;
  std::vector<double> elongation_;
  std::vector<std::size_t> slack_now_;
  std::vector<long> candidates_;
  mutable long evaluations_ = 0, single_products_ = 0, half_products_ = 0;
  long line_tries_ = 0;
  long loads_ = 0;
  // The records' states kept for one product (modal_records.cpp), a column each.
  Eigen::MatrixXd kept_states_;
  std::shared_ptr<Eigen::MatrixXd> job_states_;  // the last batch's, its job's (take_kept_records)
  long kept_ = 0;
  // The recorded axial force of tracked bar d at elongation dl.
  double record_force(std::size_t d, double dl) const;
  void exact_anchor() const;
  void push_line_anchor(double bound) const;
  void record_anchor() const;
  bool single_anchor(double reset, double* bound) const;
  // The step's check's new anchor: each block's in half precision, exact
  // where its rounding bound would exceed the reset (modal_slack_set.cpp).
  void check_anchor();
  // The droppers not certainly taut at the loaded state, work_ = eta - the
  // anchor (at_anchor: eta is the anchor).
  void find_candidates(bool at_anchor);
  bool refresh_blocks(std::size_t few);
  void exact_block(const RowBlock& b) const;
  // Block b's anchor from (base_eta, base_elongation) by 'rows', within
  // error_factor |b_d| distance + base_error |b_d|.
  void rounded_block(const RowBlock& b, const RoundedRows& rows, const Eigen::VectorXd& base_eta,
                     const Eigen::VectorXd& base_elongation, double distance,
                     double base_error = 0) const;
  // The check's next anchor of block g: half precision from its base, a new
  // base in single precision from the exact anchor, or exact.
  enum class BlockAnchor { half, single, exact };
  BlockAnchor block_anchor_kind(std::size_t g, double* to_base, double* to_exact) const;
  void make_block_anchor(std::size_t g, BlockAnchor kind, double to_base, double to_exact) const;
  // check_anchor's per block: kinds and distances (kept: no fresh memory in a step)
  std::vector<BlockAnchor> block_kind_;
  std::vector<double> block_to_base_, block_to_exact_;
  std::vector<std::size_t> block_candidates_;  // refresh_blocks: candidates per block
  bool line_candidates(std::size_t few);
  // Wire-point weights of the last few x of each contact wire (they depend
  // on x only): the point, its static height and the slope's parts. Several
  // per wire, so that pantographs on one wire do not evict each other.
  struct CachedPoint {
    double x = -1e300;
    WirePoint point;
    double z0 = 0, x_chi = 1;  // static height, dx/dchi
    double y0 = 0;             // static lateral position (point.y)
    Eigen::RowVectorXd y_eta;  // dy/d eta (empty: the basis keeps no lateral rows)
    int element = -1;          // the contact wire's cable element at x ...
    double chi = 0;            // ... and the point's coordinate on it
    Eigen::RowVectorXd z_chi;  // d(dz/dchi)/d eta, made by wire_slope() alone
    bool z_chi_made = false;   // z_chi is this x's (its storage kept from x to x)
    double z_chi0 = 0;         // static dz/dchi
    long eta_version = -1;     // point.z and point.y belong to this eta_version_
    long last_use = 0;         // for replacing the least recently used
  };
  static constexpr std::size_t kCachedPointsPerWire = 8;
  mutable std::vector<std::array<CachedPoint, kCachedPointsPerWire>> cached_;
  mutable long point_uses_ = 0;
  CachedPoint& cached_point(double x, int wire) const;
};

}  // namespace pcsim::assembly
