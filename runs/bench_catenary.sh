#!/bin/bash
# Benchmark of form-finding + statics and of the catenary modes (not a test).
#
#   runs/bench_catenary.sh [--max-spans N] [--ranks "1 2"] [--log-view] [--keep DIR]
#
# Builds parametric catenaries of 10, 100 and 1000 spans (up to N; default
# 1000) from meshes/en50318-reference.yaml by changing spans.count, runs
# `pcsim static` and `pcsim modes` (20 modes) on each rank count, and prints a
# table: spans, DOFs, ranks, Newton iterations, form-finding + static time
# (summary.json wall_time_s of `pcsim static`), modes time (modes_wall_time_s
# of `pcsim modes`, SLEPc only), lowest frequency, and the peak resident
# memory of every rank (GNU time -v "Maximum resident set size").
# The pcsim executable is $PCSIM_BIN (default build/pcsim); each run is limited
# to $BENCH_TIMEOUT seconds (default 3600). --log-view adds PETSc's -log_view to
# every run (reports in the work folder's *.log); --keep keeps the work folder.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(dirname "$here")
max_spans=1000
rank_counts="1 2"
log_view=()
keep=""
while [ $# -gt 0 ]; do
  case $1 in
    --max-spans) max_spans=$2; shift 2 ;;
    --ranks) rank_counts=$2; shift 2 ;;
    --log-view) log_view=(-log_view); shift ;;
    --keep) keep=$2; shift 2 ;;
    -h|--help) sed -n '2,15p' "$0"; exit 0 ;;
    *) echo "bench_catenary.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
PCSIM_BIN=${PCSIM_BIN:-$root/build/pcsim}
BENCH_TIMEOUT=${BENCH_TIMEOUT:-3600}
PYTHON=/usr/bin/python3
[ -x "$PCSIM_BIN" ] || { echo "bench_catenary.sh: no pcsim executable at $PCSIM_BIN (set PCSIM_BIN)" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "bench_catenary.sh: needs GNU time at /usr/bin/time (Debian package 'time')" >&2; exit 2; }

if [ -n "$keep" ]; then
  work=$keep
  mkdir -p "$work"
else
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
fi
: > "$work/runs.txt"
reference=$root/meshes/en50318-reference.yaml

for spans in 10 100 1000; do
  [ "$spans" -le "$max_spans" ] || continue
  design=$work/catenary-$spans.yaml
  sed -e "s/^spans: {count: 10, length: 60.0}/spans: {count: $spans, length: 60.0}/" \
      -e "s/^name: en50318-reference/name: bench-$spans-spans/" "$reference" > "$design"
  grep -q "^spans: {count: $spans, length: 60.0}" "$design" ||
    { echo "bench_catenary.sh: could not set spans.count in $design" >&2; exit 1; }
  scene=$work/scene-$spans.yaml
  printf 'name: bench-%s\ncatenary: {design: catenary-%s.yaml, form_finding: true}\nmodes: {count: 20}\n' \
    "$spans" "$spans" > "$scene"
  for np in $rank_counts; do
    for kind in static modes; do
      run=$work/$kind-$spans-np$np
      echo "bench_catenary.sh: $kind, $spans spans, $np rank(s) ..." >&2
      status=0
      timeout "$BENCH_TIMEOUT" "$root/scripts/mpirun.sh" -n "$np" "$here/bench/time_rank.sh" "$run.time" \
        "$PCSIM_BIN" "$kind" "$scene" -o "$run" --overwrite "${log_view[@]}" > "$run.log" 2>&1 || status=$?
      [ "$status" -ne 124 ] || status=timeout
      # GNU time opens its report before the run: keep it beside the output
      # folder (which pcsim creates atomically at the end), then move it in.
      mkdir -p "$run"
      for f in "$run.time".rank*; do
        [ ! -e "$f" ] || mv "$f" "$run/time.rank${f##*.rank}"
      done
      [ "$status" = 0 ] || { echo "  failed ($status); last lines of $run.log:" >&2; tail -5 "$run.log" >&2; }
      echo "$spans $np $kind $status $run" >> "$work/runs.txt"
    done
  done
done

echo
echo "pcsim catenary benchmark ($(date -u +%Y-%m-%d), $(nproc) cores: $(grep -m1 "model name" /proc/cpuinfo | cut -d: -f2 | sed "s/^ //"))"
"$PYTHON" "$here/bench/table.py" "$work"
[ -z "$keep" ] || echo "work folder (designs, logs, outputs): $work"
