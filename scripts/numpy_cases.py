#!/usr/bin/env python3
"""Check the expected texts of src/interp/numpy/tests.rs against numpy itself.

Each case of CASES is an expression and the text numpy gives for it (`str` of an array, `repr` of a
Python number, bool or list). This evaluates every expression with numpy and prints the cases whose
stored text differs (with numpy's), so that the table can be refreshed when numpy's text changes.

    scripts/numpy_cases.py
"""

import os
import re
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TESTS = os.path.join(ROOT, "src", "interp", "numpy", "tests.rs")


def rust_str(s):
    return bytes(s, "utf-8").decode("unicode_escape")


def main():
    text = open(TESTS).read()
    table = text[text.index("const CASES"): text.index("];", text.index("const CASES"))]
    cases = re.findall(r'\(\s*"((?:[^"\\]|\\.)*)",\s*"((?:[^"\\]|\\.)*)"\s*\)', table)
    if hasattr(np, "trapezoid") and not hasattr(np, "trapz"):
        np.trapz = np.trapezoid
    bad = 0
    for expr, want in cases:
        expr, want = rust_str(expr), rust_str(want)
        r = eval(expr, {"np": np})
        # numpy's scalars are Python numbers in the subset (numpy 2 writes them np.float64(...)).
        if isinstance(r, np.generic):
            r = r.item()
        elif isinstance(r, list):
            r = [x.item() if isinstance(x, np.generic) else x for x in r]
        got = r if isinstance(r, str) else str(r) if isinstance(r, np.ndarray) else repr(r)
        if got != want:
            bad += 1
            print("%s\n   stored: %r\n   numpy:  %r" % (expr, want, got))
    print("%d cases, %d differ (numpy %s)" % (len(cases), bad, np.__version__))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
