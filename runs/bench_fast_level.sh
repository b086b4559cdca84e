#!/usr/bin/env bash
# The fast level against its reference on the scenes users run (issue 21):
# every scene once with the linearised FE catenary (catenary.model=linear,
# the reference: same dt and mesh) and once with the reduced (modal) level at
# its defaults, one rank each; prints the table of runs/bench/fast_level_table.py
# (errors per figure and pantograph, the run's own estimate, set-up, ms/step,
# real-time factor, step-time percentiles, memory) and the load average before
# and after. Run it on an otherwise idle machine: it measures wall time. The
# first modal run of a design computes its modes into the cache (OUT/cache;
# minutes for 20 spans), later ones read them (the set-up column says which).
# Every run steps on the CPU a short probe finds fastest (-pcsim_step_cpu
# fastest): this machine's CPUs can differ by 1.5x or more, and which one is
# slower changes within minutes (docs/benchmarks.md, "The machine's two CPUs
# at different speeds"); a pcsim option after -- overrides it.
#   runs/bench_fast_level.sh                      # every scene (about an hour)
#   runs/bench_fast_level.sh runs/interaction/en50318-300.yaml ...   # these only
#   OUT=out/bench-fast runs/bench_fast_level.sh [scenes] -- [pcsim options]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh > /dev/null
OUT=${OUT:-out/bench-fast}
scenes=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do scenes+=("$1"); shift; done
[ "${1:-}" = "--" ] && shift
if [ ${#scenes[@]} -eq 0 ]; then  # the run scenes of runs/interaction and runs/lines
  for s in runs/interaction/*.yaml runs/lines/*.yaml; do
    case $s in *-fine.yaml | */elasticity-*.yaml) continue ;; esac
    scenes+=("$s")
  done
fi
mkdir -p "$OUT"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
# The hour's stalls of the machine itself: a step's time includes any that
# falls in it (docs/benchmarks.md, "What a modal run's slow steps are").
echo "the machine's stalls before the runs (runs/bench/stall_probe.py 10):"
/usr/bin/python3 runs/bench/stall_probe.py 10
names=()
for scene in "${scenes[@]}"; do
  name=$(basename "$scene" .yaml)
  names+=("$name")
  mkdir -p "$OUT/$name"
  for model in linear modal; do
    dir=$OUT/$name/$model
    # The reference runs no accuracy pilot; the modal run does (its estimate
    # and the cut-off it chooses are what is measured).
    pilot=true
    [ "$model" = linear ] && pilot=false
    if ! build/pcsim run "$scene" -o "$dir" --overwrite --no-report --cache "$OUT/cache" \
      --set catenary.model=$model \
      -pcsim_accuracy_pilot $pilot -pcsim_step_cpu fastest "$@" \
      > "$OUT/$name/$model.log" 2>&1; then
      echo "FAILED: $scene ($model), see $OUT/$name/$model.log" >&2
    fi
  done
done
echo
/usr/bin/python3 runs/bench/fast_level_table.py "$OUT" "${names[@]}"
echo
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
