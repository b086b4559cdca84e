// The distribution of the time steps' wall times, for hardware-in-the-loop
// use (a step must finish within its real-time slot): percentiles, the first
// step apart (it factors J0 and warms the caches), and the slowest steps with
// what happened in them. A step's time runs from the end of the previous
// step's output to the start of its own: the TS step (Newton, assembly,
// solves) and what follows it before the record (a moving window's shift, the
// stop-signal check); the record and the output flush are timed apart.
// Rank 0's clock (each rank runs the same steps).
#pragma once

#include <array>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "pcsim/simulation/step_scheduling.hpp"

namespace pcsim::simulation {

// What a step did besides its plain Newton iteration.
struct StepEvents {
  long newton_iterations = 0;
  long reference_builds = 0;          // J0 assembled and factored (cheap path)
  long involuntary_switches = 0;      // the OS took the stepping thread's core away (getrusage)
  long page_faults = 0;               // memory touched for the first time (getrusage)
  bool window_shift = false;          // a moving window moved
  bool output_flush_before = false;   // the previous record flushed results.h5
  bool records_batch_beside = false;  // a records' batch was computing on its own thread
  // Cheap path: the set of rank-one terms changed (a contact opened or closed,
  // a dropper went slack or taut), the Woodbury capacitance's rows formed in
  // the step, and the terms active at its end.
  long rank_one_set_changes = 0;
  long capacitance_rows = 0;
  long rank_one_terms = 0;
  // Reduced catenary: its bounded dropper check took every tracked dropper's
  // elongation in double precision (an exact anchor: each row read whole).
  long exact_dropper_anchors = 0;
  // The CPU the stepping thread ended the step on (sched_getcpu; -1 not
  // known): on a virtual machine two CPUs can run at different speeds
  // (docs/benchmarks.md, "The machine's two CPUs at different speeds").
  int cpu = -1;
};

class StepTiming {
 public:
  // A step's wall time [s] and events.
  void add(long step, double seconds, const StepEvents& events);
  // The record and output of a step [s] (not in the step's time).
  void add_output(double seconds);
  // {steps, first_step_ms, median_ms, p99_ms, p99_9_ms, p99_99_ms, max_ms,
  //  max_without_context_switch_ms, steps_with_context_switch, output_max_ms,
  //  output_mean_ms, slowest: [{step, ms, causes}], by_cause: {cause: {steps,
  //  mean_ms}}, by_cpu: {cpu: {steps, mean_ms}}, scheduling:
  //  StepScheduling::json()}; percentiles over the
  //  steps after the first (nearest rank).
  //  by_cause counts a step under each of its causes (kCauseKeys), "none"
  //  for a step without one: what the run's mean step time is made of.
  nlohmann::json json() const;
  // One console line: the percentiles and the slowest steps' causes.
  std::string summary_line() const;
  // The stepping thread's scheduling, read where the timing is made (the
  // run's session, on the thread that steps).
  const StepScheduling& scheduling() const { return scheduling_; }

 private:
  struct Slow {
    long step;
    double seconds;
    StepEvents events;
  };
  static std::string causes(const StepEvents& e);
  static constexpr std::size_t kCauses = 10;
  static const std::array<const char*, kCauses> kCauseKeys;
  static std::array<bool, kCauses> cause_flags(const StepEvents& e);
  static std::string cause_text(std::size_t c, const StepEvents& e);
  StepScheduling scheduling_ = StepScheduling::of_this_thread();
  std::vector<double> seconds_;  // after the first step
  double first_ = -1, max_quiet_ = 0, output_max_ = 0, output_total_ = 0;
  long output_count_ = 0, switched_steps_ = 0;
  std::vector<Slow> slowest_;                                // the kSlowest largest, largest first
  std::array<std::pair<long, double>, kCauses> by_cause_{};  // steps, seconds
  std::map<int, std::pair<long, double>> by_cpu_;            // steps, seconds
  static constexpr std::size_t kSlowest = 5;
};

}  // namespace pcsim::simulation
