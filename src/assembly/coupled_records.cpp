// CoupledSystem's records: the measured quantities of a state (record), and
// those that a reduced catenary computes for many states at once
// (take_records, finish_records).
#include <mpi.h>

#include <cmath>
#include <vector>

#include "pcsim/assembly/coupled_system.hpp"
#include "pcsim/assembly/interaction_terms.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/core/profiling.hpp"

namespace pcsim::assembly {

// The contact of every pantograph on every wire, then the support heights
// and dropper forces unless kept for a batch, summed over the ranks into one
// buffer on rank 0.
contact::StepRecord CoupledSystem::record(double t, Vec U, bool batched) {
  const ScopedEvent timed(log_events().record);
  load(t, U, nullptr, nullptr);
  const std::size_t np = pantographs_.size();
  const std::size_t nw = static_cast<std::size_t>(catenary_->contact_wire_count());
  batched = batched && catenary_->batches_records();
  if (batched) catenary_->keep_record_state();
  const auto supports = batched ? std::vector<double>() : catenary_->support_heights();
  const auto droppers =
      record_dropper_forces_ && !batched ? catenary_->dropper_forces() : std::vector<double>();
  constexpr std::size_t kPerWire = 4;  // Fc, z, on wire, y
  const std::size_t ns = supports.size(), nc = np * (1 + kPerWire * nw);
  // Reduction buffer: per pantograph [x, per wire (Fc, z, on wire, y)],
  // supports, droppers.
  std::vector<double> buffer(nc + ns + droppers.size(), 0.0);
  for (std::size_t p = 0; p < np; ++p) {
    double* b = &buffer[p * (1 + kPerWire * nw)];
    for (std::size_t w = 0; w < nw; ++w) {
      const auto e = contacts_[p][w]->evaluate(state_);
      if (state_.rank() == 0) b[0] = e.x;
      if (!e.wire->owned) continue;
      double* bw = b + 1 + kPerWire * w;
      bw[0] = e.force;
      bw[1] = e.wire->z;
      bw[2] = 1.0;
      bw[3] = e.wire->y;
    }
  }
  std::copy(supports.begin(), supports.end(), buffer.begin() + nc);
  std::copy(droppers.begin(), droppers.end(), buffer.begin() + nc + ns);
  MPI_Reduce(state_.rank() == 0 ? MPI_IN_PLACE : buffer.data(), buffer.data(),
             static_cast<int>(buffer.size()), MPI_DOUBLE, MPI_SUM, 0, comm());
  contact::StepRecord rec;
  rec.t = t;
  if (state_.rank() != 0) return rec;
  for (std::size_t p = 0; p < np; ++p) {
    const double* b = &buffer[p * (1 + kPerWire * nw)];
    double total = 0, z = 0, y = 0, pressed = 0, lowest = HUGE_VAL;
    rec.wire_force.emplace_back();
    for (std::size_t w = 0; w < nw; ++w) {
      const double* bw = b + 1 + kPerWire * w;
      const double f = bw[0], zw = bw[1];
      total += f;
      rec.wire_force.back().push_back(f);
      if (f > pressed) pressed = f, z = zw, y = bw[3];
      if (pressed == 0 && bw[2] > 0.5 && zw < lowest) lowest = zw, z = zw, y = bw[3];
    }
    rec.contact_force.push_back(total);
    rec.contact_x.push_back(b[0]);
    rec.wire_z.push_back(z);
    rec.wire_y.push_back(y);
    rec.head_z.push_back(state_.head_height(p));
    const Eigen::VectorXd q = state_.q(p);
    rec.q.emplace_back(q.data(), q.data() + q.size());
  }
  rec.support_z.assign(buffer.begin() + nc, buffer.begin() + nc + ns);
  rec.dropper_force.assign(buffer.begin() + nc + ns, buffer.end());
  return rec;
}

std::function<CatenaryModel::RecordQuantities()> CoupledSystem::take_records() {
  return catenary_->take_kept_records(record_dropper_forces_);
}

// The support heights and dropper forces of the records kept for a batch
// (record(t, U, true)), in the order they were recorded, from the batch's
// computation (collective: the ranks' parts summed on rank 0, which fills
// the records).
void CoupledSystem::finish_records(std::vector<contact::StepRecord*>& records,
                                   CatenaryModel::RecordQuantities q) {
  if (q.states != records.size())
    throw SolverError("records: " + std::to_string(records.size()) + " waiting for " +
                      std::to_string(q.states) + " kept states");
  const std::size_t ns = q.states ? q.support_z.size() / q.states : 0;
  const std::size_t nd = q.states ? q.dropper_force.size() / q.states : 0;
  std::vector<double> buffer(std::move(q.support_z));
  buffer.insert(buffer.end(), q.dropper_force.begin(), q.dropper_force.end());
  if (buffer.empty()) return;
  MPI_Reduce(state_.rank() == 0 ? MPI_IN_PLACE : buffer.data(), buffer.data(),
             static_cast<int>(buffer.size()), MPI_DOUBLE, MPI_SUM, 0, comm());
  if (state_.rank() != 0) return;
  const double* drop = buffer.data() + q.states * ns;
  for (std::size_t k = 0; k < q.states; ++k) {
    records[k]->support_z.assign(buffer.begin() + k * ns, buffer.begin() + (k + 1) * ns);
    records[k]->dropper_force.assign(drop + k * nd, drop + (k + 1) * nd);
  }
}

}  // namespace pcsim::assembly
