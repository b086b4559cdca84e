// Console output shared by the commands.
#include <algorithm>
#include <cstdio>

#include "command.hpp"

namespace pcsim::app {

void print_static_summary(const CommandContext& ctx, const catenary::CatenaryMesh& mesh,
                          const catenary::StaticResult& r) {
  print0(ctx, "  Newton: %d iterations (%s), ||R||:", r.snes_iterations,
         r.converged_reason.c_str());
  for (double v : r.residual_history) print0(ctx, " %.2e", v);
  print0(ctx, "\n");
  if (!mesh.height_targets.empty())
    print0(ctx, "  max contact-wire height error at droppers: %.3e m\n", r.max_height_error_m);
  if (!mesh.tension_segments.empty())
    print0(ctx, "  max wire tension error: %.3e (relative)\n", r.max_tension_error_rel);
  double fmin = 1e300, fmax = -1e300;
  int n_droppers = 0;
  for (std::size_t b = 0; b < mesh.bars.size(); ++b)
    if (mesh.bars[b].kind == catenary::BarKind::dropper) {
      fmin = std::min(fmin, r.bar_forces[b]);
      fmax = std::max(fmax, r.bar_forces[b]);
      ++n_droppers;
    }
  if (n_droppers > 0)
    print0(ctx, "  %d droppers, static force %.1f .. %.1f N\n", n_droppers, fmin, fmax);
  if (!r.registration_forces.empty()) {
    const auto [lo, hi] =
        std::minmax_element(r.registration_forces.begin(), r.registration_forces.end());
    print0(ctx, "  %zu steady arms, lateral (pull-off) force %.1f .. %.1f N\n",
           r.registration_forces.size(), *lo, *hi);
  }
  print0(ctx, "  wall time %.3f s\n", r.wall_time_s);
  if (ctx.rank == 0)
    for (const auto& w : r.warnings) std::fprintf(stderr, "pcsim: warning: %s\n", w.c_str());
}

}  // namespace pcsim::app
