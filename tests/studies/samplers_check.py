#!/usr/bin/python3
"""The designs of postproc/sample.py: LHS stratification, Sobol balance, the Saltelli blocks,
the grid, seeds, the distributions' moments, the CSV it writes and its input errors.
usage: samplers_check.py SOURCE_DIR WORK_DIR"""
import csv
import json
import math
import os
import subprocess
import sys

import numpy as np

root, work = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(root, "postproc"))
import sample  # noqa: E402

failures = []


def check(ok, what):
    print("%s %s" % ("ok  " if ok else "FAIL", what))
    if not ok:
        failures.append(what)


U = lambda a, b: {"type": "uniform", "args": [a, b]}
dists = [("a", U(10.0, 20.0)), ("b", U(-1.0, 1.0)), ("c", U(0.0, 5.0))]

# LHS: every key has one point in each of the n equal-probability strata.
n = 50
x = np.array(sample.sample("lhs", dists, n, 7), float)
strata = [np.sort(np.floor((x[:, i] - lo) / (hi - lo) * n)) for i, (_, d) in enumerate(dists)
          for lo, hi in [d["args"]]]
check(all(np.array_equal(s, np.arange(n)) for s in strata), "lhs: one point per stratum per key (n=50, k=3)")

# Sobol (scrambled): 64 points, one in each 1/64 interval of every key and one in each cell
# of the 8 x 8 grid of the first two keys (a (0, m, 2)-net).
x = np.array(sample.sample("sobol", dists, 64, 3), float)
u = np.column_stack([(x[:, i] - d["args"][0]) / (d["args"][1] - d["args"][0])
                     for i, (_, d) in enumerate(dists)])
check(all(np.array_equal(np.sort(np.floor(u[:, i] * 64)), np.arange(64)) for i in range(3)),
      "sobol: one point in each 1/64 interval of every key")
cells = np.floor(u[:, 0] * 8) * 8 + np.floor(u[:, 1] * 8)
check(np.array_equal(np.sort(cells), np.arange(64)), "sobol: one point in each cell of the 8x8 grid (keys 1, 2)")

# Seeds: the same seed gives the same design, another seed another.
for design in ("lhs", "sobol", "saltelli"):
    same = sample.sample(design, dists, 16, 5) == sample.sample(design, dists, 16, 5)
    other = sample.sample(design, dists, 16, 5) != sample.sample(design, dists, 16, 6)
    check(same and other, "%s: seed 5 twice the same, seed 6 another" % design)

# Saltelli: A, B, then A_B^(i) = A with its column i from B; N (k + 2) rows.
nb = 32
x = np.array(sample.sample("saltelli", dists, nb, 1), float)
blocks = x.reshape(5, nb, 3)
ok = x.shape == (5 * nb, 3)
for i in range(3):
    expect = blocks[0].copy()
    expect[:, i] = blocks[1][:, i]
    ok = ok and np.array_equal(blocks[2 + i], expect)
check(ok and not np.any(blocks[0] == blocks[1]), "saltelli: rows A, B, A_B^(1..3), N (k+2) = 160")

# Grid: every combination, the endpoints of uniform and loguniform, every list value.
g = sample.sample("grid", [("a", U(1.0, 3.0)), ("b", {"type": "loguniform", "args": [1.0, 100.0]}),
                           ("c", {"type": "list", "args": ["x", "y"]})], 3, 1)
check(len(g) == 18 and sorted({r[0] for r in g}) == [1, 2, 3] and
      np.allclose(sorted({r[1] for r in g}), [1, 10, 100]) and {r[2] for r in g} == {"x", "y"},
      "grid: 3 x 3 x 2 cases, uniform 1,2,3, loguniform 1,10,100, list x,y")

# Moments: 4096 points; stratified designs are at least as good as random sampling, so a
# tolerance of 4 standard errors of random sampling is conservative.
m = 4096
for design in ("lhs", "sobol"):
    d = [("n", {"type": "normal", "args": [5.0, 2.0]}), ("l", {"type": "loguniform", "args": [1.0, 100.0]}),
         ("u", U(-3.0, 1.0)), ("k", {"type": "list", "args": ["p", "q", "r"]})]
    rows = sample.sample(design, d, m, 11)
    xn = np.array([r[0] for r in rows], float)
    xl = np.log(np.array([r[1] for r in rows], float))
    xu = np.array([r[2] for r in rows], float)
    freq = [sum(r[3] == v for r in rows) / m for v in "pqr"]
    se = lambda sd: 4 * sd / math.sqrt(m)
    check(abs(xn.mean() - 5) < se(2) and abs(xn.std() - 2) < 4 * 2 / math.sqrt(2 * m),
          "%s: normal(5,2) mean %.4f, std %.4f" % (design, xn.mean(), xn.std()))
    lsd = math.log(100) / math.sqrt(12)
    check(abs(xl.mean() - math.log(10)) < se(lsd) and abs(xl.std() - lsd) < se(lsd),
          "%s: loguniform(1,100): log mean %.4f (%.4f), log std %.4f (%.4f)"
          % (design, xl.mean(), math.log(10), xl.std(), lsd))
    check(abs(xu.mean() + 1) < se(4 / math.sqrt(12)) and xu.min() >= -3 and xu.max() <= 1,
          "%s: uniform(-3,1) mean %.4f, inside [-3, 1]" % (design, xu.mean()))
    check(all(abs(f - 1 / 3) < 4 * math.sqrt(2 / 9 / m) for f in freq),
          "%s: list(p,q,r) frequencies %s" % (design, ", ".join("%.4f" % f for f in freq)))

# The CLI: a CSV with the '# sample:' record, a header of keys, N rows; the same twice.
script = os.path.join(root, "postproc", "sample.py")
args = ["saltelli", "-p", "pantographs[0].static_force=uniform(100,140)",
        "-p", "simulation.speed_kmh=list(180,200)", "-n", "4", "--seed", "3"]
for name in ("t1.csv", "t2.csv"):
    subprocess.run([sys.executable, script] + args + ["-o", os.path.join(work, name)], check=True)
text = open(os.path.join(work, "t1.csv")).read()
check(text == open(os.path.join(work, "t2.csv")).read(), "sample.py: the same table twice")
lines = text.splitlines()
rec = json.loads(lines[0][len("# sample: "):])
body = list(csv.reader(lines[1:]))
check(rec["design"] == "saltelli" and rec["seed"] == 3 and rec["block_rows"] == 4 and rec["cases"] == 16
      and body[0] == ["pantographs[0].static_force", "simulation.speed_kmh"] and len(body) == 17,
      "sample.py: '# sample:' record (design, seed, N), header, 16 rows")

# Bad input: one line naming the argument, exit 2, no file.
bad = [(["lhs", "-p", "a=uniform(2,1)"], "-p a=uniform(2,1)"),
       (["lhs", "-p", "a=normal(0,-1)"], "sigma > 0"),
       (["lhs", "-p", "a=loguniform(0,1)"], "0 < a"),
       (["lhs", "-p", "a=weibull(1,2)"], "weibull"),
       (["lhs", "-p", "a=uniform(x,2)"], "two numbers"),
       (["lhs", "-p", "a b=uniform(1,2)"], "not a scene key"),
       (["lhs", "-p", "a=uniform(1,2)", "-p", "a=uniform(1,2)"], "twice"),
       (["sobol", "-p", "a=uniform(1,2)", "-n", "12"], "power of 2"),
       (["saltelli", "-p", "a=uniform(1,2)", "-n", "4096"], "10000"),
       (["mc", "-p", "a=uniform(1,2)"], "DESIGN 'mc'"),
       (["lhs"], "-p"),
       (["lhs", "-p", "a=uniform(1,2)", "-n", "x"], "-n")]
for extra, words in bad:
    out = os.path.join(work, "bad.csv")
    p = subprocess.run([sys.executable, script] + extra + ["-o", out], capture_output=True, text=True)
    err = p.stderr.strip()
    check(p.returncode == 2 and "\n" not in err and words in err and err.startswith("sample.py: error:")
          and not os.path.exists(out), "bad input %s: exit %d, '%s'" % (" ".join(extra), p.returncode, err))
if failures:
    sys.exit("FAIL: %d check(s)" % len(failures))
