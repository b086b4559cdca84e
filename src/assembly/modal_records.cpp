// The reduced catenary's records in batches: the support heights and dropper
// forces of many recorded states in one product. A record of one state costs
// a matrix-vector product over the whole basis (tracked bars x modes: 180 x
// 8014 on two-pantographs-300 at 108.8 Hz), bound by the memory traffic of
// the matrix; the same product for 32 states at once is a matrix-matrix
// product that reads the matrix once (runs/bench/record_product_rate.cpp:
// ~5 times less time per state), exact in double precision.
#include <unistd.h>

#include <algorithm>
#include <memory>

#include "pcsim/assembly/modal_catenary.hpp"
#include "pcsim/core/dense_gemm.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::assembly {

namespace {

constexpr long kKeptStatesGrowth = 32;  // columns added when the kept states are full

// C (rows x states, column-major, leading dimension rows) = A S, A a
// row-major rows x n matrix, S rows lo .. lo + n - 1 of the first 'states'
// columns of a column-major matrix, by the system's BLAS (dense_gemm; BLIS:
// runs/bench_blas.sh).
void product(const ModalCatenary::RowMatrix& a, const Eigen::MatrixXd& s, long lo, long states,
             std::vector<double>& c) {
  c.assign(static_cast<std::size_t>(a.rows() * states), 0.0);
  if (a.rows() == 0 || states == 0 || a.cols() == 0) return;
  // A row-major is A^T column-major (m x rows).
  dense_gemm(true, false, a.rows(), states, a.cols(), 1.0, a.data(), a.cols(), s.data() + lo,
             s.rows(), 0.0, c.data(), a.rows());
}

}  // namespace

// N = N_eq + k (dl - s) (linear bars), k max(dl, 0) (force), N_eq + k
// max(dl - s, 0) (length); dl = s + b.eta, b the elongation's gradient at the
// static state.
double ModalCatenary::record_force(std::size_t d, double dl) const {
  const auto& bar = mesh_.bars[slack_bars_[d]];
  const double stretch = dl - stretch_[d];
  if (dropper_slack_ && bar.slack == catenary::SlackCriterion::force)
    return bar.stiffness * std::max(dl, 0.0);
  if (dropper_slack_ && bar.slack == catenary::SlackCriterion::length)
    return bar.equilibrium_force + bar.stiffness * std::max(stretch, 0.0);
  return bar.equilibrium_force + bar.stiffness * stretch;  // else every bar taut
}

// Records one at a time cost a single-precision product of the tracked
// bars' rows (B in float) per step, and anchor the next step's bounded check
// (modal_slack_set.cpp) at no extra cost; batched, the step makes its own
// product in half precision (0.97 per step on EN 50318: half the float
// rows' bytes) and the batch adds its share. Measured (docs/benchmarks.md,
// "Rounded rows"): batches pay once the float rows exceed half a core's
// level-2 cache (the DSA-380 at 136.1 Hz: 90 x 4804 floats, 1.7 MB, a real-
// time factor 9 % higher), and not below (EN 50318: 90 x 2736, 1.0 MB, the
// same either way). Each node's own cache decides; the ranks agree (a batch's
// records are collective), batching only where every rank's pays.
bool ModalCatenary::records_batch_pays() const {
  long cache = sysconf(_SC_LEVEL2_CACHE_SIZE);
  if (cache <= 0) cache = 1L << 21;  // not known: 2 MiB
  int pays = static_cast<long>(single_bytes_) > cache / 2 ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &pays, 1, MPI_INT, MPI_MIN, comm_);
  return pays != 0;
}

// Every rank counts the kept states; the owner keeps them.
void ModalCatenary::keep_record_state() {
  records_anchor_ = false;  // a kept state anchors no check (modal_slack_set.cpp)
  if (on_owner()) {
    if (kept_ == kept_states_.cols())
      kept_states_.conservativeResize(m_, kept_ + kKeptStatesGrowth);
    kept_states_.col(kept_) = eta_;
  }
  ++kept_;
}

// The kept states leave with the job (their columns, the count): the next
// keep_record_state() starts a new batch while the job may still run, in the
// storage of the job before once that job is done with it (none is allocated
// per batch). The job reads B, the support rows, the static values and the
// bars, which a run does not change.
std::function<CatenaryModel::RecordQuantities()> ModalCatenary::take_kept_records(
    bool with_droppers) {
  auto states = job_states_ && job_states_.use_count() == 1 ? job_states_
                                                            : std::make_shared<Eigen::MatrixXd>();
  states->swap(kept_states_);
  job_states_ = states;
  const long count = kept_;
  kept_ = 0;
  const bool owner = on_owner();
  return [this, states, count, with_droppers, owner] {
    RecordQuantities q;
    q.states = static_cast<std::size_t>(count);
    const std::size_t ns = mesh_.support_nodes.size(), nd = with_droppers ? droppers_.size() : 0;
    q.support_z.assign(q.states * ns, 0.0);
    q.dropper_force.assign(q.states * nd, 0.0);
    if (!owner) return q;
    product(support_rows_, *states, 0, count, q.support_z);
    for (std::size_t k = 0; k < q.states; ++k)
      for (std::size_t s = 0; s < ns; ++s)
        q.support_z[k * ns + s] += static_values_[6 * mesh_.support_nodes[s] + 2];
    if (nd == 0) return q;
    const auto tracked = static_cast<std::size_t>(B_.rows());
    std::vector<double> elongation(tracked * q.states), change;
    for (const RowBlock& b : row_blocks_) {  // B eta by blocks: tracked bars x states
      product(b.rows, *states, b.lo, count, change);
      const std::size_t nb = b.bars.size();
      for (std::size_t k = 0; k < q.states; ++k)
        for (std::size_t i = 0; i < nb; ++i)
          elongation[k * tracked + b.bars[i]] = stretch_[b.bars[i]] + change[k * nb + i];
    }
    for (std::size_t k = 0; k < q.states; ++k)
      for (std::size_t i = 0; i < nd; ++i) {
        const auto d = static_cast<std::size_t>(droppers_[i]);
        q.dropper_force[k * nd + i] = record_force(d, elongation[k * tracked + d]);
      }
    return q;
  };
}

}  // namespace pcsim::assembly
