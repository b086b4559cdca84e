"""Collectives per step by call site, from two runs of runs/bench/mpi_call_sites.c:
one of N steps and one of 2N (their difference over N is the steady step,
set-up apart). Prints a Markdown table: count per step, kind, and the first
pcsim or PETSc functions on the stack. Used by runs/bench_reductions.sh.
    mpi_call_sites.py SITES_N SITES_2N N
"""
import collections
import re
import subprocess
import sys

SKIP = re.compile(r"^(PMPI_|MPI_|ompi_|mca_|_?start|__libc|main$)")


def read_sites(path):
    sites = []
    for line in open(path):
        words = line.split()
        if words[0] == "site":
            sites.append((words[1], int(words[2]), []))
        else:
            sites[-1][2].append((words[1], words[2], words[3]))
    return sites


def symbolise(sites):
    """Function names of the frames without an exported symbol, one addr2line per module."""
    wanted = collections.defaultdict(set)
    for _, _, frames in sites:
        for module, offset, symbol in frames:
            if symbol == "-":
                wanted[module].add(offset)
    names = {}
    for module, offsets in wanted.items():
        offsets = sorted(offsets)
        out = subprocess.run(["addr2line", "-f", "-C", "-e", module] + offsets,
                             capture_output=True, text=True).stdout.split("\n")
        for i, offset in enumerate(offsets):
            names[(module, offset)] = out[2 * i] if 2 * i < len(out) else "??"
    return names


def short(name):
    name = re.sub(r"\(.*", "", name)  # no argument list
    return name.replace("pcsim::", "").replace("(anonymous namespace)::", "")


def by_site(path):
    sites = read_sites(path)
    names = symbolise(sites)
    counts = collections.Counter()
    for kind, count, frames in sites:
        stack = []
        for module, offset, symbol in frames:
            name = symbol if symbol != "-" else names.get((module, offset), "??")
            if name == "??" or SKIP.match(name) or "mpi_call_sites" in module:
                continue
            stack.append(short(name))
        counts[(kind, " < ".join(stack[:4]))] += count
    return counts


def main():
    once, twice, steps = by_site(sys.argv[1]), by_site(sys.argv[2]), int(sys.argv[3])
    rows = []
    for key in twice:
        per_step = (twice[key] - once.get(key, 0)) / steps
        if per_step >= 0.05:
            rows.append((per_step, key))
    rows.sort(reverse=True)
    print("| per step | kind | call stack (innermost first) |")
    print("|---:|---|---|")
    for per_step, (kind, stack) in rows:
        print(f"| {per_step:.2f} | {kind} | {stack} |")
    print(f"| **{sum(r[0] for r in rows):.2f}** | all | |")


if __name__ == "__main__":
    main()
