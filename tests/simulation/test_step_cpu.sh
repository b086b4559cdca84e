#!/bin/bash
# -pcsim_step_cpu N (simulation/step_cpu.hpp) pins the stepping thread to
# CPU N: summary.json's step_time.by_cpu (the CPU each step ended on, by
# sched_getcpu) then names N alone, for every step after the first, on each
# CPU this process may use (two at most), on linear FE and on the modal
# level with its records' batches on their own thread (which leaves CPU N to
# the step). A first run whose accuracy pilot runs linear FE in its second
# process (4-span EN 50318 line) steps on CPU N too, its pilot's runs not
# pinned (both processes would share CPU N). A run without the option counts
# every such step under some CPU. -pcsim_step_cpu fastest probes each CPU
# (summary.json step_time.pinned.probe_passes_per_s) and steps on the one
# with the most passes. Pinning keeps the run's spare core: a modal run
# whose records' thread is left to pcsim (-pcsim_record_thread auto) has one
# pinned as unpinned, where the process may use two CPUs or more.
# Bad values: tests/app/test_bad_input.sh. Run time: ~5 s.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scene=$PCSIM_SOURCE_DIR/tests/contact/data/three-span-lumped.yaml
run() {  # run NAME [options...]
  local name=$1
  shift
  "$PCSIM_BIN" run "$scene" -o "$tmp/$name" --no-report -ts_max_steps 200 --cache "$tmp/cache" \
    "$@" > "$tmp/$name.log" 2>&1 || { cat "$tmp/$name.log"; exit 1; }
}
mapfile -t cpus < <("$PCSIM_PYTHON" -c 'import os; print(*sorted(os.sched_getaffinity(0))[:2], sep="\n")')
run plain
run fastest -pcsim_step_cpu fastest
modal_auto=(--set catenary.model=modal --set catenary.max_frequency_hz=150 -pcsim_record_batches true)
run modal-auto "${modal_auto[@]}"
run modal-auto-pinned "${modal_auto[@]}" -pcsim_step_cpu fastest
for c in "${cpus[@]}"; do
  run "linear-$c" -pcsim_step_cpu "$c"
  run "modal-$c" -pcsim_step_cpu "$c" --set catenary.model=modal \
    --set catenary.max_frequency_hz=150 -pcsim_record_batches true -pcsim_record_thread true
done
"$PCSIM_BIN" run "$PCSIM_SOURCE_DIR/tests/contact/data/en50318-short.yaml" --set catenary.design.spans.count=4 \
  --set catenary.model=modal -pcsim_accuracy_pilot true -pcsim_pilot_process true -o "$tmp/pilot" \
  --no-report --cache "$tmp/cache" -pcsim_step_cpu "${cpus[0]}" > "$tmp/pilot.log" 2>&1 ||
  { cat "$tmp/pilot.log"; exit 1; }
"$PCSIM_PYTHON" - "$tmp" "${cpus[@]}" <<'PY'
import json, os, sys
tmp, cpus = sys.argv[1], sys.argv[2:]
def step_time(name):
    with open(f"{tmp}/{name}/summary.json") as f:
        return json.load(f)
failures = []
plain = step_time("plain")["step_time"]
counted = sum(v["steps"] for v in plain["by_cpu"].values())
if counted != plain["steps"] - 1:
    failures.append(f"plain: {counted} steps by CPU of {plain['steps'] - 1}")
for c in cpus:
    for level in ("linear", "modal"):
        s = step_time(f"{level}-{c}")
        by_cpu = s["step_time"]["by_cpu"]
        if list(by_cpu) != [c] or by_cpu[c]["steps"] != s["step_time"]["steps"] - 1:
            failures.append(f"{level} on CPU {c}: {by_cpu}")
        if level == "modal" and not s.get("records_thread"):
            failures.append(f"modal on CPU {c}: no records' thread ({s.get('records_thread')})")
s = step_time("fastest")["step_time"]
probe, cpu = s["pinned"].get("probe_passes_per_s", {}), str(s["pinned"]["cpu"])
allowed = sorted(os.sched_getaffinity(0))
if sorted(map(int, probe)) != allowed or probe[cpu] != max(probe.values()):
    failures.append(f"fastest: CPU {cpu} after the probe {probe} of CPUs {allowed}")
if list(s["by_cpu"]) != [cpu]:
    failures.append(f"fastest: steps on {s['by_cpu']}, pinned to {cpu}")
threads = [step_time(n).get("records_thread") for n in ("modal-auto", "modal-auto-pinned")]
if threads != [len(allowed) > 1] * 2:
    failures.append(f"records' thread unpinned, pinned: {threads} with CPUs {allowed}")
if step_time("plain")["step_time"]["pinned"] is not None:
    failures.append("plain: pinned")
s = step_time("pilot")
by_cpu = s["step_time"]["by_cpu"]
if list(by_cpu) != [cpus[0]] or by_cpu[cpus[0]]["steps"] != s["step_time"]["steps"] - 1:
    failures.append(f"first run with the pilot on CPU {cpus[0]}: {by_cpu}")
if not s["accuracy_estimate"]["pilot"]["second_process"]:
    failures.append("the pilot's FE runs not in a second process")
for f in failures:
    print("FAIL:", f)
if failures:
    sys.exit(1)
print(f"step cpu: ok (CPUs {', '.join(cpus)})")
PY
