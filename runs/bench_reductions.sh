#!/usr/bin/env bash
# The global collectives of the FE step by call site (docs/scaling.md, "The
# step's reductions, combined"): builds runs/bench/mpi_call_sites.c with mpicc,
# preloads it into two runs of the EN 50318 case at 300 km/h (STEPS and
# 2 x STEPS steps, so that the set-up cancels) and prints the collectives a
# step makes (MPI_Allreduce, MPI_Bcast, MPI_Reduce, MPI_Allgather,
# MPI_Barrier: PETSc's and pcsim's own), by call stack. Counts, not times:
# any machine state will do.
#   runs/bench_reductions.sh [PCSIM_BIN] [extra pcsim options]
# Environment: RANKS=3 SPANS=20 STEPS=150.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/pcsim}
[ $# -gt 0 ] && shift
ranks=${RANKS:-3} spans=${SPANS:-20} steps=${STEPS:-150}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mpicc -shared -fPIC -O1 -o "$tmp/libmpi_call_sites.so" runs/bench/mpi_call_sites.c -ldl
for n in "$steps" $((2 * steps)); do
  scripts/mpirun.sh -n "$ranks" -x LD_PRELOAD="$tmp/libmpi_call_sites.so" \
    -x MPI_CALL_SITES_OUT="$tmp/sites.$n" "$bin" run runs/en50318-300.yaml \
    --set catenary.design.spans.count="$spans" -ts_max_steps "$n" --no-report \
    -o "$tmp/run$n" "$@" > "$tmp/run$n.log" 2>&1 || { cat "$tmp/run$n.log"; exit 1; }
done
echo "$ranks ranks, $spans spans, $bin: collectives per step (rank 0, steps $steps to $((2 * steps)))"
/usr/bin/python3 runs/bench/mpi_call_sites.py "$tmp/sites.$steps" "$tmp/sites.$((2 * steps))" "$steps"
