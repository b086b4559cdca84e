// The reduced catenary's bounded dropper check and the dropper forces of its
// records (modal_catenary.hpp: which droppers are evaluated at each state).
//
// Anchors. An exact anchor is every tracked bar's elongation dl = s + B eta
// in double precision; a rounded one is dl_E + fl(B (eta - eta_E)) from the
// last exact anchor eta_E by B's rows in single or half precision, within
// g |b| |eta - eta_E| (rounded_rows.hpp: g ~ 2^-24 + n/8 2^-24 in single,
// 2^-11 more in half). The step's check takes the half rows (half the
// bytes) from its base: the exact anchor, or a single-precision one that
// renews it while within kBaseError (block_anchor_kind). Records made one
// at a time (dropper_forces(): a run's where batches do not pay,
// modal_records.cpp; a stepper's) make one anchor per step: in single
// precision while that bound keeps every recorded force within
// kRecordForceError, else exact. The last two record (or exact) anchors
// are the line of the bounds of the next states (line_candidates), each
// with its error bound per unit |b| (the exact product's rounding gamma_n
// |eta_E| plus the single-precision part).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "pcsim/assembly/modal_catenary.hpp"

namespace pcsim::assembly {

namespace {

constexpr double kUnitDouble = 1.1102230246251565e-16;  // 2^-53
// [m] rounding bound of a half-precision update of the bounded check
// (margins ~1 mm): a new base instead.
constexpr double kErrorReset = 1e-4;
// [m] rounding bound of a single-precision base from the exact anchor (it
// takes half of kErrorReset, the half-precision updates from it the rest):
// an exact anchor instead.
constexpr double kBaseError = kErrorReset / 2;

}  // namespace

// B's rows by the basis's column blocks (modal_catenary.hpp); one block when
// the basis has none, or when a row is not zero outside its block (a basis
// ordered otherwise).
void ModalCatenary::build_row_blocks() {
  std::vector<long> starts = basis_->column_blocks;
  if (starts.size() < 2 || starts.front() != 0 || starts.back() != m_) starts = {0, m_};
  const long tracked = B_.rows();
  std::vector<long> block_of(static_cast<std::size_t>(tracked), 0);
  bool inside = true;
  for (long d = 0; d < tracked && starts.size() > 2; ++d) {
    const long g = first_nonzero_block(B_.row(d).data(), m_, starts);
    if (g < 0) continue;  // a zero row: block 0
    block_of[d] = g;
    for (long k = starts[g + 1]; k < m_ && inside; ++k) inside = B_(d, k) == 0;
  }
  if (!inside) {
    starts = {0, m_};
    std::fill(block_of.begin(), block_of.end(), 0L);
  }
  std::vector<bool> dropper(static_cast<std::size_t>(tracked), false);
  for (int d : droppers_) dropper[d] = true;
  bar_block_.assign(static_cast<std::size_t>(tracked), -1);
  row_blocks_.clear();
  single_bytes_ = 0;
  for (std::size_t g = 0; g + 1 < starts.size(); ++g) {
    RowBlock b;
    b.lo = starts[g];
    b.n = starts[g + 1] - starts[g];
    for (long d = 0; d < tracked; ++d)
      if (block_of[d] == static_cast<long>(g)) b.bars.push_back(d);
    if (b.bars.empty()) continue;
    b.rows.resize(static_cast<long>(b.bars.size()), b.n);
    for (std::size_t i = 0; i < b.bars.size(); ++i) {
      const long d = b.bars[i];
      b.rows.row(static_cast<long>(i)) = B_.row(d).segment(b.lo, b.n);
      b.bnorm_max = std::max(b.bnorm_max, bnorm_[d]);
      if (dropper[d]) b.force_scale_max = std::max(b.force_scale_max, bar_stiffness(d) * bnorm_[d]);
      bar_block_[d] = static_cast<int>(row_blocks_.size());
    }
    b.single = RoundedRows(b.rows, RoundedRows::Precision::single);
    b.half = RoundedRows(b.rows, RoundedRows::Precision::half);
    single_bytes_ += b.single.bytes();
    row_blocks_.push_back(std::move(b));
  }
}

// work_'s norm over each block's columns (and with the Omega weighting).
void ModalCatenary::block_norms(bool omega) const {
  block_step_.assign(row_blocks_.size(), 0.0);
  block_step_omega_.assign(row_blocks_.size(), 0.0);
  for (std::size_t g = 0; g < row_blocks_.size(); ++g) {
    const auto x = work_.segment(row_blocks_[g].lo, row_blocks_[g].n);
    block_step_[g] = x.norm();
    if (omega)
      block_step_omega_[g] =
          (x.array() * omega_.segment(row_blocks_[g].lo, row_blocks_[g].n).array()).matrix().norm();
  }
}

// Every tracked bar exactly at the loaded state: the new anchor, the base of
// the single-precision ones, and the newest point of the line. A block whose
// coordinates are all zero (a tension section the train has not reached)
// takes no product: its elongations are the static stretches.
void ModalCatenary::exact_anchor() const {
  slack_set_current_ = false;  // a new anchor: the next load evaluates again
  anchor_ = eta_;
  anchor_version_ = eta_version_;
  exact_eta_ = eta_;
  const long n = B_.rows();
  anchor_elongation_.resize(n);
  anchor_error_.resize(n);
  exact_elongation_.resize(n);
  base_eta_ = eta_;
  base_elongation_.resize(n);
  base_distance_.assign(row_blocks_.size(), 0.0);
  for (const RowBlock& b : row_blocks_) exact_block(b);
  exact_norm_ = eta_.norm();
  ++exact_count_;
  evaluations_ += n;
  push_line_anchor(rounding_gamma(static_cast<double>(m_), kUnitDouble) * exact_norm_);
}

// Block b's elongations exactly at the loaded state, its bars' new exact
// anchor, the check's base and the anchor (none computed where its
// coordinates are all zero: the static stretches).
void ModalCatenary::exact_block(const RowBlock& b) const {
  const auto x = eta_.segment(b.lo, b.n);
  const bool rest = x.isZero(0);
  if (!rest) block_out_.noalias() = b.rows * x;
  for (std::size_t i = 0; i < b.bars.size(); ++i) {
    const long d = b.bars[i];
    exact_elongation_[d] = rest ? stretch_[d] : stretch_[d] + block_out_[static_cast<long>(i)];
    anchor_elongation_[d] = exact_elongation_[d];
    base_elongation_[d] = exact_elongation_[d];
    anchor_error_[d] = 0;
  }
  exact_eta_.segment(b.lo, b.n) = x;
  base_eta_.segment(b.lo, b.n) = x;
  base_distance_[static_cast<std::size_t>(&b - row_blocks_.data())] = 0;
  anchor_.segment(b.lo, b.n) = x;
}

// Block b's elongations at the loaded state from a base (the exact anchor,
// or the check's base) by 'rows' (rounded), within error_factor |b_d|
// distance + base_error |b_d|, distance = |x| for x the change from the base
// over the block (no product where it is 0).
void ModalCatenary::rounded_block(const RowBlock& b, const RoundedRows& rows,
                                  const Eigen::VectorXd& base_eta,
                                  const Eigen::VectorXd& base_elongation, double distance,
                                  double base_error) const {
  if (distance > 0) {
    block_in_ = eta_.segment(b.lo, b.n) - base_eta.segment(b.lo, b.n);
    rows.multiply(block_in_, block_out_);
  }
  for (std::size_t i = 0; i < b.bars.size(); ++i) {
    const long d = b.bars[i];
    anchor_elongation_[d] =
        distance > 0 ? base_elongation[d] + block_out_[static_cast<long>(i)] : base_elongation[d];
    anchor_error_[d] = rows.error_factor() * bnorm_[d] * distance + base_error * bnorm_[d];
  }
  anchor_.segment(b.lo, b.n) = eta_.segment(b.lo, b.n);
}

// Block g's next anchor for the check: half precision from its base while
// that bound, with the base's own, stays within kErrorReset; else a new base
// in single precision from the exact anchor while its bound stays within
// kBaseError; else exact. to_base, to_exact: the block's distances.
ModalCatenary::BlockAnchor ModalCatenary::block_anchor_kind(std::size_t g, double* to_base,
                                                            double* to_exact) const {
  const RowBlock& b = row_blocks_[g];
  *to_base = (eta_.segment(b.lo, b.n) - base_eta_.segment(b.lo, b.n)).norm();
  *to_exact = 0;
  if (b.half.error_factor() * b.bnorm_max * *to_base +
          b.single.error_factor() * b.bnorm_max * base_distance_[g] <=
      kErrorReset)
    return BlockAnchor::half;
  *to_exact = (eta_.segment(b.lo, b.n) - exact_eta_.segment(b.lo, b.n)).norm();
  if (b.single.error_factor() * b.bnorm_max * *to_exact <= kBaseError) return BlockAnchor::single;
  return BlockAnchor::exact;
}

// Block g's anchor of that kind (block_anchor_kind), counted.
void ModalCatenary::make_block_anchor(std::size_t g, BlockAnchor kind, double to_base,
                                      double to_exact) const {
  const RowBlock& b = row_blocks_[g];
  switch (kind) {
    case BlockAnchor::half:
      rounded_block(b, b.half, base_eta_, base_elongation_, to_base,
                    b.single.error_factor() * base_distance_[g]);
      return;
    case BlockAnchor::single:  // the block's new base
      rounded_block(b, b.single, exact_eta_, exact_elongation_, to_exact);
      base_eta_.segment(b.lo, b.n) = eta_.segment(b.lo, b.n);
      for (long d : b.bars) base_elongation_[d] = anchor_elongation_[d];
      base_distance_[g] = to_exact;
      ++single_products_;
      return;
    case BlockAnchor::exact:
      exact_block(b);
      ++exact_count_;
      evaluations_ += static_cast<long>(b.bars.size());
      return;
  }
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

// The records' anchor: dl = dl_e + fl(B (eta - eta_e)) from the last exact
// anchor by the rows in single precision, within g |b| |x|
// (RoundedRows::error_factor), x the change over the bar's block: it follows
// the distance from eta_e and does not add up over the updates; a block with
// no change takes no product. False, with no product, if in a block max_d
// k_d |b_d| times that bound would exceed 'reset' (a recorded force's bound).
// *bound: the bound per unit |b|, the largest block's.
bool ModalCatenary::single_anchor(double reset, double* bound) const {
  work_ = eta_ - exact_eta_;
  block_norms(false);
  for (std::size_t g = 0; g < row_blocks_.size(); ++g) {
    const RowBlock& b = row_blocks_[g];
    if (b.single.error_factor() * b.force_scale_max * block_step_[g] > reset) return false;
  }
  double largest = 0;
  for (std::size_t g = 0; g < row_blocks_.size(); ++g) {
    rounded_block(row_blocks_[g], row_blocks_[g].single, exact_eta_, exact_elongation_,
                  block_step_[g]);
    largest = std::max(largest, row_blocks_[g].single.error_factor() * block_step_[g]);
  }
  anchor_ = eta_;
  anchor_version_ = eta_version_;
  ++single_products_;
  *bound = largest;
  return true;
}

// The check's new anchor at the loaded state, block by block
// (block_anchor_kind): only the blocks over the bounds take a new base or
// the double rows (a tension section the train has passed, vibrating
// freely, moves away from its base at its own pace). All exact:
// exact_anchor(), the line's newest point too.
void ModalCatenary::check_anchor() {
  const std::size_t blocks = row_blocks_.size();
  block_kind_.resize(blocks);
  block_to_base_.resize(blocks);
  block_to_exact_.resize(blocks);
  std::size_t exact = 0, half = 0;
  for (std::size_t g = 0; g < blocks; ++g) {
    block_kind_[g] = block_anchor_kind(g, &block_to_base_[g], &block_to_exact_[g]);
    exact += block_kind_[g] == BlockAnchor::exact ? 1 : 0;
    half += block_kind_[g] == BlockAnchor::half ? 1 : 0;
  }
  if (exact == blocks) {
    exact_anchor();
    return;
  }
  for (std::size_t g = 0; g < blocks; ++g)
    make_block_anchor(g, block_kind_[g], block_to_base_[g], block_to_exact_[g]);
  if (exact > 0) exact_norm_ = exact_eta_.norm();
  anchor_ = eta_;
  anchor_version_ = eta_version_;
  if (half > 0) ++half_products_;
}

// The droppers not certainly taut at the loaded state: a bar's bound takes
// the change over its block only (work_: eta - eta_a).
void ModalCatenary::find_candidates(bool at_anchor) {
  candidates_.clear();
  if (!at_anchor) block_norms(true);
  for (long d = 0; d < B_.rows(); ++d) {
    const double step = at_anchor ? 0.0 : block_step_[bar_block_[d]];
    const double step_omega = at_anchor ? 0.0 : block_step_omega_[bar_block_[d]];
    if (anchor_elongation_[d] - anchor_error_[d] <=
        std::min(bnorm_[d] * step, bnorm_omega_[d] * step_omega))
      candidates_.push_back(d);
  }
}

// Blocks apart (a basis of several column blocks, records in batches: no
// line of bounds): only the blocks with more than 'few' candidates take a
// new anchor, each from the last exact one in half precision (exact where
// its rounding bound would exceed kErrorReset), the others keep theirs (a
// tension section the train has passed changes little, one not reached not
// at all); the candidates sought again. False, with nothing changed, where
// every block would take one: the whole anchor, as with one block.
bool ModalCatenary::refresh_blocks(std::size_t few) {
  if (records_anchor_ || row_blocks_.size() < 2) return false;
  auto& count = block_candidates_;
  count.assign(row_blocks_.size(), 0);
  for (long d : candidates_) ++count[bar_block_[d]];
  std::size_t refreshed = 0;
  for (std::size_t c : count) refreshed += c > few ? 1 : 0;
  if (refreshed == row_blocks_.size()) return false;
  if (refreshed == 0) return true;  // a few in each: evaluated exactly
  for (std::size_t g = 0; g < row_blocks_.size(); ++g) {
    if (count[g] <= few) continue;
    double to_base = 0, to_exact = 0;
    const BlockAnchor kind = block_anchor_kind(g, &to_base, &to_exact);
    make_block_anchor(g, kind, to_base, to_exact);
    if (kind == BlockAnchor::exact) exact_norm_ = exact_eta_.norm();
    if (kind == BlockAnchor::half) ++half_products_;
  }
  work_ = eta_ - anchor_;
  find_candidates(false);
  return true;
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
      find_candidates(true);
    } else if (!records_anchor_ || !line_valid_ || !line_candidates(kFewCandidates)) {
      // No line without records of the dropper forces one at a time (a moving
      // window, records in batches): it would join the error resets' anchors,
      // steps apart, and leave no fewer candidates than the anchor alone
      // (window scene: same counts, same results; the DSA-380 at 136.1 Hz,
      // batched: the same products per step without it, and 7 % of the step's
      // time with it: docs/benchmarks.md, "No line of bounds for batched records").
      work_ = eta_ - anchor_;
      find_candidates(false);
      if (candidates_.size() > kFewCandidates && !refresh_blocks(kFewCandidates)) {
        check_anchor();
        find_candidates(true);
        at_anchor = true;
      }
    }
  }
  for (long d : candidates_) {
    double& dl = elongation_[d];
    if (at_anchor && anchor_error_[d] == 0) {
      dl = anchor_elongation_[d];
    } else {
      const RowBlock& b = row_blocks_[bar_block_[d]];
      dl = stretch_[d] + B_.row(d).segment(b.lo, b.n).dot(eta_.segment(b.lo, b.n));
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
  if (!single_anchor(kRecordForceError, &single_bound)) {
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
