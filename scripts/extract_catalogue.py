#!/usr/bin/env python3
"""Extract the facts of Code_Aster's command catalogue into aster-rs' schema format.

Code_Aster describes every command in `code_aster/Cata/Commands/*.py` (SIMP, FACT, BLOC, rules, the type
of the result). This tool loads that catalogue with Python (the catalogue is plain Python, it needs
nothing compiled) and writes the facts only — names, types, allowed values, defaults, cardinalities,
bounds, block conditions, rules, produced types — in our own text format:

    src/catalog/generated/commands.cata   one schema per command (read by src/catalog/generated.rs)
    src/concepts/kind.rs                  the concept types and their hierarchy (ConceptKind)
    docs/catalogue.md                     where our hand-written schemas differ from Code_Aster's facts

No description text of Code_Aster is copied: the one-line description of each command comes from our own
`src/catalog/generated/descriptions.txt`. Conditions and result-type functions are Python in Code_Aster;
they are translated into our condition language where they follow the catalogue's usual patterns, and
the tool stops on a block condition it cannot translate. A result-type function is translated up to the
first statement it does not understand; from there on, the result is "one of" the types the function
declares it may return.

Commands with a hand-written schema (`Command::new("NAME"` in src/catalog/commands/) are emitted too,
without a description (theirs is in the hand-written schema): `aster check` validates their calls against
Code_Aster's schema widened by ours (src/catalog/merge.rs), while `aster run` keeps the hand-written schema
as the source of truth for what runs. The two are compared and the differences are written to
docs/catalogue.md.

Usage (the catalogue is taken from a checkout or an archive of Code_Aster's source tree):

    git -C CODE_ASTER archive HEAD code_aster/Cata | tar -x -C /tmp/ca
    touch /tmp/ca/code_aster/__init__.py
    scripts/extract_catalogue.py /tmp/ca [--version "main 2025-10-19"]
"""

import argparse
import ast
import inspect
import os
import re
import subprocess
import sys
import textwrap
import types

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT_CATA = os.path.join(ROOT, "src/catalog/generated/commands.cata")
DESCRIPTIONS = os.path.join(ROOT, "src/catalog/generated/descriptions.txt")
OUT_KINDS = os.path.join(ROOT, "src/concepts/kind.rs")
OUT_DOC = os.path.join(ROOT, "docs/catalogue.md")


class Untranslatable(Exception):
    pass


# ------------------------------------------------------------------ the catalogue


def load(cata_root):
    sys.path.insert(0, cata_root)
    from code_aster.Cata.Commands import commandStore  # noqa: E402
    from code_aster.Cata.Language import DataStructure as DS  # noqa: E402
    from code_aster.Cata.Language import SyntaxObjects as SO  # noqa: E402
    from code_aster.Cata.Language import Rules as RU  # noqa: E402
    from code_aster.Cata.Language import Validators as VA  # noqa: E402

    return commandStore, DS, SO, RU, VA


# ------------------------------------------------------------------ literals


def lit(v):
    """A literal in our format."""
    if isinstance(v, bool):
        return "1" if v else "0"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        r = repr(v)
        if r in ("inf", "-inf", "nan"):
            raise Untranslatable("non-finite literal")
        return r
    if isinstance(v, complex):
        return "c:%r:%r" % (v.real, v.imag)
    if isinstance(v, str):
        esc = v.replace("\\", "\\\\").replace("'", "\\'").replace("\n", "\\n").replace("\t", "\\t")
        return "'" + esc + "'"
    raise Untranslatable("literal of type %s" % type(v).__name__)


def lits(v):
    vs = v if isinstance(v, (list, tuple)) else [v]
    return ",".join(lit(x) for x in vs)


# ------------------------------------------------------------------ conditions

BLOCK_HELPERS = {"equal_to", "is_in", "exists", "value", "is_type", "size", "less_than", "greater_than"}


class CondTranslator:
    """Translate a BLOC condition (a Python expression) into our s-expression form."""

    def __init__(self, ds_names):
        self.ds = ds_names

    def kinds(self, node):
        if isinstance(node, ast.Name) and node.id in self.ds:
            return [node.id]
        if isinstance(node, (ast.Tuple, ast.List)):
            out = []
            for e in node.elts:
                out.extend(self.kinds(e))
            return out
        raise Untranslatable(ast.unparse(node))

    def const(self, node):
        if isinstance(node, ast.Constant):
            return [node.value]
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub) and isinstance(node.operand, ast.Constant):
            return [-node.operand.value]
        if isinstance(node, (ast.Tuple, ast.List)):
            out = []
            for e in node.elts:
                out.extend(self.const(e))
            return out
        raise Untranslatable(ast.unparse(node))

    def kwname(self, node):
        """`"NAME"` as a helper argument, `NAME` as a bare variable, `value("NAME")`."""
        if isinstance(node, ast.Constant) and isinstance(node.value, str):
            return node.value
        if isinstance(node, ast.Name) and node.id not in self.ds and node.id not in BLOCK_HELPERS:
            return node.id
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "value":
            return self.kwname(node.args[0])
        raise Untranslatable(ast.unparse(node))

    def type_of(self, node):
        """`is_type("K")` or `AsType(K)`: the keyword whose concept type is tested."""
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in ("is_type", "AsType"):
            return self.kwname(node.args[0])
        return None

    def tr(self, node):
        if isinstance(node, ast.Expression):
            return self.tr(node.body)
        if isinstance(node, ast.Constant) and isinstance(node.value, bool):
            return "(true)" if node.value else "(false)"
        if isinstance(node, ast.BoolOp):
            op = "and" if isinstance(node.op, ast.And) else "or"
            return "(%s %s)" % (op, " ".join(self.tr(v) for v in node.values))
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.Not):
            return "(not %s)" % self.tr(node.operand)
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
            f = node.func.id
            if f in ("equal_to", "is_in"):
                if len(node.args) < 2:
                    # a call Code_Aster cannot evaluate: its block evaluation treats the error as false
                    return "(false)"
                return "(eq %s %s)" % (self.kwname(node.args[0]), " ".join(lit(v) for v in self.const(node.args[1])))
            if f == "exists":
                return "(set %s)" % self.kwname(node.args[0])
            if f in ("less_than", "greater_than"):
                (v,) = self.const(node.args[1])
                return "(%s %s %s)" % ("lt" if f == "less_than" else "gt", self.kwname(node.args[0]), lit(v))
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "startswith":
            (v,) = self.const(node.args[0])
            return "(prefix %s %s)" % (self.kwname(node.func.value), lit(v))
        if isinstance(node, ast.Compare) and len(node.ops) == 1:
            left, op, right = node.left, node.ops[0], node.comparators[0]
            neg = isinstance(op, (ast.NotEq, ast.NotIn))
            wrap = (lambda s: "(not %s)" % s) if neg else (lambda s: s)
            # the type of a concept
            t = self.type_of(left)
            if t is not None and isinstance(op, (ast.Eq, ast.NotEq, ast.In, ast.NotIn)):
                return wrap("(type %s %s)" % (t, " ".join(self.kinds(right))))
            # 'X' in value("K"): one of the values of K is X
            if isinstance(op, (ast.In, ast.NotIn)) and isinstance(left, ast.Constant):
                return wrap("(eq %s %s)" % (self.kwname(right), lit(left.value)))
            # size('K') > n, len(K) == n
            if isinstance(left, ast.Call) and isinstance(left.func, ast.Name) and left.func.id in ("size", "len"):
                (n,) = self.const(right)
                ops = {ast.Eq: "eq", ast.Gt: "gt", ast.Lt: "lt", ast.GtE: "ge", ast.LtE: "le"}
                return "(count %s %s %s)" % (self.kwname(left.args[0]), ops[type(op)], n)
            # K[0:n] == 'X': the value starts with X
            if isinstance(left, ast.Subscript) and isinstance(left.slice, ast.Slice) and isinstance(op, (ast.Eq, ast.NotEq)):
                sl = left.slice
                if sl.lower is None or (isinstance(sl.lower, ast.Constant) and sl.lower.value == 0):
                    (v,) = self.const(right)
                    if isinstance(sl.upper, ast.Constant) and sl.upper.value == len(v):
                        return wrap("(prefix %s %s)" % (self.kwname(left.value), lit(v)))
            # K[0][a:] == K[1][a:]: the first two values agree from character a on
            if (
                isinstance(left, ast.Subscript)
                and isinstance(right, ast.Subscript)
                and isinstance(op, ast.Eq)
                and isinstance(left.slice, ast.Slice)
                and ast.unparse(left.value).replace("[0]", "[1]") == ast.unparse(right.value)
                and ast.unparse(left.slice) == ast.unparse(right.slice)
                and left.slice.upper is None
            ):
                return "(same_tail %s %d)" % (self.kwname(left.value.value), left.slice.lower.value)
            # value("K") == v, value("K") in (...)
            if isinstance(op, (ast.Eq, ast.NotEq, ast.In, ast.NotIn)):
                return wrap("(eq %s %s)" % (self.kwname(left), " ".join(lit(v) for v in self.const(right))))
            # abs(first value of K) < v
            if isinstance(op, ast.Lt) and isinstance(left, ast.Call) and getattr(left.func, "id", "") == "abs":
                names = {n.id for n in ast.walk(left.args[0]) if isinstance(n, ast.Name)} - {"type", "list", "tuple"}
                if len(names) == 1:
                    (v,) = self.const(right)
                    return "(abs_lt %s %s)" % (names.pop(), lit(float(v)))
        raise Untranslatable(ast.unparse(node))

    def translate(self, text):
        return self.tr(ast.parse(textwrap.dedent(text).strip(), mode="eval"))


# ------------------------------------------------------------------ result types


class ProdTranslator:
    """Translate an `sd_prod` function into cases `case COND KIND` (first match wins).

    Only the function's leading sequence of `if COND: return T` (and `if args.get("__all__")`) is
    translated; the first statement outside those patterns ends the translation."""

    def __init__(self, ds_names, params):
        self.ds = ds_names
        self.params = params
        self.ct = CondTranslator(ds_names)
        self.aliases = {}

    def name_of(self, node):
        """A keyword named by a parameter, `args["K"]`, `args.get("K")`, `K[0]["F"]`, or a local
        variable holding one of these."""
        if isinstance(node, ast.Name) and node.id in self.aliases:
            return self.aliases[node.id]
        if isinstance(node, ast.Name) and node.id in self.params:
            return node.id
        if isinstance(node, ast.Subscript) and isinstance(node.value, ast.Name) and node.value.id in ("args", "kargs", "kwargs"):
            if isinstance(node.slice, ast.Constant):
                return node.slice.value
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "get":
            if isinstance(node.func.value, ast.Name) and node.func.value.id in ("args", "kargs", "kwargs"):
                return node.args[0].value
        if isinstance(node, ast.Subscript) and isinstance(node.slice, ast.Constant) and isinstance(node.slice.value, str):
            inner = node.value
            if isinstance(inner, ast.Subscript) and isinstance(inner.slice, ast.Constant) and inner.slice.value == 0:
                return "%s/%s" % (self.name_of(inner.value), node.slice.value)
        raise Untranslatable(ast.unparse(node))

    def cond(self, node):
        if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.BitAnd, ast.BitOr)):
            op = "and" if isinstance(node.op, ast.BitAnd) else "or"
            return "(%s %s %s)" % (op, self.cond(node.left), self.cond(node.right))
        if isinstance(node, ast.BoolOp):
            op = "and" if isinstance(node.op, ast.And) else "or"
            return "(%s %s)" % (op, " ".join(self.cond(v) for v in node.values))
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.Not):
            return "(not %s)" % self.cond(node.operand)
        if isinstance(node, ast.Compare) and len(node.ops) == 1:
            left, op, right = node.left, node.ops[0], node.comparators[0]
            if isinstance(right, ast.Constant) and right.value is None and isinstance(op, (ast.Is, ast.IsNot)):
                s = "(set %s)" % self.name_of(left)
                return s if isinstance(op, ast.IsNot) else "(not %s)" % s
            neg = isinstance(op, (ast.NotEq, ast.NotIn))
            wrap = (lambda s: "(not %s)" % s) if neg else (lambda s: s)
            if isinstance(left, ast.Call) and isinstance(left.func, ast.Name) and left.func.id == "AsType":
                return wrap("(type %s %s)" % (self.name_of(left.args[0]), " ".join(self.ct.kinds(right))))
            if isinstance(op, (ast.Eq, ast.NotEq, ast.In, ast.NotIn)):
                if isinstance(left, ast.Subscript) and isinstance(left.slice, ast.Slice):
                    sl = left.slice
                    (v,) = self.ct.const(right)
                    if sl.lower is None and isinstance(sl.upper, ast.Constant) and sl.upper.value == len(v):
                        return wrap("(prefix %s %s)" % (self.name_of(left.value), lit(v)))
                    raise Untranslatable(ast.unparse(node))
                return wrap("(eq %s %s)" % (self.name_of(left), " ".join(lit(v) for v in self.ct.const(right))))
        # a bare keyword: present (and not empty)
        return "(set %s)" % self.name_of(node)

    def result(self, node):
        if node is None:
            return "none"
        if isinstance(node, ast.Name) and node.id in self.ds:
            return "DataStructure" if node.id == "ASSD" else node.id
        if isinstance(node, ast.Constant) and node.value is None:
            return "none"
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "AsType":
            return "typeof:%s" % self.name_of(node.args[0])
        raise Untranslatable(ast.unparse(node))

    def is_all_guard(self, test):
        s = ast.unparse(test)
        return s in ('args.get("__all__")', "args.get('__all__')", 'kargs.get("__all__")', 'kwargs.get("__all__")')

    def body(self, stmts, guard, out):
        """Translate statements under the conditions `guard`; True when the block always returns."""
        for st in stmts:
            if isinstance(st, ast.Expr) and isinstance(st.value, ast.Constant):
                continue  # docstring
            if isinstance(st, ast.If) and self.is_all_guard(st.test):
                continue
            if isinstance(st, ast.Assign) and len(st.targets) == 1 and isinstance(st.targets[0], ast.Name) and not guard:
                # `x = args["K"]`: a local name for a keyword
                self.aliases[st.targets[0].id] = self.name_of(st.value)
                continue
            if isinstance(st, ast.Return):
                out.append((guard, self.result(st.value)))
                return True
            if isinstance(st, ast.Raise):
                out.append((guard, "error"))
                return True
            if isinstance(st, ast.If):
                c = self.cond(st.test)
                self.body(st.body, guard + [c], out)
                if st.orelse:
                    if self.body(st.orelse, guard + ["(not %s)" % c], out):
                        # both branches handled: nothing after the if is reached through it
                        pass
                continue
            raise Untranslatable(ast.unparse(st).splitlines()[0])
        return False

    def translate(self, func):
        tree = ast.parse(textwrap.dedent(inspect.getsource(func)))
        fdef = tree.body[0]
        out = []
        try:
            self.body(fdef.body, [], out)
            complete = True
        except Untranslatable:
            complete = False
        cases = []
        for guard, res in out:
            c = guard[0] if len(guard) == 1 else ("(and %s)" % " ".join(guard) if guard else "(true)")
            cases.append((c, res))
        return cases, complete


def co_types_from_source(func, ds_names):
    """`self.type_sdprod(KW, T)` calls: the types given to CO() results, by keyword."""
    out = {}
    if not isinstance(func, types.FunctionType):
        return out
    tree = ast.parse(textwrap.dedent(inspect.getsource(func)))
    for n in ast.walk(tree):
        if isinstance(n, ast.Call) and isinstance(n.func, ast.Attribute) and n.func.attr == "type_sdprod" and len(n.args) == 2:
            kw, t = n.args
            name = None
            if isinstance(kw, ast.Name):
                name = kw.id
            elif isinstance(kw, ast.Subscript) and isinstance(kw.slice, ast.Constant):
                name = kw.slice.value
            if name and isinstance(t, ast.Name) and t.id in ds_names:
                out.setdefault(name, set()).add(t.id)
    return out


# ------------------------------------------------------------------ emitting


class Emitter:
    def __init__(self, mods, ds_names):
        self.commandStore, self.DS, self.SO, self.RU, self.VA = mods
        self.ds_names = ds_names
        self.ct = CondTranslator(ds_names)
        self.lines = []
        self.co_types = {}
        self.co_default = []

    def w(self, depth, text):
        self.lines.append("  " * depth + text)

    def typename(self, t):
        DS = self.DS
        if isinstance(t, str):
            m = {"R": "R", "I": "I", "C": "C", "TXM": "T"}
            if t in m:
                return m[t]
            raise Untranslatable("type %r" % t)
        if isinstance(t, type):
            if issubclass(t, DS.UnitBaseType):
                return "unit"
            if issubclass(t, (DS.GEOM,)) or (hasattr(DS, "MeshEntity") and issubclass(t, DS.MeshEntity)):
                return "T"
            if t is DS.not_checked:
                return "any"
            if t is DS.CO:
                return "CO"
            if issubclass(t, DS.DataStructure):
                name = t.__name__
                return "co:" + ("DataStructure" if name in ("ASSD", "DataStructure") else name)
        raise Untranslatable("type %r" % (t,))

    def types(self, name, typ):
        ts = list(typ) if isinstance(typ, (list, tuple)) else [typ]
        names = [self.typename(t) for t in ts]
        kinds = [n[3:] for n in names if n.startswith("co:")]
        out = []
        cos = []
        for n in names:
            if n.startswith("co:"):
                cos.append(n[3:])
            elif n == "CO":
                new = kinds or sorted(self.co_types.get(name, ())) or self.co_default or ["DataStructure"]
                out.append("new:" + ",".join(new))
            else:
                out.append(n)
        if cos:
            out.insert(0, "co:" + ",".join(cos))
        return " ".join(out)

    def card(self, d, default_max=1):
        mn = d.get("min")
        mx = d.get("max", default_max)
        mx = "*" if mx == "**" else mx
        if mn is None and mx == 1:
            return ""
        return " n=%s..%s" % (1 if mn is None else mn, mx)

    def validator(self, v):
        VA = self.VA
        n = type(v).__name__
        if n == "NoRepeat":
            return "norepeat"
        if n == "OrdList":
            return "ordered_desc" if v._predicate.keywords.get("reverse") else "ordered"
        if n == "LongStr":
            return "len=%d..%d" % (v.args[0], v.args[1])
        if n in ("Compulsory", "Together", "Absent"):
            names = v.args[0] if isinstance(v.args[0], (list, tuple)) else v.args
            key = {"Compulsory": "has_all", "Together": "together", "Absent": "has_none"}[n]
            return "(%s %s)" % (key, " ".join(lit(x) for x in names))
        if n == "AtMostOneStartsWith":
            return "(one_prefix %s)" % lit(v.args[0])
        if n in ("AndVal", "OrVal"):
            parts = [self.validator(x) for x in v.args]
            tag = "and" if n == "AndVal" else "or"
            return "(%s %s)" % (tag, " ".join(p if p.startswith("(") else "(%s)" % p for p in parts))
        raise Untranslatable("validator %s" % n)

    def simp(self, depth, name, kw):
        d = kw.definition
        statut = d.get("statut", "f")
        statut = {"o": "o", "f": "f", "c": "f", "d": "f"}[statut]
        line = "s %s %s %s" % (name, statut, self.types(name, d["typ"]))
        line += self.card(d)
        if "defaut" in d and d["defaut"] is not None:
            line += " d=" + lits(d["defaut"])
        if "into" in d and d["into"] is not None:
            line += " into=" + lits(d["into"])
        if d.get("val_min") is not None:
            line += " lo=" + lit(d["val_min"])
            if d.get("val_min_included") is False:
                line += " lo_open"
        if d.get("val_max") is not None:
            line += " hi=" + lit(d["val_max"])
            if d.get("val_max_included") is False:
                line += " hi_open"
        vals = d.get("validators")
        if vals is not None:
            vals = vals if isinstance(vals, (list, tuple)) else [vals]
            checks = []
            for v in vals:
                s = self.validator(v)
                if type(v).__name__ == "AndVal" and all(type(x).__name__ in ("NoRepeat", "OrdList", "LongStr") for x in v.args):
                    checks.extend(self.validator(x) for x in v.args)
                else:
                    checks.append(s)
            for c in checks:
                line += " " + (("check" + c) if c.startswith("(") else c)
        self.w(depth, line)

    def rules(self, depth, obj):
        names = {
            "AtLeastOne": "at_least_one",
            "ExactlyOne": "exactly_one",
            "AtMostOne": "at_most_one",
            "IfFirstAllPresent": "present_present",
            "OnlyFirstPresent": "present_absent",
            "AllTogether": "together",
            "NotEmpty": "not_empty",
        }
        for r in obj.rules:
            line = "rule %s %s" % (names[type(r).__name__], " ".join(r.ruleArgs))
            for k, v in (getattr(r, "ruleKwargs", None) or {}).items():
                line += " default %s=%s" % (k, lit(v))
            self.w(depth, line.rstrip())

    def entries(self, depth, obj):
        SO = self.SO
        self.rules(depth, obj)
        for name, kw in obj.definition.items():
            if isinstance(kw, SO.SimpleKeyword):
                self.simp(depth, name, kw)
            elif isinstance(kw, SO.FactorKeyword):
                d = kw.definition
                statut = {"o": "o", "f": "f", "d": "d", "c": "f"}[d.get("statut", "f")]
                self.w(depth, "f %s %s%s {" % (name, statut, self.card(d)))
                self.entries(depth + 1, kw)
                self.w(depth, "}")
            elif isinstance(kw, SO.Bloc):
                cond = self.ct.translate(kw.getCondition())
                self.w(depth, "b %s {" % cond)
                self.entries(depth + 1, kw)
                self.w(depth, "}")

    def command(self, name, cmd, description):
        SO = self.SO
        d = cmd.definition
        kind = {SO.Operator: "oper", SO.Macro: "macro", SO.Procedure: "proc", SO.Formule: "form"}[type(cmd)]
        reentr = d.get("reentrant", "n").split(":")[0]
        sd_prod = d.get("sd_prod")
        self.co_types = co_types_from_source(sd_prod, self.ds_names)
        self.co_default = []
        head = "command %s %s" % (name, kind)
        if reentr in ("o", "f"):
            head += " reuse"
        self.w(0, head)
        self.w(1, "doc " + lit(description))
        if sd_prod is None:
            self.w(1, "produces none")
        elif isinstance(sd_prod, type):
            self.w(1, "produces %s" % self.kindname(sd_prod))
        else:
            alltypes = cmd.get_all_types()
            main = alltypes
            if alltypes and isinstance(alltypes[0], (list, tuple)):
                main = alltypes[0]
                extra = set()
                for lst in alltypes[1:]:
                    extra.update(self.kindname(t) for t in lst if t is not None)
                self.co_default = sorted(extra)
            main_names = [self.kindname(t) for t in main if t is not None]
            # Code_Aster's result-type functions return the base type ASSD to make an invalid call fail
            # later: it is not a type a valid call produces.
            if len(main_names) > 1:
                main_names = [n for n in main_names if n != "DataStructure"]
            params = list(inspect.signature(sd_prod).parameters)
            cases, complete = ProdTranslator(self.ds_names, params).translate(sd_prod)
            if main_names:
                self.w(1, "produces one_of %s" % " ".join(dict.fromkeys(main_names)))
            elif None in main:
                self.w(1, "produces none")
            for c, r in cases:
                if r == "error":
                    continue
                self.w(1, "case %s %s" % (c, r))
            if not complete:
                self.w(1, "# the rest of Code_Aster's result-type function is not translated: one of the types above")
        self.entries(1, cmd)
        self.w(0, "end")
        self.w(0, "")

    def kindname(self, t):
        if isinstance(t, str):
            return t
        n = t.__name__
        return "DataStructure" if n in ("ASSD", "DataStructure") else n


# ------------------------------------------------------------------ concept kinds


SPECIAL_VARIANTS = {"listr8_sdaster": "ListR8", "listis_sdaster": "ListIs", "table_sdaster": "Table", "CO": "Co"}


def variant(name):
    if name in SPECIAL_VARIANTS:
        return SPECIAL_VARIANTS[name]
    base = name[: -len("_sdaster")] if name.endswith("_sdaster") else name
    return "".join(p[:1].upper() + p[1:] for p in base.split("_"))


def write_kinds(DS, path):
    classes = []
    for name, obj in vars(DS).items():
        if inspect.isclass(obj) and issubclass(obj, DS.DataStructure) and obj.__module__ == DS.__name__:
            if name in ("ASSD", "PythonVariable", "not_checked"):
                continue
            classes.append((name, obj))
    rows = []
    for name, obj in classes:
        parent = None
        for b in obj.__bases__:
            if issubclass(b, DS.DataStructure) and b.__name__ not in ("PythonVariable",):
                parent = b.__name__
        rows.append((name, parent))
    out = []
    out.append("//! The types of concepts (Code_Aster's data structures) and their hierarchy: a keyword that")
    out.append("//! accepts a type accepts its subtypes (`cham_no_sdaster` is a `cham_gd_sdaster`).")
    out.append("//!")
    out.append("//! Generated by `scripts/extract_catalogue.py` from Code_Aster's `Cata/Language/DataStructure.py`;")
    out.append("//! do not edit by hand.")
    out.append("")
    out.append("/// A concept type, named as Code_Aster names it (`ConceptKind::aster_name`).")
    out.append("#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]")
    out.append("pub enum ConceptKind {")
    for name, _ in rows:
        out.append("    %s," % variant(name))
    out.append("}")
    out.append("")
    out.append("/// Every kind: (kind, Code_Aster name, parent).")
    out.append("pub const KINDS: &[(ConceptKind, &str, Option<ConceptKind>)] = &[")
    for name, parent in rows:
        p = "None" if parent is None else "Some(ConceptKind::%s)" % variant(parent)
        out.append('    (ConceptKind::%s, "%s", %s),' % (variant(name), name, p))
    out.append("];")
    out.append("")
    with open(path, "w") as f:
        f.write("\n".join(out))
    subprocess.run(["rustfmt", "--edition", "2021", path], check=False)
    return [n for n, _ in rows]


# ------------------------------------------------------------------ hand-written schemas


def hand_written():
    names = set()
    cdir = os.path.join(ROOT, "src/catalog/commands")
    for dirpath, _, files in os.walk(cdir):
        for f in files:
            if f.endswith(".rs"):
                with open(os.path.join(dirpath, f)) as fh:
                    names.update(re.findall(r'Command::new\(\s*"([A-Z0-9_]+)"', fh.read()))
    return names


def flatten(text):
    """Facts of one schema text as {path: description}, blocks folded into their level."""
    out = {}
    stack = []
    for line in text.splitlines():
        t = line.strip()
        if not t or t.startswith("#"):
            continue
        if t == "}":
            stack.pop()
            continue
        head = t.split()[0]
        if head == "f":
            name = t.split()[1]
            path = "/".join([p for p in stack if p] + [name])
            out.setdefault(path, "factor " + " ".join(t.split()[2:-1]))
            stack.append(name)
        elif head == "b":
            stack.append("")
        elif head == "s":
            parts = t.split(None, 2)
            path = "/".join([p for p in stack if p] + [parts[1]])
            prev = out.get(path)
            desc = parts[2] if len(parts) > 2 else ""
            out[path] = desc if prev is None or prev == desc else prev + " | " + desc
    return out


def compare(name, ours, theirs):
    a, b = flatten(ours), flatten(theirs)
    only_ours = sorted(set(a) - set(b))
    only_theirs = sorted(set(b) - set(a))
    differ = sorted(k for k in set(a) & set(b) if norm(a[k]) != norm(b[k]))
    return only_ours, only_theirs, [(k, a[k], b[k]) for k in differ]


def norm(desc):
    # Facts our validator does not carry yet are left out of the comparison of hand-written schemas.
    d = re.sub(r" check\(.*", "", desc)
    d = re.sub(r" (norepeat|ordered|len=\S+|lo_open|hi_open)", "", d)
    return d.strip()


def our_schema(name):
    exe = os.path.join(ROOT, "target/release/aster")
    r = subprocess.run([exe, "catalog", "--schema", name, "--hand-written"], capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit("aster catalog --schema %s failed: %s" % (name, r.stderr))
    return r.stdout


# ------------------------------------------------------------------ main


def read_descriptions():
    out = {}
    if os.path.exists(DESCRIPTIONS):
        with open(DESCRIPTIONS) as f:
            for line in f:
                line = line.rstrip("\n")
                if not line or line.startswith("#"):
                    continue
                k, _, v = line.partition(" ")
                out[k] = v.strip()
    return out


def main():
    # Code_Aster builds some `into` lists from sets, whose order follows Python's string hashing: fix
    # the hash seed so that the output does not change from run to run.
    if os.environ.get("PYTHONHASHSEED") != "0":
        os.execve(sys.executable, [sys.executable] + sys.argv, dict(os.environ, PYTHONHASHSEED="0"))
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("cata_root", help="folder holding code_aster/Cata")
    ap.add_argument("--version", default="", help="the version of Code_Aster, for the header")
    ap.add_argument("--no-compare", action="store_true", help="do not compare the hand-written schemas")
    opts = ap.parse_args()
    mods = load(opts.cata_root)
    commandStore, DS = mods[0], mods[1]
    kinds = write_kinds(DS, OUT_KINDS)
    em = Emitter(mods, set(kinds) | {"ASSD", "DataStructure"})
    desc = read_descriptions()
    hand = hand_written()
    em.w(0, "# The command schemas taken from Code_Aster's catalogue (%s): facts only." % (opts.version or "code_aster/Cata"))
    em.w(0, "# Generated by scripts/extract_catalogue.py; do not edit by hand. The format is described in")
    em.w(0, "# src/catalog/generated.rs. Where a command also has a hand-written schema (src/catalog/commands/), that")
    em.w(0, "# one is the source of truth: this one completes it for `aster check` (see src/catalog/merge.rs).")
    em.w(0, "")
    missing_desc = []
    theirs = {}
    for name in sorted(commandStore):
        cmd = commandStore[name]
        if not hasattr(cmd, "definition"):
            continue  # VARIABLE: a Python helper, not a command
        if name not in desc and name not in hand:
            missing_desc.append(name)
        start = len(em.lines)
        em.command(name, cmd, desc.get(name, ""))
        if name in hand:
            theirs[name] = "\n".join(em.lines[start:])
    if missing_desc:
        print("no description for: %s" % " ".join(missing_desc), file=sys.stderr)
    os.makedirs(os.path.dirname(OUT_CATA), exist_ok=True)
    with open(OUT_CATA, "w") as f:
        f.write("\n".join(em.lines).rstrip() + "\n")
    print("wrote %s (%d commands, %d of them with a hand-written schema)" % (OUT_CATA, len(commandStore) - 1, len(theirs)))
    if not opts.no_compare:
        write_comparison(theirs, hand, opts.version)


def write_comparison(theirs, hand, version):
    out = []
    out.append("# The catalogue: generated and hand-written schemas")
    out.append("")
    out.append("Generated by `scripts/extract_catalogue.py`; do not edit by hand.")
    out.append("")
    out.append("Every command of Code_Aster's catalogue (%s) has a schema in aster-rs. Most are" % (version or "2025"))
    out.append("generated from Code_Aster's facts (`src/catalog/generated/commands.cata`); the commands that have a stage")
    out.append("keep their hand-written schema (`src/catalog/commands/`), which is the source of truth. This page lists,")
    out.append("for each hand-written schema, where it differs from Code_Aster's facts: keywords Code_Aster has that")
    out.append("ours does not (a file using them stops at `aster check` with the keyword named), keywords only ours")
    out.append("has (older spellings kept for the files that use them), and keywords whose type, status, number of")
    out.append("values, default or allowed values differ (ours first). Keyword notation as in the schema format:")
    out.append("`s NAME o|f TYPES n=min..max d=default into=values lo=/hi=bounds`.")
    out.append("")
    only_cata = sorted(n for n in hand if n not in theirs)
    if only_cata:
        out.append("Hand-written commands that Code_Aster 2025 does not have: %s." % ", ".join(only_cata))
        out.append("")
    for name in sorted(theirs):
        only_ours, only_theirs, differ = compare(name, our_schema(name), theirs[name])
        out.append("## %s" % name)
        out.append("")
        if not (only_ours or only_theirs or differ):
            out.append("Same keywords and facts.")
            out.append("")
            continue
        if only_theirs:
            out.append("Code_Aster's keywords we do not have (%d): %s." % (len(only_theirs), ", ".join("`%s`" % k for k in only_theirs)))
            out.append("")
        if only_ours:
            out.append("Only ours (%d): %s." % (len(only_ours), ", ".join("`%s`" % k for k in only_ours)))
            out.append("")
        if differ:
            out.append("Facts that differ (%d):" % len(differ))
            out.append("")
            for k, a, b in differ:
                out.append("- `%s`: ours `%s`, Code_Aster `%s`" % (k, a, b))
            out.append("")
    with open(OUT_DOC, "w") as f:
        f.write("\n".join(out).rstrip() + "\n")
    print("wrote %s" % OUT_DOC)


if __name__ == "__main__":
    main()
