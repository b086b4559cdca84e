#include "sweep_bases.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "pcsim/output/modal_cache.hpp"
#include "pcsim/simulation/setup_memory.hpp"

namespace pcsim::app {

namespace {

std::string file_content(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The highest of the cut-offs (every mode, <= 0, is the highest).
double highest(const std::set<double>& cutoffs) {
  return *cutoffs.begin() <= 0 ? *cutoffs.begin() : *cutoffs.rbegin();
}

}  // namespace

void SweepBases::add(const CommandContext& ctx, const scene::RunScene& run, long dofs) {
  if (run.catenary.fidelity != catenary::CatenaryFidelity::modal) return;
  ++modal_cases_;
  // As simulation/catenary_setup.cpp keys the case's basis.
  const std::string key =
      output::modal_cache_key(file_content(run.catenary.design_path), run.catenary.mesh,
                              run.catenary.form_finding, run.snapshot_every > 0);
  Design& d = designs_[key];
  d.cutoffs.insert(run.catenary.modal.max_frequency_hz);
  ++d.cases;
  d.dofs = dofs;
  if (ctx.rank == 0)
    d.cached = !output::modal_data_candidates(ctx.cache_dir, key, highest(d.cutoffs)).empty();
}

std::string SweepBases::summary() const {
  if (modal_cases_ == 0) return "";
  std::size_t cached = 0, cutoffs = 0;
  long largest = 0;
  for (const auto& [key, d] : designs_) {
    cached += d.cached ? 1 : 0;
    cutoffs += d.cutoffs.size();
    largest = std::max(largest, d.dofs);
  }
  const std::size_t compute = designs_.size() - cached;
  std::string pairs;  // several cut-offs of one design
  if (cutoffs > designs_.size())
    pairs = ", " + std::to_string(cutoffs) + " (design, cut-off) pairs";
  char text[600];
  std::snprintf(text, sizeof text,
                "  modal bases: %zu case(s) on %zu catenary design(s)%s: %zu served by the cache "
                "folder, %zu to compute (an eigensolve of up to %ld unknowns each, by the first "
                "case that needs it%s); each group keeps its last %zu in memory\n",
                modal_cases_, designs_.size(), pairs.c_str(), cached, compute, largest,
                pairs.empty() ? "" : "; one more when a lower cut-off of a design runs first",
                simulation::kKeptBases);
  return text;
}

}  // namespace pcsim::app
