#!/usr/bin/env python3
"""How much of Code_Aster's verification corpus `aster check` accepts, and what stops the rest.

Runs `aster check` (parse, run the Python, validate every command call against the catalogue, compute
nothing) over every command file of the corpus (`*.comm` and the `*.com0`, `*.com1`, ... of continued
runs), groups the first refusal of each failing file by what it names, and prints the counts. With
--write, the section "Checking the corpus" of docs/corpus.md (between its markers) is regenerated.

    scripts/corpus_check.py                 # counts and the most frequent reasons
    scripts/corpus_check.py --write         # ... and regenerate docs/corpus.md's section
    scripts/corpus_check.py --top 60 --examples 3
"""

import argparse
import collections
import datetime
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CORPUS = os.environ.get("CORPUS", os.path.join(ROOT, "..", "shared", "corpus", "astest-2025"))
DOC = os.path.join(ROOT, "docs", "corpus.md")
BEGIN = "<!-- scripts/corpus_check.py: begin -->"
END = "<!-- scripts/corpus_check.py: end -->"
COMMAND_FILE = re.compile(r"\.com(m|\d+)$")


def run_check(files):
    exe = os.path.join(ROOT, "target", "release", "aster")
    out = {}
    for i in range(0, len(files), 200):
        batch = files[i : i + 200]
        r = subprocess.run([exe, "check"] + batch, cwd=CORPUS, capture_output=True, text=True)
        lines = (r.stdout + r.stderr).splitlines()
        for f in batch:
            out[f] = None
        for line in lines:
            m = re.match(r"^(\S+?): OK \(", line)
            if m and m.group(1) in out:
                out[m.group(1)] = "OK"
                continue
            m = re.match(r"^(\S+?):(\d+):(\d+): (.*)$", line)
            if m and m.group(1) in out and out[m.group(1)] is None:
                out[m.group(1)] = m.group(4)
                continue
            m = re.match(r"^(\S+?): (.*)$", line)
            if m and m.group(1) in out and out[m.group(1)] is None:
                out[m.group(1)] = m.group(2)
    return out


def reason(msg):
    """(kind, reason): the construct a refusal names, with the details that vary folded."""
    m = re.match(r"import ([\w.]+)", msg)
    if m:
        mod = m.group(1)
        if mod.startswith("code_aster"):
            return "python", "import %s (the code_aster object API)" % mod
        return "python", "import %s" % mod
    m = re.search(r"NameError: name '(\w+)' is not defined", msg)
    if m:
        return "python", "NameError: %s" % m.group(1)
    m = re.match(r"(invalid syntax|SyntaxError)[: ]*(.*)", msg)
    if m:
        return "python", "syntax: %s" % re.sub(r"'[^']*'", "'…'", m.group(2))[:70]
    m = re.match(r"([A-Z][A-Z0-9_]+): (.*)", msg)
    if m and m.group(1) not in ("NameError", "TypeError", "ValueError", "AttributeError", "KeyError", "IndexError"):
        cmd, rest = m.groups()
        rest = re.sub(r" \(did you mean '[^']*'\?\)", "", rest)
        rest = re.sub(r"got (\S+) \S+", r"got \1", rest)
        rest = re.sub(r"\d+", "N", rest)
        return "catalogue", "%s: %s" % (cmd, rest[:110])
    folded = re.sub(r"\d+", "N", msg)
    folded = re.sub(r"'[^']{20,}'", "'…'", folded)
    return "python", folded[:110]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--write", action="store_true", help="regenerate the section of docs/corpus.md")
    ap.add_argument("--top", type=int, default=40)
    ap.add_argument("--examples", type=int, default=2)
    opts = ap.parse_args()
    if not os.path.isdir(CORPUS):
        sys.exit("corpus_check: %s is absent" % CORPUS)
    subprocess.run(["cargo", "build", "--release", "-q", "--bin", "aster"], cwd=ROOT, check=True)
    files = sorted(f for f in os.listdir(CORPUS) if COMMAND_FILE.search(f))
    res = run_check(files)
    ok = [f for f, r in res.items() if r == "OK"]
    bad = {f: r or "no verdict" for f, r in res.items() if r != "OK"}
    groups = collections.defaultdict(list)
    kinds = collections.Counter()
    for f, msg in bad.items():
        k, r = reason(msg)
        kinds[k] += 1
        groups[r].append(f)
    n_comm = sum(1 for f in files if f.endswith(".comm"))
    lines = []
    lines.append("## Checking the corpus (`scripts/corpus_check.py`)")
    lines.append("")
    lines.append(
        "`aster check` parses a command file, runs its Python and validates every command call against the "
        "catalogue, computing nothing. Measured on %s over the %s command files of the corpus (%s `.comm`, %s "
        "`.com0`/`.com1`/… of continued runs, each checked alone):"
        % (datetime.date.today().isoformat(), fmt(len(files)), fmt(n_comm), fmt(len(files) - n_comm))
    )
    lines.append("")
    lines.append("| command files | pass `aster check` | stop on Python outside the subset | stop on a catalogue rule |")
    lines.append("|---:|---:|---:|---:|")
    for label, sel in ((" `.comm`", lambda f: f.endswith(".comm")), (" continued", lambda f: not f.endswith(".comm")), ("", lambda f: True)):
        fs = [f for f in files if sel(f)]
        k = collections.Counter(reason(bad[f])[0] for f in fs if f in bad)
        n_ok = sum(1 for f in fs if res[f] == "OK")
        lines.append("| %s%s | %s | %s | %s |" % (fmt(len(fs)), label, fmt(n_ok), fmt(k["python"]), fmt(k["catalogue"])))
    lines.append("")
    lines.append("The first refusal of the other files, grouped by what it names (most frequent first):")
    lines.append("")
    lines.append("| files | first refusal | e.g. |")
    lines.append("|---:|---|---|")
    ranked = sorted(groups.items(), key=lambda kv: (-len(kv[1]), kv[0]))
    for r, fs in ranked[: opts.top]:
        lines.append("| %d | %s | %s |" % (len(fs), r.replace("|", "\\|"), ", ".join(fs[: opts.examples])))
    rest = ranked[opts.top :]
    if rest:
        lines.append("| %d | %d other reasons, each stopping %d file(s) or fewer | |" % (sum(len(f) for _, f in rest), len(rest), len(rest[0][1])))
    lines.append("")
    text = "\n".join(lines)
    print(text)
    if opts.write:
        doc = open(DOC).read()
        block = BEGIN + "\n" + text + "\n" + END
        if BEGIN in doc and END in doc:
            doc = doc[: doc.index(BEGIN)] + block + doc[doc.index(END) + len(END) :]
        else:
            doc = doc.rstrip() + "\n\n" + block + "\n"
        with open(DOC, "w") as f:
            f.write(doc)
        print("wrote %s" % DOC, file=sys.stderr)


def fmt(n):
    return "{:,}".format(n)


if __name__ == "__main__":
    main()
