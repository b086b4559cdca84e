#include "pcsim/output/accuracy_study.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace pcsim::output {

namespace {

std::string format(const char* fmt, double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), fmt, v);
  return buffer;
}

double relative(double value, double reference) {
  return 100.0 * (value - reference) / std::max(std::abs(reference), 1e-12);
}

// The larger-magnitude of a and b (keeps the sign).
double worse(double a, double b) {
  return std::abs(b) > std::abs(a) ? b : a;
}

}  // namespace

std::string StudyRun::label() const {
  std::string s = model + " dt=" + format("%g", dt * 1e3) + "ms h=" + format("%g", element_length);
  if (model == "modal") {
    s += " fc=" + format("%.0f", cutoff_hz) + "Hz";
    if (vertical_only) s += " vertical";
  }
  return s;
}

StudyErrors study_errors(const StudyRun& run, const StudyRun& ref) {
  StudyErrors e;
  if (!run.ok || !ref.ok || run.figures.size() != ref.figures.size()) return e;
  e.valid = true;
  for (std::size_t p = 0; p < run.figures.size(); ++p) {
    const auto& a = run.figures[p];
    const auto& b = ref.figures[p];
    e.mean = worse(e.mean, relative(a.mean, b.mean));
    e.std_dev = worse(e.std_dev, relative(a.std_dev, b.std_dev));
    e.stat_max = worse(e.stat_max, relative(a.stat_max, b.stat_max));
    e.stat_min = worse(e.stat_min, relative(a.stat_min, b.stat_min));
    e.max = worse(e.max, relative(a.max, b.max));
    e.min = worse(e.min, relative(a.min, b.min));
  }
  e.uplift = relative(run.uplift_m, ref.uplift_m);
  for (double v : {e.mean, e.std_dev, e.stat_max, e.max, e.uplift})
    e.worst = std::max(e.worst, std::abs(v));
  return e;
}

int finest_fe_run(const std::vector<StudyRun>& runs) {
  int best = -1;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const auto& r = runs[i];
    if (!r.ok || r.model == "modal") continue;
    if (best < 0) {
      best = static_cast<int>(i);
      continue;
    }
    const auto& b = runs[best];
    const double size = r.dt * r.element_length, best_size = b.dt * b.element_length;
    if (size < best_size * (1 - 1e-9) ||
        (size < best_size * (1 + 1e-9) && r.model == "nonlinear" && b.model != "nonlinear"))
      best = static_cast<int>(i);
  }
  return best;
}

void evaluate_study(StudyTable& t) {
  const std::size_t n = t.runs.size();
  if (t.reference < 0) t.reference = finest_fe_run(t.runs);
  t.errors.assign(n, {});
  t.reduction_errors.assign(n, {});
  t.pareto.assign(n, false);
  for (std::size_t i = 0; i < n; ++i) {
    if (t.reference >= 0) t.errors[i] = study_errors(t.runs[i], t.runs[t.reference]);
    if (t.runs[i].model != "modal") continue;
    for (const auto& fe : t.runs)
      if (fe.model == "linear" && fe.ok && std::abs(fe.dt - t.runs[i].dt) < 1e-12 &&
          std::abs(fe.element_length - t.runs[i].element_length) < 1e-9)
        t.reduction_errors[i] = study_errors(t.runs[i], fe);
  }
  // Pareto: no other run at most as costly and as wrong, and better in one.
  for (std::size_t i = 0; i < n; ++i) {
    if (!t.errors[i].valid || static_cast<int>(i) == t.reference) continue;
    bool dominated = false;
    for (std::size_t j = 0; j < n && !dominated; ++j) {
      if (j == i || !t.errors[j].valid || static_cast<int>(j) == t.reference) continue;
      const double ci = t.runs[i].ms_per_step, cj = t.runs[j].ms_per_step;
      const double ei = t.errors[i].worst, ej = t.errors[j].worst;
      dominated = cj <= ci && ej <= ei && (cj < ci || ej < ei);
    }
    t.pareto[i] = !dominated;
  }
}

void write_accuracy_csv(const std::string& path, const StudyTable& t) {
  std::ofstream f(path);
  f << "run,model,dt_s,element_length_m,cutoff_hz,vertical_only,basis_size,pantograph,mean_N,"
       "std_N,stat_max_N,stat_min_N,max_N,min_N,uplift_m,err_mean_pct,err_std_pct,"
       "err_stat_max_pct,err_stat_min_pct,err_max_pct,err_min_pct,err_uplift_pct,"
       "err_worst_pct,reduction_err_worst_pct,steps,wall_s,ms_per_step,real_time_factor,"
       "peak_memory_mb,setup_s,predicted_sigma_err_pct,estimate_ok,reference,pareto,failure\n";
  f.precision(10);
  for (std::size_t i = 0; i < t.runs.size(); ++i) {
    const auto& r = t.runs[i];
    const auto& e = t.errors[i];
    const auto& re = t.reduction_errors[i];
    const std::size_t rows = std::max<std::size_t>(1, r.figures.size());
    for (std::size_t p = 0; p < rows; ++p) {
      const StudyFigures fig = p < r.figures.size() ? r.figures[p] : StudyFigures{};
      f << i << ',' << r.model << ',' << r.dt << ',' << r.element_length << ',' << r.cutoff_hz
        << ',' << r.vertical_only << ',' << r.basis_size << ',' << fig.pantograph << ',' << fig.mean
        << ',' << fig.std_dev << ',' << fig.stat_max << ',' << fig.stat_min << ',' << fig.max << ','
        << fig.min << ',' << r.uplift_m << ',' << e.mean << ',' << e.std_dev << ',' << e.stat_max
        << ',' << e.stat_min << ',' << e.max << ',' << e.min << ',' << e.uplift << ','
        << (e.valid ? e.worst : NAN) << ',' << (re.valid ? re.worst : NAN) << ',' << r.steps << ','
        << r.wall_s << ',' << r.ms_per_step << ',' << r.real_time_factor << ',' << r.peak_memory_mb
        << ',' << r.setup_s << ',' << r.predicted_error_percent << ',' << r.estimate_ok << ','
        << (static_cast<int>(i) == t.reference) << ',' << t.pareto[i] << ",\"" << r.failure
        << "\"\n";
    }
  }
}

std::string accuracy_markdown(const StudyTable& t) {
  std::ostringstream s;
  s << "| fidelity | dt [ms] | h [m] | cut-off [Hz] (vectors) | mean | σ | Fm+3σ | Fm−3σ | max "
       "| min | uplift | worst | reduction | ms/step | RTF | memory [MB] | estimate |\n"
    << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  const auto pct = [](const StudyErrors& e, double v) {
    return e.valid ? format("%+.2f %%", v) : std::string("–");
  };
  for (std::size_t i = 0; i < t.runs.size(); ++i) {
    const auto& r = t.runs[i];
    const auto& e = t.errors[i];
    const bool ref = static_cast<int>(i) == t.reference;
    s << "| " << (t.pareto[i] ? "**" + r.model + "**" : r.model)
      << (r.vertical_only ? " (vertical)" : "") << " | " << format("%g", r.dt * 1e3) << " | "
      << format("%g", r.element_length) << " | "
      << (r.model == "modal"
              ? format("%.0f", r.cutoff_hz) + " (" + std::to_string(r.basis_size) + ")"
              : std::string("–"))
      << " | ";
    if (!r.ok) {
      s << "failed: " << r.failure << " | | | | | | | | | | | | |\n";
      continue;
    }
    if (ref) {
      s << "reference | | | | | | | | ";
    } else {
      for (double v : {e.mean, e.std_dev, e.stat_max, e.stat_min, e.max, e.min, e.uplift})
        s << pct(e, v) << " | ";
      s << (e.valid ? format("%.2f %%", e.worst) : "–") << " | ";
    }
    const auto& re = t.reduction_errors[i];
    s << (re.valid ? format("%.2f %%", re.worst) : "–") << " | " << format("%.3f", r.ms_per_step)
      << " | " << format("%.2f", r.real_time_factor) << " | " << format("%.0f", r.peak_memory_mb)
      << " | " << (r.estimate_ok ? "in" : "**out**")
      << format(" (~%.1f %%)", r.predicted_error_percent) << " |\n";
  }
  s << "\nErrors: relative to the reference run (the finest FE run: smallest dt x h, nonlinear "
       "before linear), worst over the pantographs; 'worst' over mean, σ, Fm+3σ, actual max and "
       "uplift; 'reduction': the modal run against the linearised FE run at the same dt and h. "
       "Bold: on the Pareto front of worst error against ms/step. Estimate: the run's accuracy "
       "estimate (inside or outside the converged region, predicted σ error). Costs: wall time "
       "of the time loop (nonlinear: full Newton path; linear, modal: cheap path) on "
    << t.ranks << " rank(s), machine load average " << format("%.1f", t.load_before) << " before, "
    << format("%.1f", t.load_after) << " after.\n";
  return s.str();
}

nlohmann::json study_json(const StudyTable& t) {
  nlohmann::json j;
  j["scene"] = t.scene;
  j["reference"] = t.reference;
  j["ranks"] = t.ranks;
  j["load_average_before"] = t.load_before;
  j["load_average_after"] = t.load_after;
  for (std::size_t i = 0; i < t.runs.size(); ++i) {
    const auto& r = t.runs[i];
    j["runs"].push_back({{"label", r.label()},
                         {"ok", r.ok},
                         {"ms_per_step", r.ms_per_step},
                         {"real_time_factor", r.real_time_factor},
                         {"worst_error_percent", t.errors[i].valid ? t.errors[i].worst : -1.0},
                         {"reduction_error_percent",
                          t.reduction_errors[i].valid ? t.reduction_errors[i].worst : -1.0},
                         {"pareto", static_cast<bool>(t.pareto[i])}});
  }
  return j;
}

}  // namespace pcsim::output
