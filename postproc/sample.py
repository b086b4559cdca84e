#!/usr/bin/python3
"""A case table for `pcsim sweep SCENE --cases FILE.csv`: a sampling design over scene keys.

    sample.py DESIGN -p KEY=DIST [-p KEY=DIST ...] [-n N] [--seed S] -o FILE.csv

DESIGN:
  grid      every combination of the keys' levels: N levels of a continuous distribution
            (uniform, loguniform: N evenly spaced values from a to b, in log for loguniform;
            normal: the N quantiles at (i + 1/2)/N), every value of a list; N^k cases at most
  lhs       Latin hypercube (scipy.stats.qmc.LatinHypercube): N cases, one in each of the N
            equal-probability strata of every key
  sobol     scrambled Sobol sequence (scipy.stats.qmc.Sobol), N cases, N a power of 2
  saltelli  the Saltelli design for first-order and total Sobol indices: a scrambled Sobol
            sequence of 2k dimensions gives the N x k matrices A and B; the table holds A,
            B, then A_B^(1) .. A_B^(k) (A with its column i from B), N rows each: N (k + 2)
            cases, N a power of 2 (postproc/sensitivity.py reads them in this order)
DIST (per key, the key as `pcsim --set` takes it, e.g. pantographs[0].static_force):
  uniform(a,b)       a < b
  normal(mu,sigma)   sigma > 0
  loguniform(a,b)    0 < a < b
  list(v1,v2,...)    the values as given (text; no commas inside), equally likely
The table (CSV) starts with a comment `# sample: {JSON}`: the design, seed, N, the keys and
their distributions, the number of cases and, for saltelli, the order of the blocks; pcsim
sweep keeps it in its summary.json. Same design, keys, N and seed: the same table.
Bad input: one line naming the argument on stderr, exit 2, no file written.
"""
import argparse
import json
import math
import os
import re
import sys

MAX_CASES = 10000  # what pcsim sweep takes
DESIGNS = ("grid", "lhs", "sobol", "saltelli")
DIST_PATTERN = re.compile(r"^\s*(uniform|normal|loguniform|list)\s*\((.*)\)\s*$")
KEY_PATTERN = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*(\[[0-9]+\])?(\.[A-Za-z_][A-Za-z0-9_]*(\[[0-9]+\])?)*$")


class SampleError(Exception):
    """Bad input: one line, exit 2."""


def parse_distribution(text):
    """'KEY=DIST' -> (key, {'type', 'args'}); SampleError naming the argument if bad."""
    arg = "-p %s" % text
    if "=" not in text:
        raise SampleError("%s: give KEY=DIST, e.g. simulation.speed_kmh=uniform(250,320)" % arg)
    key, dist = (s.strip() for s in text.split("=", 1))
    if not KEY_PATTERN.match(key):
        raise SampleError("%s: '%s' is not a scene key (e.g. pantographs[0].static_force)" % (arg, key))
    m = DIST_PATTERN.match(dist)
    if not m:
        raise SampleError("%s: '%s' is not uniform(a,b), normal(mu,sigma), loguniform(a,b) or "
                          "list(v1,v2,...)" % (arg, dist))
    kind, inside = m.group(1), [s.strip() for s in m.group(2).split(",")]
    if kind == "list":
        if any(not v or '"' in v for v in inside) or len(set(inside)) != len(inside):
            raise SampleError("%s: a list needs distinct, non-empty values without quotes" % arg)
        return key, {"type": kind, "args": inside}
    try:
        a, b = (float(v) for v in inside)
    except ValueError:
        raise SampleError("%s: %s takes two numbers" % (arg, kind)) from None
    if not (math.isfinite(a) and math.isfinite(b)):
        raise SampleError("%s: the numbers must be finite" % arg)
    if kind in ("uniform", "loguniform") and not a < b:
        raise SampleError("%s: %s(a,b) needs a < b" % (arg, kind))
    if kind == "loguniform" and not a > 0:
        raise SampleError("%s: loguniform(a,b) needs 0 < a" % arg)
    if kind == "normal" and not b > 0:
        raise SampleError("%s: normal(mu,sigma) needs sigma > 0" % arg)
    return key, {"type": kind, "args": [a, b]}


def from_unit(u, dist):
    """Values of a distribution at probabilities u (array in [0, 1)): the inverse CDF."""
    import numpy as np
    kind, args = dist["type"], dist["args"]
    u = np.clip(np.asarray(u, dtype=float), 1e-12, 1 - 1e-12)
    if kind == "uniform":
        return args[0] + u * (args[1] - args[0])
    if kind == "loguniform":
        return np.exp(math.log(args[0]) + u * (math.log(args[1]) - math.log(args[0])))
    if kind == "normal":
        from scipy.stats import norm
        return norm.ppf(u, loc=args[0], scale=args[1])
    index = np.minimum((u * len(args)).astype(int), len(args) - 1)
    return np.array(args, dtype=object)[index]


def levels(dist, n):
    """The grid's values of one key."""
    import numpy as np
    kind, args = dist["type"], dist["args"]
    if kind == "list":
        return list(args)
    if kind == "uniform":
        return list(np.linspace(args[0], args[1], n)) if n > 1 else [0.5 * (args[0] + args[1])]
    if kind == "loguniform":
        return list(np.geomspace(args[0], args[1], n)) if n > 1 else [math.sqrt(args[0] * args[1])]
    return list(from_unit((np.arange(n) + 0.5) / n, dist))


def power_of_two(n, design):
    if n < 2 or n & (n - 1):
        raise SampleError("-n %d: the %s design needs a power of 2 >= 2 (its balance), e.g. 64"
                          % (n, design))
    return int(round(math.log2(n)))


def unit_design(design, k, n, seed):
    """Rows in the unit hypercube [0, 1)^k (lhs, sobol) or [0, 1)^2k (saltelli: A | B)."""
    from scipy.stats import qmc
    if design == "lhs":
        return qmc.LatinHypercube(d=k, seed=seed).random(n)
    m = power_of_two(n, design)
    return qmc.Sobol(d=k if design == "sobol" else 2 * k, scramble=True, seed=seed).random_base2(m)


def saltelli_blocks(a, b):
    """[A; B; A_B^(1); ...; A_B^(k)]: A with its column i taken from B."""
    import numpy as np
    blocks = [a, b]
    for i in range(a.shape[1]):
        ab = a.copy()
        ab[:, i] = b[:, i]
        blocks.append(ab)
    return np.vstack(blocks)


def sample(design, dists, n, seed):
    """The case table's rows (lists of values, one per key) for the design; dists is
    [(key, dist)]. No limit on the number of rows but a grid's (main() keeps a table to
    what pcsim sweep runs)."""
    import itertools
    import numpy as np
    k = len(dists)
    if design == "grid":
        grids = [levels(d, n) for _, d in dists]
        if np.prod([float(len(g)) for g in grids]) > MAX_CASES:
            raise SampleError("-n %d: the grid has more than %d cases" % (n, MAX_CASES))
        return [list(row) for row in itertools.product(*grids)]
    u = unit_design(design, k, n, seed)
    if design == "saltelli":
        u = saltelli_blocks(u[:, :k], u[:, k:])
    columns = [from_unit(u[:, i], d) for i, (_, d) in enumerate(dists)]
    return [[c[j] for c in columns] for j in range(len(u))]


def text_of(value):
    """A CSV field: numbers to 10 significant digits, text quoted if it needs it."""
    if isinstance(value, str):
        if any(c in value for c in ',"') or value != value.strip():
            return '"%s"' % value.replace('"', '""')
        return value
    return "%.10g" % float(value)


def record(design, dists, n, seed, rows):
    r = {"design": design, "seed": None if design == "grid" else seed, "n": n,
         "keys": [key for key, _ in dists], "distributions": {key: d for key, d in dists},
         "cases": len(rows), "tool": "postproc/sample.py"}
    if design == "saltelli":
        r["blocks"] = ["A", "B"] + ["AB_%d" % (i + 1) for i in range(len(dists))]
        r["block_rows"] = n
    return r


def write_table(path, rec, rows):
    """The CSV, written whole (a temporary file renamed) or not at all."""
    lines = ["# sample: " + json.dumps(rec, separators=(",", ":")),
             ",".join(rec["keys"])] + [",".join(text_of(v) for v in row) for row in rows]
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(tmp, path)


class Parser(argparse.ArgumentParser):
    def error(self, message):
        raise SampleError(message)


def parse_args(argv):
    ap = Parser(prog="sample.py", description=__doc__.split("\n")[0],
                epilog=__doc__.split("\n\n", 2)[2], formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("design", metavar="DESIGN", help="grid, lhs, sobol or saltelli")
    ap.add_argument("-p", "--param", action="append", default=[], metavar="KEY=DIST",
                    help="a sampled scene key and its distribution (repeat for each key)")
    ap.add_argument("-n", type=int, default=None,
                    help="grid: levels per continuous key (3); lhs, sobol: cases (16); "
                         "saltelli: base rows N (16), N (k + 2) cases")
    ap.add_argument("--seed", type=int, default=1, help="seed of the random designs (1)")
    ap.add_argument("-o", "--output", required=True, metavar="FILE.csv", help="the case table")
    a = ap.parse_args(argv)
    if a.design not in DESIGNS:
        raise SampleError("DESIGN '%s': one of %s" % (a.design, ", ".join(DESIGNS)))
    if not a.param:
        raise SampleError("-p: give at least one KEY=DIST")
    if a.n is None:
        a.n = 3 if a.design == "grid" else 16
    if a.n < 1:
        raise SampleError("-n %d: at least 1" % a.n)
    if a.seed < 0:
        raise SampleError("--seed %d: a seed is >= 0" % a.seed)
    folder = os.path.dirname(os.path.abspath(a.output))
    if not os.path.isdir(folder):
        raise SampleError("-o %s: the folder %s does not exist" % (a.output, folder))
    return a


def main(argv=None):
    try:
        a = parse_args(sys.argv[1:] if argv is None else argv)
        dists = [parse_distribution(p) for p in a.param]
        keys = [key for key, _ in dists]
        for key in keys:
            if keys.count(key) > 1:
                raise SampleError("-p %s: the key is given twice" % key)
        count = {"lhs": a.n, "sobol": a.n, "saltelli": a.n * (len(dists) + 2)}.get(a.design, 0)
        if count > MAX_CASES:
            raise SampleError("-n %d: %d cases, pcsim sweep takes %d at most" % (a.n, count, MAX_CASES))
        rows = sample(a.design, dists, a.n, a.seed)
        rec = record(a.design, dists, a.n, a.seed, rows)
        write_table(a.output, rec, rows)
    except SampleError as e:
        sys.stderr.write("sample.py: error: %s\n" % e)
        sys.exit(2)
    except ImportError as e:
        sys.stderr.write("sample.py: error: %s (Debian: apt-get install python3-scipy)\n" % e)
        sys.exit(2)
    print("sample.py: %s design, %d cases of %s -> %s" % (a.design, len(rows), ", ".join(keys), a.output))


if __name__ == "__main__":
    main()
