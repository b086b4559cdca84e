# shellcheck shell=bash
# The runs of the window tests (test_run_window.sh, test_run_window_stitched.sh),
# sourced once tmp, S and scene are set: the scene cut to 10 spans, end at
# 250 m, statistics over spans 3-4; the window of 5 spans (1 behind, 2 with
# the pantograph, 2 ahead), which moves once, at 180 m, inside that section.
# shellcheck disable=SC2034  # window: the sourcing test's
: "${tmp:?}" "${S:?}" "${scene:?}"
line=(--set catenary.design.spans.count=10 --set simulation.end_x=250
  --set analysis.from_span=3 --set analysis.to_span=4 --no-report --cache "$tmp/cache")
window=(--set window.spans_behind=1 --set window.spans_ahead=2)

run() {  # run NAME RANKS [options]: `pcsim run "$scene"` into $tmp/NAME
  local name=$1 np=$2
  shift 2
  "$S/scripts/mpirun.sh" -n "$np" "$PCSIM_BIN" run "$scene" -o "$tmp/$name" "${line[@]}" "$@" \
    > "$tmp/$name.log" 2>&1 || { cat "$tmp/$name.log"; exit 1; }
}
