// The reduced catenary's bounded dropper check and the dropper forces of its
// records (modal_catenary.hpp: which droppers are evaluated at each state).
//
// Anchors. An exact anchor is every tracked bar's elongation dl = s + B eta
// in double precision; a rounded one is dl_E + fl(B (eta - eta_E)) from the
// last exact anchor eta_E by B's rows in single or half precision, within
// g |b| |eta - eta_E| (rounded_rows.hpp: g ~ 2^-24 + n/8 2^-24 in single,
// 2^-11 more in half). The step's check takes the half rows (half the
// bytes). Records made one at a time (dropper_forces(): a run's where
// batches do not pay, modal_records.cpp; a stepper's) make one anchor per
// step: in single precision while that bound keeps every recorded force
// within kRecordForceError, else exact. The last two record (or exact) anchors are
// the line of the bounds
// of the next states (line_candidates), each with its error bound per unit
// |b| (the exact product's rounding gamma_n |eta_E| plus the single-precision
// part).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "pcsim/assembly/modal_catenary.hpp"

namespace pcsim::assembly {

namespace {

constexpr double kUnitDouble = 1.1102230246251565e-16;  // 2^-53
// [m] rounding bound of a half-precision update of the bounded check
// (margins ~1 mm): an exact anchor instead.
constexpr double kErrorReset = 1e-4;

}  // namespace

// Every tracked bar exactly at the loaded state: the new anchor, the base of
// the single-precision ones, and the newest point of the line.
void ModalCatenary::exact_anchor() const {
  slack_set_current_ = false;  // a new anchor: the next load evaluates again
  anchor_ = eta_;
  anchor_version_ = eta_version_;
  anchor_elongation_.noalias() = B_ * eta_;
  anchor_elongation_ += Eigen::Map<const Eigen::VectorXd>(stretch_.data(), B_.rows());
  anchor_error_.setZero(B_.rows());
  exact_eta_ = eta_;
  exact_norm_ = eta_.norm();
  exact_elongation_ = anchor_elongation_;
  ++exact_count_;
  evaluations_ += B_.rows();
  push_line_anchor(rounding_gamma(static_cast<double>(m_), kUnitDouble) * exact_norm_);
}

// The anchor just made (anchor_, anchor_elongation_), within 'bound' |b| of
// the exact elongations, becomes the line's newest point.
void ModalCatenary::push_line_anchor(double bound) const {
  line_valid_ = line_count_ > 0;
  if (line_valid_) {
    line_ = anchor_ - line_eta_;
    line_elongation_ = anchor_elongation_ - line_elongation_end_;
    line_norm2_ = line_.squaredNorm();
    line_valid_ = line_norm2_ > 0;
    line_bound_start_ = line_bound_end_;
  }
  line_eta_ = anchor_;
  line_elongation_end_ = anchor_elongation_;
  line_bound_end_ = bound;
  ++line_count_;
}

// The droppers not certainly taut at the loaded state, from the line through
// the last two anchors eta_p, eta_e: with d = eta_e - eta_p,
// eta = eta_e + tau d + r (tau minimising |r|), dl = dl_e + tau (dl_e - dl_p)
// + b . r, and |b . r| <= min(|b| |r|, |Omega^-1 b| |Omega r|). The states of
// a time step lie near the line of the last step (r is the change of the
// change), so this bound leaves a few candidates where the one from the
// anchor alone (the change itself) leaves most. The anchors' error bounds
// and the rounding of this arithmetic are added to the bound. False if more
// than 'few' candidates remain.
bool ModalCatenary::line_candidates(std::size_t few) {
  constexpr double u = kUnitDouble;
  ++line_tries_;
  work_ = eta_ - line_eta_;
  const double tau = work_.dot(line_) / line_norm2_;
  work_ -= tau * line_;  // r
  const double r = work_.norm(), r_omega = (work_.array() * omega_.array()).matrix().norm();
  const double line_norm = std::sqrt(line_norm2_);
  const double reach = line_bound_end_ * (1 + std::abs(tau)) + std::abs(tau) * line_bound_start_ +
                       4 * u * (r + 2 * std::abs(tau) * line_norm);
  candidates_.clear();
  for (long d = 0; d < B_.rows(); ++d) {
    const double predicted = line_elongation_end_[d] + tau * line_elongation_[d];
    const double rounding =
        bnorm_[d] * reach +
        4 * u * (std::abs(line_elongation_end_[d]) + std::abs(tau * line_elongation_[d]));
    if (predicted - rounding <= std::min(bnorm_[d] * r, bnorm_omega_[d] * r_omega))
      candidates_.push_back(d);
    if (candidates_.size() > few) return false;
  }
  return true;
}

// dl = dl_e + fl(B (eta - eta_e)) from the last exact anchor by the rows
// in half or single precision, within g |b| |eta - eta_e|
// (RoundedRows::error_factor): it follows the distance from eta_e and does
// not add up over the updates. False, with no product, if max_d scale_d
// times that bound would exceed 'reset' (scale_max: max_d scale_d |b_d|).
// *bound: the bound per unit |b| (if given).
bool ModalCatenary::rounded_anchor(double reset, double scale_max, const RoundedRows& rows,
                                   double* bound) const {
  const double g = rows.error_factor();
  work_ = eta_ - exact_eta_;
  const double distance = work_.norm();
  if (g * scale_max * distance > reset) return false;
  rows.multiply(work_, change_);
  for (long d = 0; d < B_.rows(); ++d) {
    anchor_elongation_[d] = exact_elongation_[d] + change_[d];
    anchor_error_[d] = g * bnorm_[d] * distance;
  }
  anchor_ = eta_;
  anchor_version_ = eta_version_;
  ++(&rows == &B_half_ ? half_products_ : single_products_);
  if (bound) *bound = g * distance;
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
      // No line without records of the dropper forces one at a time (a moving
      // window, records in batches): it would join the error resets' anchors,
      // steps apart, and leave no fewer candidates than the anchor alone
      // (window scene: same counts, same results; the DSA-380 at 136.1 Hz,
      // batched: the same products per step without it, and 7 % of the step's
      // time with it: docs/benchmarks.md, "No line of bounds for batched records").
      work_ = eta_ - anchor_;
      const double step = work_.norm();
      const double step_omega = (work_.array() * omega_.array()).matrix().norm();
      find_candidates(step, step_omega);
      if (candidates_.size() > kFewCandidates) {
        if (!rounded_anchor(kErrorReset, bnorm_max_, B_half_)) exact_anchor();
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

// The record's anchor at the loaded state: single precision while every
// recorded force stays within kRecordForceError of the exact one, else exact
// (the first record, after a restart too, is exact). It is the line's newest
// point either way.
void ModalCatenary::record_anchor() const {
  constexpr double kRecordForceError = 1.0;  // [N] bound on a recorded dropper force
  // Exact here already (a load's reset, or every dropper checked): on the line too.
  if (anchor_version_ == eta_version_ && anchor_error_.isZero(0)) return;
  double single_bound = 0;
  if (!rounded_anchor(kRecordForceError, force_scale_max_, B_single_, &single_bound)) {
    exact_anchor();
    return;
  }
  slack_set_current_ = false;
  push_line_anchor(rounding_gamma(static_cast<double>(m_), kUnitDouble) * exact_norm_ +
                   single_bound);
}

// The dropper forces at the loaded state from the record's anchor (forces:
// record_force, modal_records.cpp).
std::vector<double> ModalCatenary::dropper_forces() const {
  std::vector<double> forces(droppers_.size(), 0.0);
  record_anchor();  // every rank: the records' states anchor the bounded set
  records_anchor_ = true;
  if (!on_owner()) return forces;
  for (std::size_t i = 0; i < droppers_.size(); ++i) {
    const auto d = static_cast<std::size_t>(droppers_[i]);
    forces[i] = record_force(d, anchor_elongation_[static_cast<long>(d)]);
  }
  return forces;
}

}  // namespace pcsim::assembly
