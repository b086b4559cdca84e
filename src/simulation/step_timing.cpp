#include "pcsim/simulation/step_timing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace pcsim::simulation {

void StepTiming::add(long step, double seconds, const StepEvents& events) {
  if (first_ < 0) {
    first_ = seconds;
    return;
  }
  seconds_.push_back(seconds);
  const auto flags = cause_flags(events);
  for (std::size_t c = 0; c < kCauses; ++c)
    if (flags[c]) {
      ++by_cause_[c].first;
      by_cause_[c].second += seconds;
    }
  if (events.cpu >= 0) {
    auto& [steps, total] = by_cpu_[events.cpu];
    ++steps;
    total += seconds;
  }
  if (events.involuntary_switches > 0)
    ++switched_steps_;
  else
    max_quiet_ = std::max(max_quiet_, seconds);
  if (slowest_.size() < kSlowest || seconds > slowest_.back().seconds) {
    slowest_.push_back({step, seconds, events});
    std::sort(slowest_.begin(), slowest_.end(),
              [](const Slow& a, const Slow& b) { return a.seconds > b.seconds; });
    if (slowest_.size() > kSlowest) slowest_.pop_back();
  }
}

void StepTiming::add_output(double seconds) {
  output_max_ = std::max(output_max_, seconds);
  output_total_ += seconds;
  ++output_count_;
}

// The keys of summary.json's step_time.by_cause, in causes()'s order
// (cause_text).
const std::array<const char*, StepTiming::kCauses> StepTiming::kCauseKeys = {
    "j0_refactored",
    "newton_iterations_above_1",
    "contacts_or_slack_droppers_changed",
    "dropper_exact_anchor",
    "window_shift",
    "after_output_flush",
    "records_batch_beside",
    "page_faults",
    "context_switch",
    "none"};

// The step's causes as flags over kCauseKeys ("none" alone when it has none).
std::array<bool, StepTiming::kCauses> StepTiming::cause_flags(const StepEvents& e) {
  std::array<bool, kCauses> flags = {e.reference_builds > 0,
                                     e.newton_iterations > 1,
                                     e.rank_one_set_changes > 0,
                                     e.exact_dropper_anchors > 0,
                                     e.window_shift,
                                     e.output_flush_before,
                                     e.records_batch_beside,
                                     e.page_faults > 0,
                                     e.involuntary_switches > 0,
                                     false};
  flags[kCauses - 1] = std::none_of(flags.begin(), flags.end(), [](bool f) { return f; });
  return flags;
}

// Cause c of kCauseKeys in words, with the step's counts.
std::string StepTiming::cause_text(std::size_t c, const StepEvents& e) {
  switch (c) {
    case 0:
      return "J0 refactored";
    case 1:
      return std::to_string(e.newton_iterations) + " Newton iterations";
    case 2:
      return "contacts or slack droppers changed (" + std::to_string(e.rank_one_terms) +
             " rank-one terms, " + std::to_string(e.capacitance_rows) + " capacitance rows formed)";
    case 3:
      return "dropper check's exact anchor";
    case 4:
      return "window shift";
    case 5:
      return "after an output flush";
    case 6:
      return "records' batch computing beside it";
    case 7:
      return std::to_string(e.page_faults) + " page fault(s)";
    case 8:
      return std::to_string(e.involuntary_switches) + " involuntary context switch(es)";
    default:
      return "none found";
  }
}

std::string StepTiming::causes(const StepEvents& e) {
  const auto flags = cause_flags(e);
  std::string out;
  for (std::size_t c = 0; c < kCauses; ++c)
    if (flags[c]) out += (out.empty() ? "" : ", ") + cause_text(c, e);
  return out;
}

nlohmann::json StepTiming::json() const {
  std::vector<double> sorted = seconds_;
  std::sort(sorted.begin(), sorted.end());
  auto percentile = [&](double p) {  // nearest rank
    if (sorted.empty()) return 0.0;
    const auto rank = static_cast<std::size_t>(std::ceil(p / 100.0 * sorted.size()));
    return 1e3 * sorted[std::min(sorted.size(), std::max<std::size_t>(rank, 1)) - 1];
  };
  nlohmann::json slowest = nlohmann::json::array();
  for (const auto& s : slowest_)
    slowest.push_back({{"step", s.step}, {"ms", 1e3 * s.seconds}, {"causes", causes(s.events)}});
  nlohmann::json by_cause = nlohmann::json::object();
  for (std::size_t c = 0; c < kCauses; ++c)
    if (const auto& [steps, total] = by_cause_[c]; steps > 0)
      by_cause[kCauseKeys[c]] = {{"steps", steps}, {"mean_ms", 1e3 * total / steps}};
  nlohmann::json by_cpu = nlohmann::json::object();
  for (const auto& [cpu, count] : by_cpu_)
    by_cpu[std::to_string(cpu)] = {{"steps", count.first},
                                   {"mean_ms", 1e3 * count.second / count.first}};
  return {{"steps", seconds_.size() + (first_ >= 0 ? 1 : 0)},
          {"first_step_ms", 1e3 * std::max(first_, 0.0)},
          {"median_ms", percentile(50)},
          {"p99_ms", percentile(99)},
          {"p99_9_ms", percentile(99.9)},
          {"p99_99_ms", percentile(99.99)},
          {"max_ms", sorted.empty() ? 0.0 : 1e3 * sorted.back()},
          {"max_without_context_switch_ms", 1e3 * max_quiet_},
          {"steps_with_context_switch", switched_steps_},
          {"output_max_ms", 1e3 * output_max_},
          {"output_mean_ms", output_count_ > 0 ? 1e3 * output_total_ / output_count_ : 0.0},
          {"slowest", slowest},
          {"by_cause", by_cause},
          {"by_cpu", by_cpu},
          {"scheduling", scheduling_.json()}};
}

namespace {

// "    steps by WHAT (count, mean ms): key steps, mean; ..." over {key:
// {steps, mean_ms}} (the by_cause and by_cpu of json()).
std::string counts_line(const char* what, const nlohmann::json& counts) {
  std::string line = std::string("    steps by ") + what + " (count, mean ms):";
  const char* separator = " ";
  char text[80];
  for (const auto& [key, count] : counts.items()) {
    std::snprintf(text, sizeof text, "%s%s %ld, %.3f", separator, key.c_str(),
                  count["steps"].get<long>(), count["mean_ms"].get<double>());
    line += text;
    separator = "; ";
  }
  return line + "\n";
}

}  // namespace

std::string StepTiming::summary_line() const {
  const auto j = json();
  char text[400];
  std::snprintf(text, sizeof text,
                "  step time: median %.3f ms, 99%% %.3f, 99.9%% %.3f, 99.99%% %.3f, max %.3f "
                "(%.3f without a context switch; %ld steps had one), first step %.2f ms; "
                "output %.3f ms at most, apart\n",
                j["median_ms"].get<double>(), j["p99_ms"].get<double>(),
                j["p99_9_ms"].get<double>(), j["p99_99_ms"].get<double>(),
                j["max_ms"].get<double>(), j["max_without_context_switch_ms"].get<double>(),
                j["steps_with_context_switch"].get<long>(), j["first_step_ms"].get<double>(),
                j["output_max_ms"].get<double>());
  std::string line = text;
  const auto& by_cause = j["by_cause"];
  if (by_cause.size() > 1 || (!by_cause.empty() && !by_cause.contains("none")))
    line += counts_line("cause", by_cause);
  if (!j["by_cpu"].empty()) line += counts_line("CPU", j["by_cpu"]);
  for (std::size_t i = 0; i < slowest_.size() && i < 3; ++i) {
    std::snprintf(text, sizeof text, "    slowest: step %ld, %.3f ms (%s)\n", slowest_[i].step,
                  1e3 * slowest_[i].seconds, causes(slowest_[i].events).c_str());
    line += text;
  }
  return line;
}

}  // namespace pcsim::simulation
