#!/bin/bash
# Runs one MPI rank of a command under GNU time (/usr/bin/time -v) and writes
# its report to PREFIX.rank<R> (R: the MPI rank from Open MPI / PMI, else 0).
#   usage: runs/bench/time_rank.sh PREFIX COMMAND [ARGS...]
# Used by runs/bench_catenary.sh for the peak memory of every rank.
set -euo pipefail
prefix=$1
shift
rank=${OMPI_COMM_WORLD_RANK:-${PMI_RANK:-0}}
exec /usr/bin/time -v -o "$prefix.rank$rank" "$@"
