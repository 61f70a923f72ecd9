#!/usr/bin/env python3
"""Regenerate the two maps of tests/README.md: every command that runs (from `aster catalog`) with the
integration tests, our scenes and the passing legacy cases whose command files call it; and every case
of ../shared/astest with its state (tests/passing.txt) and the tests that read it. tidy::docs checks
that both maps are complete and agree with tests/passing.txt.

    cargo build --release && python3 scripts/test_map.py
"""
import glob
import os
import re
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
os.chdir(ROOT)
AST = "../shared/astest"

cat = subprocess.run(["target/release/aster", "catalog"], capture_output=True, text=True, check=True).stdout
cmds = [l.split()[0] for l in cat.splitlines() if len(l.split()) > 1 and l.split()[1] == "runs"]
passing = {}
for l in open("tests/passing.txt"):
    if l.strip() and not l.startswith("#"):
        w = l.split()
        passing[w[0]] = w[1]


def comm_of(case):
    ex = open(f"{AST}/{case}.export").read()
    m = re.search(r"^F comm (\S+)", ex, re.M)
    return open(f"{AST}/{m.group(1)}").read()


def calls(text, c):
    return re.search(r"\b" + c + r"\s*\(", text) is not None


modules = []
for f in sorted(glob.glob("tests/it/**/*.rs", recursive=True)):
    m = f[len("tests/it/"):-3].replace("/", "::")
    if m in ("main", "common") or m.endswith("::mod"):
        continue
    modules.append((m, open(f).read()))
scenes = [(os.path.basename(f)[:-5], open(f).read()) for f in sorted(glob.glob("comm/*.comm"))]
legacy = [(c, comm_of(c)) for c in passing] if os.path.isdir(AST) else []

rows = ["| command | test modules (tests/it/) | our scenes (comm/, legacy::scenes) | legacy cases (legacy::astest) |",
        "|---|---|---|---|"]
for c in cmds:
    mods = [f"`{m}`" for m, t in modules if not m.startswith(("tidy", "language::fuzz")) and calls(t, c)]
    sc = [n for n, t in scenes if calls(t, c)]
    lc = [n for n, t in legacy if calls(t, c)]
    rows.append(f"| {c} | {', '.join(mods) or '—'} | {', '.join(sc) or '—'} | {', '.join(lc) or '—'} |")
command_map = "\n".join(rows) + "\n"

case_map = ""
if os.path.isdir(AST):
    cases = sorted(os.path.basename(f)[:-7] for f in glob.glob(f"{AST}/*.export"))
    rung, r = {}, "?"
    for line in open(f"{AST}/README.md"):
        m = re.match(r"## \((\w)\)", line)
        if m:
            r = m.group(1)
        m = re.match(r"- \*\*(\w+)\*\*", line)
        if m:
            rung[m.group(1)] = r
    rows = ["| case | rung | state | tests beyond the conformance run |", "|---|---|---|---|"]
    for c in sorted(cases, key=lambda c: (rung.get(c, "z"), c)):
        st = f"passing, {passing[c]} OK" if c in passing else "stops (the conformance table says where)"
        mods = [f"`{m}`" for m, t in modules if m != "legacy::astest" and re.search(r"\b" + c + r"\b", t)]
        rows.append(f"| {c} | {rung.get(c, '?')} | {st} | {', '.join(mods) or '—'} |")
    case_map = "\n".join(rows) + "\n"

s = open("tests/README.md").read()
a = s.index("| command | test modules")
b = s.index("## Legacy cases and their tests")
s = s[:a] + command_map + "\n" + s[b:]
if case_map:
    a = s.index("| case | rung |")
    s = s[:a] + case_map
open("tests/README.md", "w").write(s)
