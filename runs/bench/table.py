"""Prints the table of runs/bench_catenary.sh from its work folder.

usage: /usr/bin/python3 runs/bench/table.py WORK_DIR
WORK_DIR/runs.txt lists one run per line: spans ranks kind status folder
(kind static|modes; status the exit code, or 'timeout'); every run folder
holds summary.json (if it succeeded) and time.rank<R> (GNU time -v reports).
"""
import glob
import json
import os
import re
import sys


def peak_rss_mb(folder):
    """Maximum resident set size of every rank [MB] as text, in rank order."""
    values = []
    for path in sorted(glob.glob(os.path.join(folder, "time.rank*")),
                       key=lambda p: int(p.rsplit("rank", 1)[1])):
        m = re.search(r"Maximum resident set size \(kbytes\): (\d+)", open(path).read())
        values.append(f"{int(m.group(1)) / 1024:.0f}" if m else "-")
    return values


def elapsed_s(folder):
    """Elapsed wall-clock time of the whole job (rank 0's GNU time report) [s]."""
    path = os.path.join(folder, "time.rank0")
    if not os.path.exists(path):
        return float("nan")
    m = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): ([0-9:.]+)", open(path).read())
    if not m:
        return float("nan")
    seconds = 0.0
    for part in m.group(1).split(":"):
        seconds = 60 * seconds + float(part)
    return seconds


def load(folder):
    path = os.path.join(folder, "summary.json")
    return json.load(open(path)) if os.path.exists(path) else None


def main(work):
    runs = {}
    for line in open(os.path.join(work, "runs.txt")):
        spans, ranks, kind, status, folder = line.split()
        runs[(int(spans), int(ranks), kind)] = (status, folder)
    header = ("| spans | DOFs | ranks | Newton its | form-finding + static [s] | static job [s] "
              "| peak RSS static [MB/rank] | modes (20, SLEPc) [s] | f1 [Hz] | modes job [s] "
              "| peak RSS modes [MB/rank] |")
    print(header)
    print("|" + "---|" * (header.count("|") - 1))
    for spans, ranks in sorted({(s, r) for s, r, _ in runs}):
        row = [str(spans), "", str(ranks)]
        cells = {}
        for kind in ("static", "modes"):
            status, folder = runs.get((spans, ranks, kind), ("not run", ""))
            s = load(folder) if folder else None
            rss = "/".join(peak_rss_mb(folder)) or "-" if folder else "-"
            seconds = elapsed_s(folder) if folder else float("nan")
            job = f"{seconds:.1f}" if seconds == seconds else "-"
            cells[kind] = (status, s, rss, job)
        status, s, rss, job = cells["static"]
        dofs = s["dofs"] if s else (cells["modes"][1]["dofs"] if cells["modes"][1] else "?")
        row[1] = str(dofs)
        if s:
            row += [str(s["snes_iterations"]), f"{s['wall_time_s']:.2f}", job, rss]
        else:
            row += ["-", f"FAILED ({status})", job, rss]
        status, s, rss, job = cells["modes"]
        if s:
            f = s["catenary_frequencies_hz"]
            row += [f"{s['modes_wall_time_s']:.2f}", f"{f[0]:.4f}" if f else "-", job, rss]
        else:
            row += [f"FAILED ({status})", "-", job, rss]
        print("| " + " | ".join(row) + " |")


if __name__ == "__main__":
    main(sys.argv[1])
