#!/bin/bash
# A run's report and a sweep's table, plots and report, read back as a user would:
#  - `pcsim run` (EN 50318 scene shortened to 3 spans by --set, 1440 steps, snapshots)
#    ends with the EN 50318 table and writes report.html (postproc/report.py); a run with
#    three pantographs gets a force and a spectrum panel per pantograph;
#  - `pcsim sweep` over two speeds, two cases at a time: sweep.csv, sweep.md, sweep.png,
#    report.html, summary.json, one run result per case;
#  - each report.html is parsed: its tables (the EN 50318 figures with a verdict per row,
#    a run's accuracy estimate: its calibrated criteria without a pilot),
#    its images (every one an embedded PNG that decodes), and no reference to anything
#    outside the page (every href is an anchor of the page, every src a data: URI);
#  - postproc/animate.py renders a GIF of the snapshots (one frame per snapshot);
#  - every postproc script answers --help with a help text for every argument, and a
#    missing folder with one line on stderr, no traceback.
set -euo pipefail
: "${PCSIM_BIN:?}" "${PCSIM_SOURCE_DIR:?}" "${PCSIM_PYTHON:=/usr/bin/python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
scene=$PCSIM_SOURCE_DIR/tests/contact/data/en50318-short.yaml
short=(--set catenary.design.spans.count=3)

"$PCSIM_BIN" run "$scene" "${short[@]}" --set output.snapshot_every=100 -o run > run.log 2>&1 ||
  { cat run.log; exit 1; }
grep -q "acceptance ranges of EN 50318:2002 at 300 km/h" run.log || { cat run.log; exit 1; }
grep -qE "mean contact force Fm +N +[0-9.]+ +110 \.\. 120 +(pass|FAIL)" run.log || { cat run.log; exit 1; }
"$PCSIM_BIN" sweep "$scene" "${short[@]}" --set simulation.speed_kmh=250:300:50 -j 2 -o sweep \
  > sweep.log 2>&1 || { cat sweep.log; exit 1; }
"$PCSIM_PYTHON" "$PCSIM_SOURCE_DIR/postproc/animate.py" run -o run.gif > animate.log 2>&1 ||
  { cat animate.log; exit 1; }
"$PCSIM_BIN" run "$PCSIM_SOURCE_DIR/tests/contact/data/three-span-three-pantographs.yaml" \
  -o three > three.log 2>&1 || { cat three.log; exit 1; }

"$PCSIM_PYTHON" - "$tmp" "$PCSIM_SOURCE_DIR/postproc" <<'PY'
import base64, csv, json, os, re, subprocess, sys
from html.parser import HTMLParser
from PIL import Image
tmp, postproc = sys.argv[1], sys.argv[2]

class Page(HTMLParser):
    def __init__(self):
        super().__init__()
        self.tables, self.images, self.refs, self.ids = [], [], [], set()
        self.cell = None
    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "id" in a: self.ids.add(a["id"])
        if tag == "table": self.tables.append([])
        if tag == "tr": self.tables[-1].append([])
        if tag in ("td", "th"): self.cell = ""
        if tag == "img": self.images.append(a.get("src", ""))
        for key in ("href", "src"):
            if key in a: self.refs.append(a[key])
    def handle_endtag(self, tag):
        if tag in ("td", "th"):
            self.tables[-1][-1].append(self.cell.strip())
            self.cell = None
    def handle_data(self, data):
        if self.cell is not None: self.cell += data

def check_page(path, n_images, verdict_rows):
    p = Page()
    p.feed(open(path).read())
    assert len(p.images) == n_images, (path, len(p.images))
    for src in p.images:
        assert src.startswith("data:image/png;base64,"), src[:40]
        png = base64.b64decode(src.split(",", 1)[1])
        assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 5000, len(png)
    for ref in p.refs:  # nothing outside the page
        assert ref.startswith("data:") or (ref.startswith("#") and ref[1:] in p.ids), ref
    header = next(t for t in p.tables if t and "verdict" in t[0] or t and len(t[0]) > 10)
    assert len(header) - 1 == verdict_rows, (path, len(header) - 1)
    return p

run = check_page(os.path.join(tmp, "run/report.html"), 3, 8)  # force, spectrum, uplift
figures = next(t for t in run.tables if t[0][:5] == ["figure", "unit", "value", "range", "verdict"])
assert [r[0] for r in figures[1:]][:2] == ["mean contact force Fm", "standard deviation sigma"]
assert all(r[4] in ("pass", "fail") for r in figures[1:]), figures
assert any(t[0][0] == "" and any(r[0] == "git_commit" for r in t) for t in run.tables)
summary = json.load(open(os.path.join(tmp, "run/summary.json")))
assert summary["en50318"]["pantograph"]["edition"] == "EN 50318:2002"
assert summary["provenance"]["overrides"] == ["catenary.design.spans.count=3", "output.snapshot_every=100"]
# The accuracy estimate: without a pilot (the tests' options), the calibrated criteria
# as summary.json has them, each inside or outside its converged region.
criteria = next(t for t in run.tables if t and t[0][:2] == ["criterion", "value"])
assert [r[0] for r in criteria[1:]] == [c["name"] for c in summary["accuracy_estimate"]["criteria"]]
for r, c in zip(criteria[1:], summary["accuracy_estimate"]["criteria"]):
    assert r[1] == "%.2f" % c["value"] and r[5] == ("inside" if c["ok"] else "OUTSIDE"), (r, c)

sweep = check_page(os.path.join(tmp, "sweep/report.html"), 1, 2)  # figures vs speed; 2 cases
rows = list(csv.DictReader(open(os.path.join(tmp, "sweep/sweep.csv"))))
assert [r["simulation.speed_kmh"] for r in rows] == ["250", "300"], rows
assert all(r["status"] == "ok" and r["std_N_verdict"] in ("pass", "fail") for r in rows), rows
for r in rows:  # the table holds the cases' own figures
    s = json.load(open(os.path.join(tmp, "sweep/cases", r["case"], "summary.json")))
    assert abs(float(r["std_N"]) - s["pantographs"][0]["std_N"]) <= 1e-5 * s["pantographs"][0]["std_N"]
    assert abs(s["speed_kmh"] - float(r["simulation.speed_kmh"])) < 1e-9
assert open(os.path.join(tmp, "sweep/sweep.md")).read().count("\n| 0") == 2
assert os.path.getsize(os.path.join(tmp, "sweep/sweep.png")) > 20000
assert os.path.isfile(os.path.join(tmp, "sweep/.pcsim-result"))

# Three pantographs: a force and a spectrum panel each (readable, every
# pantograph's spectrum), then the uplift.
three = Page()
three.feed(open(os.path.join(tmp, "three/report.html")).read())
assert len(three.images) == 7, len(three.images)
alts = re.findall(r'alt="([^"]*)"', open(os.path.join(tmp, "three/report.html")).read())
assert alts == [f"contact force{s} of &#x27;{n}&#x27;" for n in ("first", "second", "third")
                for s in ("", " spectrum")] + ["uplift at the supports"], alts

gif = Image.open(os.path.join(tmp, "run.gif"))
assert gif.format == "GIF" and gif.n_frames == 15, gif.n_frames  # snapshots at steps 0, 100, ..., 1400

# Every postproc script: --help describes every argument; a missing folder gives one line.
# The helper modules say "(not a script itself)" on their first line (pcsim_post.py,
# measurement_csv.py).
for script in sorted(os.listdir(postproc)):
    path = os.path.join(postproc, script)
    if not script.endswith(".py") or "(not a script itself)" in open(path).read(300):
        continue
    help_text = subprocess.run([sys.executable, path, "--help"], capture_output=True, text=True, check=True).stdout
    sections = help_text.split("\n\n")
    entries = [l for s in sections if s.startswith(("positional arguments:", "options:"))
               for l in s.splitlines()[1:] if l.startswith("  ") and not l.startswith("   " * 6)]
    bare = [l for l in entries if len(l.strip().split("  ")) == 1 and not l.strip().startswith("{")]
    # an argument whose help did not fit on its line continues on the next, deeper indented
    lines = help_text.splitlines() + [""]
    bare = [l for l in bare if not lines[lines.index(l) + 1].startswith(" " * 20)]
    assert not bare, (script, bare)
    args = {"interaction_plots.py": ["force", "/nonexistent", "-o", "x.png"],
            "report.py": ["run", "/nonexistent"],
            "interaction_static_curve.py": ["/nonexistent", "/nonexistent", "-o", "x.png"],
            "pantograph_compare.py": ["modes", "/nonexistent", "/nonexistent"]}.get(
        script, ["/nonexistent"] + (["-o", "x.png"] if script.startswith(("pantograph_", "animate")) else []))
    r = subprocess.run([sys.executable, path] + args, capture_output=True, text=True)
    err = r.stderr.strip().splitlines()
    assert r.returncode != 0 and len(err) == 1 and err[0].startswith(script + ": error:"), (script, r.stderr)
print("report, sweep, animation and postproc checks passed")
PY
