"""Checks the user documentation (README.md and docs/**/*.md) of a pcsim tree.

  /usr/bin/python3 tests/app/doc_links.py [SOURCE_DIR]

1. Every relative link and image, [text](target) or ![alt](target), names a
   file or folder of the repository (resolved from the page's own folder,
   the part after '#' dropped); a '#anchor' must be a heading of the target
   page (GitHub's slugs). Links to web addresses are not followed.
2. No page names a path outside the repository: '../shared', 'shared/seed',
   'shared/reference', or an absolute path of a machine (/work/, /home/,
   /root/, /tmp/, /mnt/, /Users/). System programs (/usr/bin/python3) are
   allowed.
3. Every repository path named in the text (include/..., src/..., tests/...,
   runs/..., meshes/..., scripts/..., postproc/..., docs/..., cmake/...)
   exists; a '*' or '{a,b}' in it is a glob that must match something, and
   'x.yaml' style names are placeholders.

Prints every problem as FILE:LINE: message and exits 1 if there is any.
"""
import glob
import os
import re
import sys

root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                       os.path.join(os.path.dirname(__file__), "..", ".."))
pages = ["README.md"] + sorted(
    os.path.relpath(p, root) for p in glob.glob(os.path.join(root, "docs", "**", "*.md"),
                                                recursive=True))

LINK = re.compile(r"!?\[(?:[^\]\[]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
OUTSIDE = re.compile(r"\.\./shared|\bshared/(?:seed|reference)\b|(?<![\w.~-])/(?:work|home|root|tmp|mnt|Users)/")
REPO_PATH = re.compile(
    r"(?<![A-Za-z0-9_./{-])((?:include|src|tests|runs|meshes|scripts|postproc|docs|cmake)/"
    r"[A-Za-z0-9_./*{},-]*[A-Za-z0-9_/*}])")
PLACEHOLDER = re.compile(r"^(?:x|X|NAME|DIR|SCENE)\.[a-z0-9]+$|<|[A-Z]{3,}")

problems = []


def line_of(text, pos):
    return text.count("\n", 0, pos) + 1


def slug(heading):
    """GitHub's anchor of a heading: lower case, punctuation dropped, spaces to '-'."""
    s = heading.strip().lower()
    s = re.sub(r"[`*_]", lambda m: "_" if m.group(0) == "_" else "", s)
    s = re.sub(r"[^\w\- ]", "", s, flags=re.UNICODE)
    return s.replace(" ", "-")


anchor_cache = {}


def anchors(path):
    if path not in anchor_cache:
        found, counts, fenced = set(), {}, False
        with open(path, encoding="utf-8") as f:
            for line in f:
                if line.lstrip().startswith("```"):
                    fenced = not fenced
                    continue
                m = None if fenced else re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
                if m:
                    base = slug(m.group(1))
                    n = counts.get(base, 0)
                    counts[base] = n + 1
                    found.add(base if n == 0 else f"{base}-{n}")
        anchor_cache[path] = found
    return anchor_cache[path]


def expand_braces(pattern):
    m = re.search(r"\{([^{}]*)\}", pattern)
    if not m:
        return [pattern]
    out = []
    for alt in m.group(1).split(","):
        out += expand_braces(pattern[:m.start()] + alt + pattern[m.end():])
    return out


for page in pages:
    path = os.path.join(root, page)
    with open(path, encoding="utf-8") as f:
        text = f.read()
    here = os.path.dirname(path)

    for m in LINK.finditer(text):
        target = m.group(1)
        where = f"{page}:{line_of(text, m.start())}"
        if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto:
            continue
        file_part, _, anchor = target.partition("#")
        if file_part.startswith("/"):
            problems.append(f"{where}: link '{target}' is an absolute path")
            continue
        dest = os.path.normpath(os.path.join(here, file_part)) if file_part else path
        if os.path.relpath(dest, root).startswith(".."):
            problems.append(f"{where}: link '{target}' leaves the repository")
            continue
        if not os.path.exists(dest):
            problems.append(f"{where}: link '{target}': no such file {os.path.relpath(dest, root)}")
            continue
        if anchor and dest.endswith(".md") and anchor not in anchors(dest):
            problems.append(f"{where}: link '{target}': no heading '#{anchor}' in "
                            f"{os.path.relpath(dest, root)}")

    for m in OUTSIDE.finditer(text):
        problems.append(f"{page}:{line_of(text, m.start())}: names a path outside the "
                        f"repository: '{text[m.start():m.start() + 40].splitlines()[0]}'")

    for m in REPO_PATH.finditer(text):
        name = m.group(1).rstrip(".,")
        if PLACEHOLDER.search(os.path.basename(name.rstrip("/"))):
            continue
        if any(c in name for c in "*{"):
            ok = any(glob.glob(os.path.join(root, p)) for p in expand_braces(name))
        else:
            ok = os.path.exists(os.path.join(root, name))
        if not ok:
            problems.append(f"{page}:{line_of(text, m.start())}: names {name}, which does not exist")

for p in problems:
    print(p)
print(f"{len(pages)} pages checked, {len(problems)} problem(s)")
sys.exit(1 if problems else 0)
