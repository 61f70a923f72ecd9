#!/usr/bin/env python3
"""Stability sweep of X-FEM cuttings (issue 10, point 4; docs/stability.md).

Small boxes of every cell family `aster mesh box` makes (2D: QUAD8, QUAD4, TRIA3, TRIA6, 4x4 cells of
size h = 1; 3D: HEXA20, HEXA8, TETRA4, TETRA10, PENTA6, PENTA15, 2x2x2) are cut by straight interfaces
and compressed equally along every axis, so that u_i = U (1 - X_i/L) is the answer on both sides.
Every node of the mesh and of the visual mesh is checked to 1e-8 U. Scenes:

- glued: one interface glued by the cohesive law (CZM_LIN_MIX, mortar, ORDRE_INT=4 in 2D, 5 in 3D) at
  10^-k h from a row of nodes, k = 1..14, and through it (k = inf), for three rows:
    row12: Y = X/2 (3D: Z = X/2), vertices and mid-side nodes alternately;
    diag:  X + Y (+ Z) = 2, through vertices (and mid-side nodes in 3D);
    axis:  X = 1, along a row (plane) of nodes, i.e. 10^-k h from a row of edges (faces);
- lips: the same cuts with free lips loaded by the exact field's pressure (PRES_REP FISSURE, no
  contact): a check of the sub-cells, their sides, the facets and the lips' load that the glued scene
  (whose multipliers can absorb a wrong facet integral) does not make;
- junction: FISS2 branching off FISS1, both through the node (2, 2) (3D: the row (1, y, 1)) shifted by
  10^-k h along their normals: the junction point 10^-k h from the node;
- tilt: the interface through the node row X = 1 tilted by 10^-j rad, j = 1..8 (glued and lips);
- uncut: the box without interface, the reference of the condition estimates (scaled condition =
  condition / uncut condition);
- PENA_LAGR = 1e-3 .. 1e6 and E = 1 .. 1e12 (SIGM_C and GC scaled with E: a change of the stress unit),
  rows row12 and diag at k = 1, 6, 12, on every family.

Writes the plots docs/stability/{error,condition,lips,lips_condition,junction,tilt}.svg and the data target/stability/
(sweep.csv, params.csv, table.md, params.md); docs/stability.md quotes the tables.

    cargo build --release && python3 scripts/stability_sweep.py [FAMILY ...]
"""
import csv
import math
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ASTER = os.path.join(ROOT, "target/release/aster")
OUT = os.path.join(ROOT, "docs/stability")
DATA = os.path.join(ROOT, "target/stability")
U = 1.0e-4

HEAD = """DEBUT(CODE="OUI")
U = 1.0e-4
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MA = DEFI_GROUP(reuse=MA, MAILLAGE=MA, CREA_GROUP_NO=_F(GROUP_MA="{group}"))
ROCHE = DEFI_MATERIAU(ELAS=_F(E={young!r}, NU=0.2), RUPT_FRAG=_F(GC={gc!r}, SIGM_C={sigc!r}, PENA_LAGR={pena!r}))
LINST = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=_F(JUSQU_A=1.0, NOMBRE=1))
{checks}"""

XFEM = """LN = FORMULE(VALE="{phi}", NOM_PARA={para})
MO0 = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(GROUP_MA="{group}", PHENOMENE="MECANIQUE", MODELISATION="{model}"))
FISS = DEFI_FISS_XFEM(MAILLAGE=MA, TYPE_DISCONTINUITE="INTERFACE", DEFI_FISS=_F(FONC_LN=LN))
{branch}MO = MODI_MODELE_XFEM(MODELE_IN=MO0, FISSURE={cracks}, DECOUPE_FACETTE="SOUS_ELEMENTS"{mortar})
{contact}CHMAT = AFFE_MATERIAU(MAILLAGE=MA, MODELE=MO, AFFE=_F(TOUT="OUI", MATER=ROCHE))
BLOC = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=({bounds}))
{load}RESU = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT={excit},{ctx}
                     COMPORTEMENT=_F(RELATION="ELAS"), INCREMENT=_F(LIST_INST=LINST),
                     CONVERGENCE=_F(RESI_GLOB_RELA=1.0e-10))
MAVISU = POST_MAIL_XFEM(MODELE=MO)
MAVISU = DEFI_GROUP(reuse=MAVISU, MAILLAGE=MAVISU, CREA_GROUP_NO=_F(GROUP_MA="{group}"))
MOVISU = AFFE_MODELE(MAILLAGE=MAVISU, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="{model}"))
RESVISU = POST_CHAM_XFEM(MODELE_VISU=MOVISU, RESULTAT=RESU)
RESULTS = (RESU, RESVISU)
"""

UNCUT = """MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(GROUP_MA="{group}", PHENOMENE="MECANIQUE", MODELISATION="{model}"))
CHMAT = AFFE_MATERIAU(MAILLAGE=MA, MODELE=MO, AFFE=_F(TOUT="OUI", MATER=ROCHE))
BLOC = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=({bounds}))
RESU = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=BLOC),
                     COMPORTEMENT=_F(RELATION="ELAS"), INCREMENT=_F(LIST_INST=LINST),
                     CONVERGENCE=_F(RESI_GLOB_RELA=1.0e-10))
RESULTS = (RESU,)
"""

TAIL = """for res in RESULTS:
    DEP = POST_RELEVE_T(ACTION=_F(INTITULE="N", GROUP_NO="{group}", RESULTAT=res, NOM_CHAM="DEPL", NUME_ORDRE=1,
                                  NOM_CMP=({cmps}), OPERATION="EXTRACTION"))
    DEP = CALC_TABLE(reuse=DEP, TABLE=DEP, ACTION=({opers}))
    for cmp in ({errs}):
        for typ in ("MAX", "MIN"):
            TEST_TABLE(TABLE=DEP, NOM_PARA=cmp, TYPE_TEST=typ, CRITERE="ABSOLU", PRECISION=1.0e-8,
                       VALE_CALC=0.0, VALE_REFE=0.0, REFERENCE="ANALYTIQUE", ORDRE_GRANDEUR=1.0)
FIN()
"""

FAMILIES = ["QUAD8", "QUAD4", "TRIA3", "TRIA6", "HEXA20", "HEXA8", "TETRA4", "TETRA10", "PENTA6", "PENTA15"]
# `python3 scripts/stability_sweep.py TRIA3 TETRA4` sweeps those families only (exploration: the
# tables and plots are then of those families alone).
if len(sys.argv) > 1:
    FAMILIES = [c for c in FAMILIES if c in sys.argv[1:]]
CELLS = {c: ((2, "4,4", "4,4", 4.0) if c in ("QUAD8", "QUAD4", "TRIA3", "TRIA6") else (3, "2,2,2", "2,2,2", 2.0))
         for c in FAMILIES}
ROWS = {
    2: {"row12": "(Y-0.5*X)/1.118033988749895", "diag": "(X+Y-2.0)/1.4142135623730951", "axis": "X-1.0"},
    3: {"row12": "(Z-0.5*X)/1.118033988749895", "diag": "(X+Y+Z-2.0)/1.7320508075688772", "axis": "X-1.0"},
}
# Junction: FISS1 and FISS2 through the node (2, 2) (3D: the row (1, y, 1)), FISS2 on FISS1's + side
# (POINT).
JUNCTION = {
    2: ("(Y-0.5*X-1.0)/1.118033988749895", "(Y+0.7*X-3.4)/1.2206555615733703", "(1.0, 4.0)"),
    3: ("(Z-0.5*X-0.5)/1.118033988749895", "(Z+0.7*X-1.7)/1.2206555615733703", "(1.0, 1.0, 2.0)"),
}
KS = list(range(1, 15)) + [math.inf]
ANGLES = list(range(1, 9))


# Unequal strains (the "aniso" scene): u_i = s_i U (1 − X_i/L), so that the stress is not a pressure and the
# traction on an inclined interface has a tangential part.
STRAINS = {"X": 1.0, "Y": 2.0, "Z": 3.0}


def scene(dim, length, phi, young=5.8e9, pena=100.0, variant="glued", phi2=None):
    """The command file of one run. variant: glued | aniso (glued, unequal strains) | lips | uncut; phi2:
    FISS2 (a junction)."""
    if variant == "aniso":
        text = scene(dim, length, phi, young, pena, "glued", phi2)
        for x, f in STRAINS.items():
            text = text.replace(f"(D{x} - U*(1.0 - COOR_{x}/", f"(D{x} - {f!r}*U*(1.0 - COOR_{x}/")
            text = re.sub(rf"\bD{x}=U([,)])", rf"D{x}={f!r}*U\1", text)
        return text
    if dim == 2:
        model, group, para = "D_PLAN", "SURFACE", '["X", "Y"]'
        sides = [("GAUCHE", "DROITE", "X"), ("BAS", "HAUT", "Y")]
    else:
        model, group, para = "3D", "VOLUME", '["X", "Y", "Z"]'
        sides = [("XMIN", "XMAX", "X"), ("YMIN", "YMAX", "Y"), ("ZMIN", "ZMAX", "Z")]
    xs = [x for _, _, x in sides]
    checks = "".join(f'E{x} = FORMULE(VALE="(D{x} - U*(1.0 - COOR_{x}/{length}))/U", U=U, '
                     f'NOM_PARA=["D{x}", "COOR_{x}"])\n' for x in xs)
    # A change of the stress unit scales E, SIGM_C and GC (a stress times a length) alike.
    s = young / 5.8e9
    text = HEAD.format(group=group, young=young, gc=9.0e3 * s, sigc=5.0e5 * s, pena=pena, checks=checks)
    if variant == "uncut":
        bounds = ", ".join(f'_F(GROUP_MA="{lo}", D{x}=U), _F(GROUP_MA="{hi}", D{x}=0.0)' for lo, hi, x in sides)
        text += UNCUT.format(group=group, model=model, bounds=bounds)
    else:
        heav = ", H2{x}=0.0" if phi2 else ""
        bounds = ", ".join(f'_F(GROUP_MA="{lo}", D{x}=U, H1{x}=0.0{heav.format(x=x)}), '
                           f'_F(GROUP_MA="{hi}", D{x}=0.0, H1{x}=0.0{heav.format(x=x)})' for lo, hi, x in sides)
        # Facet rule: 4 Gauss points (degree 7) in 2D, FPG7 (degree 5) in 3D (tests/it/xfem/property.rs).
        order = 4 if dim == 2 else 5
        zone = ('_F(FISS_MAIT={f}, INTEGRATION="GAUSS", ORDRE_INT=%d, ALGO_CONT="CZM", ALGO_LAGR="VERSION2", '
                'RELATION="CZM_LIN_MIX")' % order)
        branch, cracks = "", "FISS"
        if phi2:
            point = JUNCTION[dim][2]
            branch = (f'LN2 = FORMULE(VALE="{phi2}", NOM_PARA={para})\n'
                      f'FISS2 = DEFI_FISS_XFEM(MAILLAGE=MA, TYPE_DISCONTINUITE="INTERFACE", '
                      f'DEFI_FISS=_F(FONC_LN=LN2), JONCTION=_F(FISSURE=FISS, POINT={point}))\n')
            cracks = "(FISS, FISS2)"
        if variant == "glued":
            zones = zone.format(f="FISS") if not phi2 else f'({zone.format(f="FISS")}, {zone.format(f="FISS2")})'
            contact = f'CTX = DEFI_CONTACT(MODELE=MO, FORMULATION="XFEM", ZONE={zones})\n'
            mortar, load, excit, ctx = ', CONTACT="MORTAR"', "", "_F(CHARGE=BLOC)", " CONTACT=CTX,"
        else:
            # σ = −p I: p = E/((1+ν)(1−2ν))·U/L in plane strain, E/(1−2ν)·U/L in 3D.
            p = young / ((1.2 if dim == 2 else 1.0) * 0.6) * U / length
            contact, mortar, ctx = "", "", ""
            load = f"PR = AFFE_CHAR_MECA(MODELE=MO, PRES_REP=_F(FISSURE={cracks}, PRES={p!r}))\n"
            excit = "(_F(CHARGE=BLOC), _F(CHARGE=PR))"
        text += XFEM.format(phi=phi, para=para, group=group, model=model, branch=branch, cracks=cracks,
                            mortar=mortar, contact=contact, bounds=bounds, load=load, excit=excit, ctx=ctx)
    text += TAIL.format(group=group, cmps=", ".join(f'"D{x}"' for x in xs),
                        errs=", ".join(f'"ERR_{x}"' for x in xs),
                        opers=", ".join(f'_F(OPERATION="OPER", FORMULE=E{x}, NOM_PARA="ERR_{x}")' for x in xs))
    return text


def run(work, cell, mesh, text, **tags):
    comm = os.path.join(work, "case.comm")
    with open(comm, "w") as f:
        f.write(text)
    out = os.path.join(work, "out")
    subprocess.run([ASTER, "run", comm, "--unit", f"20={mesh}", "--out", out, "-q"], capture_output=True)
    mess = open(os.path.join(out, "case.mess")).read() if os.path.exists(os.path.join(out, "case.mess")) else ""
    resu_path = os.path.join(out, "case.resu")
    resu = open(resu_path).read() if os.path.exists(resu_path) else ""
    for p in (resu_path, os.path.join(out, "case.mess")):
        if os.path.exists(p):
            os.remove(p)
    diag = re.search(r"DIAGNOSTIC JOB : (\S+)", mess)
    cond = re.search(r"condition estimate ([0-9.eE+-]+)", mess)
    errs = [abs(float(l.split()[4])) for l in resu.splitlines()
            if len(l.split()) >= 5 and l.split()[1] == "ANALYTIQUE"]
    fatal = re.search(r"<F> [^:]*:\d+:\d+: (.*)", mess)
    r = {"cell": cell, **tags, "diagnostic": diag.group(1) if diag else "?",
         "error": max(errs) if errs else float("nan"),
         "condition": float(cond.group(1)) if cond else float("nan"),
         "message": fatal.group(1)[:160] if fatal else ""}
    print(" ".join(f"{v}" for v in tags.values()), f'{cell:7} {r["diagnostic"]:16} err {r["error"]:.2e} '
          f'cond {r["condition"]:.1e} {r["message"]}', flush=True)
    return r


def delta(k):
    return 0.0 if k == math.inf else 10.0 ** -k


def kname(k):
    return "inf" if k == math.inf else k


def fmt(r):
    if r["diagnostic"] == "OK":
        return f'{r["error"]:.1e}'
    if r["diagnostic"] == "NOOK_TEST_RESU":
        return f'**{r["error"]:.1e}**'
    return "**stop**"


COLORS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf", "#7f7f7f",
          "#bcbd22", "#000000", "#aec7e8", "#ff9896", "#98df8a", "#c5b0d5", "#ffbb78", "#c49c94", "#f7b6d2",
          "#9edae5", "#dbdb8d", "#393b79", "#637939", "#8c6d31", "#843c39", "#7b4173", "#3182bd", "#e6550d",
          "#31a354", "#756bb1", "#636363"]


def svg(series, xlabels, title, xtitle, path, ymin, ymax, line=None):
    """series: {label: [(x index, value, ok)]}; log-scale y from 1e{ymin} to 1e{ymax}."""
    w, h, ml, mr, mt, mb = 780, 470, 60, 180, 30, 40
    n = len(xlabels)
    xs = lambda i: ml + (w - ml - mr) * i / max(n - 1, 1)
    ys = lambda v: mt + (h - mt - mb) * (ymax - max(ymin, min(ymax, math.log10(max(v, 1e-300))))) / (ymax - ymin)
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" '
           f'font-size="11">', f'<text x="{ml}" y="18" font-size="13">{title}</text>']
    for e in range(ymin, ymax + 1):
        y = ys(10.0 ** e)
        out.append(f'<line x1="{ml}" y1="{y:.1f}" x2="{w - mr}" y2="{y:.1f}" stroke="#ddd"/>')
        out.append(f'<text x="{ml - 6}" y="{y + 4:.1f}" text-anchor="end">1e{e}</text>')
    for i, lab in enumerate(xlabels):
        out.append(f'<text x="{xs(i):.1f}" y="{h - mb + 15}" text-anchor="middle">{lab}</text>')
    out.append(f'<text x="{(ml + w - mr) / 2}" y="{h - 8}" text-anchor="middle">{xtitle}</text>')
    for j, (label, pts) in enumerate(series.items()):
        c = COLORS[j % len(COLORS)]
        segments, seg = [], []
        for i, v, ok in pts:
            if math.isnan(v) or v <= 0:
                segments.append(seg)
                seg = []
            else:
                seg.append((xs(i), ys(v)))
        segments.append(seg)
        for s in segments:
            if len(s) > 1:
                out.append(f'<polyline fill="none" stroke="{c}" stroke-width="1.5" points="'
                           + " ".join(f"{x:.1f},{y:.1f}" for x, y in s) + '"/>')
        for i, v, ok in pts:
            if math.isnan(v) or v <= 0:
                continue
            x, y = xs(i), ys(v)
            out.append(f'<circle cx="{x:.1f}" cy="{y:.1f}" r="2.5" fill="{c}"/>' if ok else
                       f'<text x="{x:.1f}" y="{y + 4:.1f}" fill="{c}" text-anchor="middle">×</text>')
        ly = mt + 13 * j
        out.append(f'<line x1="{w - mr + 10}" y1="{ly}" x2="{w - mr + 30}" y2="{ly}" stroke="{c}" stroke-width="2"/>')
        out.append(f'<text x="{w - mr + 34}" y="{ly + 4}">{label}</text>')
    if line is not None:
        y = ys(line)
        out.append(f'<line x1="{ml}" y1="{y:.1f}" x2="{w - mr}" y2="{y:.1f}" stroke="#000" stroke-dasharray="4 3"/>')
    out.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def table(rows, xs, xkey, series, cell_fmt, xfmt=str, header=None):
    """Markdown table: one line per x, one column per (cell, tag) in `series` (dicts of tag filters)."""
    lines = ["| " + (header or xkey) + " | " + " | ".join(lab for lab, _ in series) + " |", "|---" * (len(series) + 1) + "|"]
    for x in xs:
        cells = []
        for _, flt in series:
            r = next((q for q in rows if q[xkey] == x and all(q.get(a) == b for a, b in flt.items())), None)
            cells.append("—" if r is None else cell_fmt(r))
        lines.append(f"| {xfmt(x)} | " + " | ".join(cells) + " |")
    return lines + [""]


def kfmt(k):
    return "∞" if k == "inf" else str(k)


def main():
    os.makedirs(OUT, exist_ok=True)
    os.makedirs(DATA, exist_ok=True)
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for cell, (dim, n, size, length) in CELLS.items():
            mesh = os.path.join(work, f"{cell}.med")
            subprocess.run([ASTER, "mesh", "box", "--cell", cell, "--n", n, "--size", size, "-o", mesh],
                           check=True, capture_output=True)
            rows.append(run(work, cell, mesh, scene(dim, length, "", variant="uncut"), scene="uncut", row="", k=""))
            for variant in ("glued", "lips", "aniso"):
                for row, base in ROWS[dim].items():
                    for k in KS:
                        phi = f"{base}-{delta(k)!r}"
                        rows.append(run(work, cell, mesh, scene(dim, length, phi, variant=variant),
                                        scene=variant, row=row, k=kname(k)))
            f1, f2, _ = JUNCTION[dim]
            for k in KS:
                d = delta(k)
                rows.append(run(work, cell, mesh, scene(dim, length, f"{f1}-{d!r}", phi2=f"{f2}-{d!r}"),
                                scene="junction", row="node", k=kname(k)))
            for variant in ("glued", "lips"):
                for j in ANGLES:
                    t = math.tan(10.0 ** -j)
                    other = "Y" if dim == 2 else "Z"
                    phi = f"((X-1.0)-{t!r}*({other}-1.0))/{math.sqrt(1 + t * t)!r}"
                    rows.append(run(work, cell, mesh, scene(dim, length, phi, variant=variant),
                                    scene="tilt-" + variant, row="tilt", k=j))
    with open(os.path.join(DATA, "sweep.csv"), "w", newline="") as f:
        wr = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        wr.writeheader()
        wr.writerows(rows)
    uncut = {r["cell"]: r["condition"] for r in rows if r["scene"] == "uncut"}
    first = {(r["cell"], r["scene"], r["row"]): r["condition"] for r in rows if r["k"] == 1}
    for r in rows:
        u = uncut.get(r["cell"], float("nan"))
        r["scaled"] = r["condition"] / u if u and not math.isnan(u) else float("nan")
        f = first.get((r["cell"], r["scene"], r["row"]), float("nan"))
        r["vs_k1"] = r["condition"] / f if f and not math.isnan(f) else float("nan")
    ks = [kname(k) for k in KS]
    lines = []
    for variant, title in (("glued", "worst node error / U, glued interface"),
                           ("lips", "worst node error / U, free lips under the exact pressure"),
                           ("aniso", "worst node error / U, glued interface, unequal strains 1 : 2 : 3")):
        for dim in (2, 3):
            series = [(f"{c} {rw}", {"cell": c, "row": rw, "scene": variant}) for c in CELLS if CELLS[c][0] == dim
                      for rw in ROWS[dim]]
            if series:
                lines.append(f"{title}, {dim}D:\n")
                lines += table(rows, ks, "k", series, fmt, kfmt)
    ratio = lambda key: (lambda r: "—" if math.isnan(r[key]) else f'{r[key]:.0e}')
    for variant, key, title in (("glued", "vs_k1", "condition / the same row's at k = 1, glued interface"),
                                ("glued", "scaled", "condition / uncut mesh's, glued interface"),
                                ("lips", "scaled", "condition / uncut mesh's, free lips (no multipliers)")):
        for dim in (2, 3):
            series = [(f"{c} {rw}", {"cell": c, "row": rw, "scene": variant}) for c in CELLS if CELLS[c][0] == dim
                      for rw in ROWS[dim]]
            if series:
                lines.append(f"{title}, {dim}D:\n")
                lines += table(rows, ks, "k", series, ratio(key), kfmt)
    series = [(c, {"cell": c, "scene": "junction"}) for c in CELLS]
    lines.append("junction 10⁻ᵏ·h from a node, worst node error / U:\n")
    lines += table(rows, ks, "k", series, fmt, kfmt)
    lines.append("junction, condition / uncut mesh's:\n")
    lines += table(rows, ks, "k", series, ratio("scaled"), kfmt)
    for variant in ("glued", "lips"):
        series = [(c, {"cell": c, "scene": "tilt-" + variant}) for c in CELLS]
        lines.append(f"interface through the row X = 1 tilted by 10⁻ʲ rad, {variant}, worst node error / U:\n")
        lines += table(rows, ANGLES, "k", series, fmt, lambda j: f"1e-{j}", header="tilt (rad)")
    lines.append("per family: runs, not OK, worst node error / U (where), condition of the uncut mesh, condition / "
                 "uncut of the glued and of the free-lips scenes, lowest – highest (where highest)\n")
    lines.append("| family | runs | not OK | worst error / U | at | uncut | glued / uncut | highest at | lips / uncut | "
                 "highest at |")
    lines.append("|---|---|---|---|---|---|---|---|---|---|")
    at = lambda x: f'{x["row"]}, k = {kfmt(x["k"])}'
    for c in CELLS:
        rs = [x for x in rows if x["cell"] == c and x["scene"] != "uncut"]
        bad = sum(x["diagnostic"] != "OK" for x in rs)
        w = max(rs, key=lambda x: -1.0 if math.isnan(x["error"]) else x["error"])
        cols = []
        for variant in ("glued", "lips"):
            sc = [x for x in rs if x["scene"] == variant and not math.isnan(x["scaled"])]
            hi = max(sc, key=lambda x: x["scaled"]) if sc else None
            cols.append(f'{min(x["scaled"] for x in sc):.0e} – {hi["scaled"]:.0e} | {at(hi)}' if hi else "— | —")
        lines.append(f'| {c} | {len(rs)} | {bad} | {w["error"]:.1e} | {w["scene"]} {at(w)} | '
                     f'{uncut.get(c, float("nan")):.0e} | {cols[0]} | {cols[1]} |')
    lines.append("")
    with open(os.path.join(DATA, "table.md"), "w") as f:
        f.write("\n".join(lines))

    def curves(scene, key, rowwise=True, xs=ks):
        out = {}
        for c in CELLS:
            for rw in (ROWS[CELLS[c][0]] if rowwise else [None]):
                pts = []
                for i, x in enumerate(xs):
                    r = next((q for q in rows if q["cell"] == c and q["scene"] == scene and q["k"] == x
                              and (rw is None or q["row"] == rw)), None)
                    if r:
                        pts.append((i, r[key], r["diagnostic"] == "OK"))
                out[f"{c} {rw}" if rw else c] = pts
        return out

    klab = [kfmt(k) for k in ks]
    ktitle = "k (interface at 10^-k h from the row; ∞: through it)"
    svg(curves("glued", "error"), klab, "glued interface: worst node error / U (mesh and visual nodes); × a NOOK",
        ktitle, os.path.join(OUT, "error.svg"), -16, 1, line=1e-8)
    svg(curves("glued", "vs_k1"), klab, "glued interface: condition estimate / the same row's at k = 1",
        ktitle, os.path.join(OUT, "condition.svg"), -2, 12, line=100.0)
    svg(curves("lips", "scaled"), klab, "free lips: condition estimate / the uncut mesh's",
        ktitle, os.path.join(OUT, "lips_condition.svg"), -1, 14, line=100.0)
    svg(curves("aniso", "error"), klab, "glued, unequal strains (1 : 2 : 3): worst node error / U; × a NOOK",
        ktitle, os.path.join(OUT, "aniso.svg"), -16, 1, line=1e-8)
    svg(curves("lips", "error"), klab, "free lips under the exact pressure: worst node error / U; × a NOOK",
        ktitle, os.path.join(OUT, "lips.svg"), -16, 1, line=1e-8)
    svg(curves("junction", "error", rowwise=False), klab, "junction 10^-k h from a node: worst node error / U",
        "k (both interfaces at 10^-k h from the node; ∞: through it)", os.path.join(OUT, "junction.svg"), -16, 1,
        line=1e-8)
    tilt = {f"{lab} {v}": pts for v in ("glued", "lips")
            for lab, pts in curves("tilt-" + v, "error", rowwise=False, xs=ANGLES).items()}
    svg(tilt, [f"1e-{j}" for j in ANGLES], "interface tilted from the node row X = 1: worst node error / U",
        "tilt angle (rad)", os.path.join(OUT, "tilt.svg"), -16, 1, line=1e-8)
    params()


PENAS = [1e-3, 1.0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6]
YOUNGS = [1.0, 1e2, 1e4, 1e6, 1e8, 1e10, 1e12]
PARAM_KS = [1, 6, 12]


def params():
    """PENA_LAGR (E = 5.8e9) and E (PENA_LAGR = 100; SIGM_C and GC scaled with E, a change of the stress
    unit) on every family, rows row12 and diag, k = 1, 6, 12: target/stability/params.csv and params.md
    (per value, the worst error and the largest condition estimate over the three k)."""
    out = []
    with tempfile.TemporaryDirectory() as work:
        for cell, (dim, n, size, length) in CELLS.items():
            mesh = os.path.join(work, f"{cell}.med")
            subprocess.run([ASTER, "mesh", "box", "--cell", cell, "--n", n, "--size", size, "-o", mesh],
                           check=True, capture_output=True)
            for name, values in (("PENA_LAGR", PENAS), ("E", YOUNGS)):
                for v in values:
                    young, pena = (5.8e9, v) if name == "PENA_LAGR" else (v, 100.0)
                    for row in ("row12", "diag"):
                        for k in PARAM_KS:
                            phi = f"{ROWS[dim][row]}-{delta(k)!r}"
                            out.append(run(work, cell, mesh, scene(dim, length, phi, young, pena),
                                           param=name, value=v, row=row, k=k))
    with open(os.path.join(DATA, "params.csv"), "w", newline="") as f:
        wr = csv.DictWriter(f, fieldnames=list(out[0].keys()))
        wr.writeheader()
        wr.writerows(out)
    lines = []
    for name, values in (("PENA_LAGR", PENAS), ("E", YOUNGS)):
        for dim in (2, 3):
            series = [(f"{c} {rw}", c, rw) for c in CELLS if CELLS[c][0] == dim for rw in ("row12", "diag")]
            if not series:
                continue
            lines.append(f"{name}, {dim}D: worst node error / U and largest condition estimate over k = "
                         + ", ".join(map(str, PARAM_KS)) + "\n")
            lines.append(f"| {name} | " + " | ".join(s for s, _, _ in series) + " |")
            lines.append("|---" * (len(series) + 1) + "|")
            for v in values:
                cells_md = []
                for _, c, rw in series:
                    rs = [x for x in out if x["param"] == name and x["value"] == v and x["cell"] == c and x["row"] == rw]
                    if any(x["diagnostic"] not in ("OK", "NOOK_TEST_RESU") for x in rs):
                        cells_md.append("**stop**")
                        continue
                    err = max(x["error"] for x in rs)
                    cond = max(x["condition"] for x in rs)
                    e = f"{err:.1e}" if all(x["diagnostic"] == "OK" for x in rs) else f"**{err:.1e}**"
                    cells_md.append(f"{e} / {cond:.0e}")
                lines.append(f"| {v:.0e} | " + " | ".join(cells_md) + " |")
            lines.append("")
    msgs = sorted({x["message"] for x in out if x["message"]})
    if msgs:
        lines.append("stops: " + "; ".join(msgs) + "\n")
    with open(os.path.join(DATA, "params.md"), "w") as f:
        f.write("\n".join(lines))


if __name__ == "__main__":
    main()
