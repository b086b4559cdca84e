#!/usr/bin/python3
"""Checks pcsim's architecture rules (docs/architecture.md); exit 1 on a breach.

1. Every #include of a pcsim header follows the allowed dependencies between
   the parts (folders of src/ and include/pcsim/):
     app -> simulation, scene, output, solvers, catenary, pantograph  (only these:
            never assembly or contact, whatever they include);
     simulation -> scene, solvers, output, assembly (and what they may include);
     solvers -> assembly  (only: of catenary, contact and pantograph just the
            result types and the model interfaces its drivers call back,
            SOLVER_PHYSICS_HEADERS);
     assembly -> catenary, contact, pantograph;  contact -> catenary;
     scene, output -> catenary, pantograph, contact;  everything -> core.
   Rules are transitive except for app and solvers.
2. The physics parts (catenary, pantograph, contact) create no solvers,
   include no solver headers and do not mention YAML; no part but scene
   includes yaml-cpp.
3. No source file in src/ is longer than 500 lines and no function longer
   than 80 lines (a brace-matching count of the lines between a function's
   opening and closing braces).

usage: scripts/check-architecture.py [ROOT]
"""
import os
import re
import sys

DIRECT = {
    "core": set(),
    "catenary": {"core"},
    "pantograph": {"core"},
    "contact": {"catenary", "core"},
    "assembly": {"catenary", "contact", "pantograph", "core"},
    "solvers": {"assembly", "core"},
    "scene": {"catenary", "pantograph", "contact", "core"},
    "output": {"catenary", "pantograph", "contact", "core"},
    "simulation": {"scene", "solvers", "output", "assembly", "core"},
    "app": {"simulation", "scene", "output", "solvers", "catenary", "pantograph", "core"},
    "python": {"simulation", "scene", "output", "core"},  # the Python API: like app
}
NOT_TRANSITIVE = {"app", "solvers", "python"}
# What solvers may include of the physics parts: result types and the model
# interfaces its drivers call back.
SOLVER_PHYSICS_HEADERS = {
    "pcsim/catenary/results.hpp",        # StaticResult, ModesResult
    "pcsim/pantograph/model.hpp",        # PantographModel: residual and tangents (time responses)
    "pcsim/pantograph/linear.hpp",       # LinearModel: M, C, K of a linearised pantograph (modes)
    "pcsim/pantograph/time_history.hpp", # a time response
}
PHYSICS = ("catenary", "pantograph", "contact")
SOLVER_PATTERN = re.compile(r"pcsim/solvers|pcsim/simulation|petscts\.h|petscsnes\.h|petscksp\.h|"
                            r"slepceps\.h|SNESCreate|SNESSetFunction|EPSCreate|TSCreate|KSPCreate|"
                            r"PCShellSet\w*")
MAX_FILE_LINES = 500
MAX_FUNCTION_LINES = 80


def closure(part):
    if part in NOT_TRANSITIVE:
        return DIRECT[part] | {part}
    seen, todo = set(), [part]
    while todo:
        for dep in DIRECT[todo.pop()]:
            if dep not in seen:
                seen.add(dep)
                todo.append(dep)
    return seen | {part}


def header_part(header):
    """Part of a pcsim header named in an #include ('pcsim/x/y.hpp')."""
    parts = header.split("/")
    if len(parts) == 2:  # pcsim/error.hpp: the core
        return "core"
    return parts[1]


def source_files(root):
    for top in ("src", os.path.join("include", "pcsim")):
        for folder, _, files in os.walk(os.path.join(root, top)):
            for name in files:
                if name.endswith((".cpp", ".hpp")):
                    path = os.path.join(folder, name)
                    rel = os.path.relpath(path, os.path.join(root, top))
                    part = rel.split(os.sep)[0] if os.sep in rel else "core"
                    yield path, part


def function_lengths(text):
    """(name, lines) of every function body at namespace/class level."""
    out = []
    depth, start, name = 0, None, None
    header = re.compile(r"([A-Za-z_][\w:~<>]*)\s*\([^;{}]*\)\s*(const)?\s*(override)?\s*(noexcept)?\s*"
                        r"(->\s*[\w:<>]+\s*)?(:[^;{}]*)?$")
    pending = ""
    for lineno, line in enumerate(text.splitlines(), 1):
        code = re.sub(r"//.*", "", line)
        for ch in code:
            if ch == "{":
                if start is None and header.search(pending.strip()):
                    m = header.search(pending.strip())
                    name, start = m.group(1), lineno
                    base = depth
                depth += 1
                pending = ""
            elif ch == "}":
                depth -= 1
                if start is not None and depth == base:
                    out.append((name, lineno - start + 1, start))
                    start = None
                pending = ""
            elif ch == ";":
                pending = ""
            else:
                pending += ch
        pending += " "
    return out


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    problems = []
    include = re.compile(r'#include\s+"(pcsim/[^"]+)"')
    for path, part in source_files(root):
        rel = os.path.relpath(path, root)
        if part not in DIRECT:
            problems.append(f"{rel}: unknown part '{part}'")
            continue
        text = open(path, encoding="utf-8").read()
        allowed = closure(part)
        for header in include.findall(text):
            dep = header_part(header)
            if part == "solvers" and header in SOLVER_PHYSICS_HEADERS:
                continue
            if dep not in allowed:
                problems.append(f"{rel}: {part} may not include {header} ({dep})")
        if part in PHYSICS and SOLVER_PATTERN.search(text):
            problems.append(f"{rel}: a physics part creates or includes a solver "
                            f"({SOLVER_PATTERN.search(text).group(0)})")
        if part in PHYSICS and re.search(r"yaml", text, re.IGNORECASE):
            problems.append(f"{rel}: a physics part mentions YAML (readers live in scene/)")
        if part != "scene" and re.search(r"#include\s*[<\"]yaml-cpp", text):
            problems.append(f"{rel}: only scene/ includes yaml-cpp")
        if rel.startswith("src" + os.sep):
            n = text.count("\n")
            if n > MAX_FILE_LINES:
                problems.append(f"{rel}: {n} lines (limit {MAX_FILE_LINES})")
            for name, length, start in function_lengths(text):
                if length > MAX_FUNCTION_LINES:
                    problems.append(f"{rel}:{start}: function {name} has {length} lines "
                                    f"(limit {MAX_FUNCTION_LINES})")
    for p in problems:
        print(p)
    print(f"check-architecture: {len(problems)} problem(s)")
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
