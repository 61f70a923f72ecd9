#!/usr/bin/env python3
"""Stability sweep of X-FEM cuttings (issue 10, point 4; docs/stability.md).

One straight interface cuts a small box (QUAD8 / QUAD4: 4x4 cells of size h = 1; HEXA20 / HEXA8: 2x2x2)
at 10^-k * h from a row of nodes, k = 1..14, and exactly through it (k = inf), for three rows:

- row12: the line (plane) Z = X/2 (2D: Y = X/2), through vertices and mid-side nodes alternately;
- diag:  the diagonal X + Y (+ Z) = 2, through vertices (and, in 3D, mid-side nodes);
- axis:  X = 1, along a row (2D) or plane (3D) of nodes.

Each case is the property test's scene (tests/it/xfem/property.rs): equal compression, glued cohesive
interface (CZM_LIN_MIX, mortar, ORDRE_INT=4 in 2D, 5 in 3D), checks at every node of the mesh and of the
visual mesh.
Then, on QUAD8 and HEXA20 (row12, diag, k = 1, 6, 12), PENA_LAGR = 1e-3 .. 1e6 and E = 1 .. 1e12 (SIGM_C
and GC scaled with E): target/stability/params.csv and params.md.
Recorded: the diagnostic, the worst node error relative to U and the condition estimate of the solve.
Writes the plots docs/stability/error.svg and docs/stability/condition.svg, and the run's data
target/stability/sweep.csv and its markdown tables target/stability/table.md (docs/stability.md quotes
them).

    cargo build --release && python3 scripts/stability_sweep.py
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

SCENE = """DEBUT(CODE="OUI")
U = 1.0e-4
LN = FORMULE(VALE="{phi}", NOM_PARA={para})
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MA = DEFI_GROUP(reuse=MA, MAILLAGE=MA, CREA_GROUP_NO=_F(GROUP_MA="{group}"))
MO0 = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(GROUP_MA="{group}", PHENOMENE="MECANIQUE", MODELISATION="{model}"))
FISS = DEFI_FISS_XFEM(MAILLAGE=MA, TYPE_DISCONTINUITE="INTERFACE", DEFI_FISS=_F(FONC_LN=LN))
MO = MODI_MODELE_XFEM(MODELE_IN=MO0, FISSURE=FISS, DECOUPE_FACETTE="SOUS_ELEMENTS", CONTACT="MORTAR")
CTX = DEFI_CONTACT(MODELE=MO, FORMULATION="XFEM",
                   ZONE=_F(FISS_MAIT=FISS, INTEGRATION="GAUSS", ORDRE_INT={order}, ALGO_CONT="CZM",
                           ALGO_LAGR="VERSION2", RELATION="CZM_LIN_MIX"))
ROCHE = DEFI_MATERIAU(ELAS=_F(E={young!r}, NU=0.2), RUPT_FRAG=_F(GC={gc!r}, SIGM_C={sigc!r}, PENA_LAGR={pena!r}))
CHMAT = AFFE_MATERIAU(MAILLAGE=MA, MODELE=MO, AFFE=_F(TOUT="OUI", MATER=ROCHE))
BLOC = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=({bounds}))
LINST = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=_F(JUSQU_A=1.0, NOMBRE=1))
RESU = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CHMAT, EXCIT=_F(CHARGE=BLOC), CONTACT=CTX,
                     COMPORTEMENT=_F(RELATION="ELAS"), INCREMENT=_F(LIST_INST=LINST),
                     CONVERGENCE=_F(RESI_GLOB_RELA=1.0e-10))
MAVISU = POST_MAIL_XFEM(MODELE=MO)
MAVISU = DEFI_GROUP(reuse=MAVISU, MAILLAGE=MAVISU, CREA_GROUP_NO=_F(GROUP_MA="{group}"))
MOVISU = AFFE_MODELE(MAILLAGE=MAVISU, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="{model}"))
RESVISU = POST_CHAM_XFEM(MODELE_VISU=MOVISU, RESULTAT=RESU)
{checks}for res in (RESU, RESVISU):
    DEP = POST_RELEVE_T(ACTION=_F(INTITULE="N", GROUP_NO="{group}", RESULTAT=res, NOM_CHAM="DEPL", NUME_ORDRE=1,
                                  NOM_CMP=({cmps}), OPERATION="EXTRACTION"))
    DEP = CALC_TABLE(reuse=DEP, TABLE=DEP, ACTION=({opers}))
    for cmp in ({errs}):
        for typ in ("MAX", "MIN"):
            TEST_TABLE(TABLE=DEP, NOM_PARA=cmp, TYPE_TEST=typ, CRITERE="ABSOLU", PRECISION=1.0e-8,
                       VALE_CALC=0.0, VALE_REFE=0.0, REFERENCE="ANALYTIQUE", ORDRE_GRANDEUR=1.0)
FIN()
"""

CELLS = {"QUAD8": (2, "4,4", "4,4", 4.0), "QUAD4": (2, "4,4", "4,4", 4.0), "TRIA3": (2, "4,4", "4,4", 4.0), "TRIA6": (2, "4,4", "4,4", 4.0),
         "HEXA20": (3, "2,2,2", "2,2,2", 2.0), "HEXA8": (3, "2,2,2", "2,2,2", 2.0),
         "TETRA4": (3, "2,2,2", "2,2,2", 2.0), "TETRA10": (3, "2,2,2", "2,2,2", 2.0), "PENTA6": (3, "2,2,2", "2,2,2", 2.0),
         "PENTA15": (3, "2,2,2", "2,2,2", 2.0)}
# `python3 scripts/stability_sweep.py TRIA3 TETRA4` sweeps those families only (exploration: the
# tables and plots are then of those families alone).
if len(sys.argv) > 1:
    CELLS = {c: v for c, v in CELLS.items() if c in sys.argv[1:]}
ROWS = {
    2: {"row12": "(Y-0.5*X)/1.118033988749895", "diag": "(X+Y-2.0)/1.4142135623730951", "axis": "X-1.0"},
    3: {"row12": "(Z-0.5*X)/1.118033988749895", "diag": "(X+Y+Z-2.0)/1.7320508075688772", "axis": "X-1.0"},
}
KS = list(range(1, 15)) + [math.inf]


def scene(dim, length, phi, young=5.8e9, pena=100.0):
    if dim == 2:
        model, group, para = "D_PLAN", "SURFACE", '["X", "Y"]'
        sides = [("GAUCHE", "DROITE", "X"), ("BAS", "HAUT", "Y")]
    else:
        model, group, para = "3D", "VOLUME", '["X", "Y", "Z"]'
        sides = [("XMIN", "XMAX", "X"), ("YMIN", "YMAX", "Y"), ("ZMIN", "ZMAX", "Z")]
    bounds = ", ".join(f'_F(GROUP_MA="{lo}", D{x}=U, H1{x}=0.0), _F(GROUP_MA="{hi}", D{x}=0.0, H1{x}=0.0)'
                       for lo, hi, x in sides)
    xs = [x for _, _, x in sides]
    checks = "".join(f'E{x} = FORMULE(VALE="(D{x} - U*(1.0 - COOR_{x}/{length}))/U", U=U, '
                     f'NOM_PARA=["D{x}", "COOR_{x}"])\n' for x in xs)
    # Facet rule: 4 Gauss points (degree 7) in 2D, FPG7 (degree 5) in 3D (see tests/it/xfem/property.rs).
    order = 4 if dim == 2 else 5
    # A change of the stress unit scales E, SIGM_C and GC (a stress times a length) alike.
    s = young / 5.8e9
    return SCENE.format(young=young, pena=pena, sigc=5.0e5 * s, gc=9.0e3 * s, phi=phi, para=para, group=group, model=model, bounds=bounds, checks=checks, order=order,
                        cmps=", ".join(f'"D{x}"' for x in xs), errs=", ".join(f'"ERR_{x}"' for x in xs),
                        opers=", ".join(f'_F(OPERATION="OPER", FORMULE=E{x}, NOM_PARA="ERR_{x}")' for x in xs))


def run_case(work, cell, mesh, dim, length, row, k, young=5.8e9, pena=100.0):
    delta = 0.0 if k == math.inf else 10.0 ** -k
    phi = f"{ROWS[dim][row]}-{delta!r}"
    comm = os.path.join(work, "case.comm")
    with open(comm, "w") as f:
        f.write(scene(dim, length, phi, young, pena))
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
    return {"cell": cell, "row": row, "k": "inf" if k == math.inf else k,
            "diagnostic": diag.group(1) if diag else "?",
            "error": max(errs) if errs else float("nan"),
            "condition": float(cond.group(1)) if cond else float("nan"),
            "message": fatal.group(1)[:160] if fatal else ""}


def fmt(r):
    if r["diagnostic"] == "OK":
        return f'{r["error"]:.1e}'
    if r["diagnostic"] == "NOOK_TEST_RESU":
        return f'**{r["error"]:.1e}**'
    return "**stop**"


def svg(rows, key, title, path, ymin, ymax):
    w, h, ml, mr, mt, mb = 760, 460, 60, 170, 30, 40
    colors = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf",
              "#7f7f7f", "#bcbd22", "#000000", "#aec7e8", "#ff9896", "#98df8a", "#c5b0d5", "#ffbb78",
              "#c49c94", "#f7b6d2", "#9edae5", "#dbdb8d", "#393b79", "#637939", "#8c6d31", "#843c39", "#7b4173", "#3182bd", "#e6550d"]
    xs = lambda k: ml + (w - ml - mr) * ((15 if k == "inf" else k) - 1) / 14
    ys = lambda v: mt + (h - mt - mb) * (ymax - max(ymin, min(ymax, math.log10(max(v, 1e-300))))) / (ymax - ymin)
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" '
           f'font-size="11">', f'<text x="{ml}" y="18" font-size="13">{title}</text>']
    for e in range(ymin, ymax + 1):
        y = ys(10.0 ** e)
        out.append(f'<line x1="{ml}" y1="{y:.1f}" x2="{w - mr}" y2="{y:.1f}" stroke="#ddd"/>')
        out.append(f'<text x="{ml - 6}" y="{y + 4:.1f}" text-anchor="end">1e{e}</text>')
    for k in list(range(1, 15)) + ["inf"]:
        x = xs(k)
        out.append(f'<text x="{x:.1f}" y="{h - mb + 15}" text-anchor="middle">{"∞" if k == "inf" else k}</text>')
    out.append(f'<text x="{(ml + w - mr) / 2}" y="{h - 8}" text-anchor="middle">k (interface at 10^-k h from '
               f'the row; ∞: through it)</text>')
    series = sorted({(r["cell"], r["row"]) for r in rows})
    for i, (cell, row) in enumerate(series):
        c = colors[i % len(colors)]
        # One polyline per run of consecutive k that gave a value (a stopped run breaks the line).
        segments, seg = [], []
        for r in rows:
            if r["cell"] == cell and r["row"] == row:
                if math.isnan(r[key]) or r[key] <= 0:
                    segments.append(seg)
                    seg = []
                else:
                    seg.append((xs(r["k"]), ys(r[key])))
        segments.append(seg)
        for pts in segments:
            if len(pts) > 1:
                out.append(f'<polyline fill="none" stroke="{c}" stroke-width="1.5" points="'
                           + " ".join(f"{x:.1f},{y:.1f}" for x, y in pts) + '"/>')
        for r in rows:
            if r["cell"] == cell and r["row"] == row:
                if math.isnan(r[key]) or r[key] <= 0:
                    continue
                x, y = xs(r["k"]), ys(r[key])
                if r["diagnostic"] == "OK":
                    out.append(f'<circle cx="{x:.1f}" cy="{y:.1f}" r="2.5" fill="{c}"/>')
                else:
                    out.append(f'<text x="{x:.1f}" y="{y + 4:.1f}" fill="{c}" text-anchor="middle">×</text>')
        ly = mt + 14 * i
        out.append(f'<line x1="{w - mr + 10}" y1="{ly}" x2="{w - mr + 30}" y2="{ly}" stroke="{c}" stroke-width="2"/>')
        out.append(f'<text x="{w - mr + 34}" y="{ly + 4}">{cell} {row}</text>')
    if key == "error":
        y = ys(1e-8)
        out.append(f'<line x1="{ml}" y1="{y:.1f}" x2="{w - mr}" y2="{y:.1f}" stroke="#000" stroke-dasharray="4 3"/>')
    out.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def main():
    os.makedirs(OUT, exist_ok=True)
    os.makedirs(DATA, exist_ok=True)
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for cell, (dim, n, size, length) in CELLS.items():
            mesh = os.path.join(work, f"{cell}.med")
            subprocess.run([ASTER, "mesh", "box", "--cell", cell, "--n", n, "--size", size, "-o", mesh],
                           check=True, capture_output=True)
            for row in ROWS[dim]:
                for k in KS:
                    r = run_case(work, cell, mesh, dim, length, row, k)
                    print(f'{cell:7} {row:6} k={r["k"]!s:4} {r["diagnostic"]:16} err {r["error"]:.2e} '
                          f'cond {r["condition"]:.1e} {r["message"]}', flush=True)
                    rows.append(r)
    with open(os.path.join(DATA, "sweep.csv"), "w", newline="") as f:
        wr = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        wr.writeheader()
        wr.writerows(rows)
    lines = []
    for (key, title), dim in [(kt, d) for kt in (("error", "worst node error / U"), ("condition", "condition estimate"))
                              for d in (2, 3)]:
        series = [(c, r) for c in CELLS if CELLS[c][0] == dim for r in ROWS[dim]]
        if not series:
            continue
        lines.append(f"{title}, {dim}D:\n")
        lines.append("| k | " + " | ".join(f"{c} {r}" for c, r in series) + " |")
        lines.append("|---" * (len(series) + 1) + "|")
        for k in KS:
            kk = "inf" if k == math.inf else k
            cells = []
            for c, rw in series:
                r = next(x for x in rows if x["cell"] == c and x["row"] == rw and x["k"] == kk)
                cells.append(fmt(r) if key == "error" else
                             ("—" if math.isnan(r["condition"]) else f'{r["condition"]:.0e}'))
            lines.append(f'| {"∞" if kk == "inf" else kk} | ' + " | ".join(cells) + " |")
        lines.append("")
    lines.append("per family (every row and k): runs, worst node error / U (where), condition estimate lowest – highest\n")
    lines.append("| family | runs | not OK | worst error / U | at | condition |")
    lines.append("|---|---|---|---|---|---|")
    for c in CELLS:
        rs = [x for x in rows if x["cell"] == c]
        bad = sum(x["diagnostic"] != "OK" for x in rs)
        w = max(rs, key=lambda x: -1.0 if math.isnan(x["error"]) else x["error"])
        cs = [x["condition"] for x in rs if not math.isnan(x["condition"])]
        at = f'{w["row"]}, k = {"∞" if w["k"] == "inf" else w["k"]}'
        cond = f"{min(cs):.0e} – {max(cs):.0e}" if cs else "—"
        lines.append(f'| {c} | {len(rs)} | {bad} | {w["error"]:.1e} | {at} | {cond} |')
    lines.append("")
    with open(os.path.join(DATA, "table.md"), "w") as f:
        f.write("\n".join(lines))
    svg(rows, "error", "worst node error / U (mesh and visual nodes); × a NOOK, no point: the run stopped", os.path.join(OUT, "error.svg"),
        -16, 1)
    svg(rows, "condition", "condition estimate of the solve (no point: the run stopped; above 1e20 drawn at 1e20)", os.path.join(OUT, "condition.svg"), 8, 20)

    params()


PENAS = [1e-3, 1e-2, 1e-1, 1.0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6]
YOUNGS = [1.0, 1e2, 1e4, 1e6, 1e8, 1e10, 1e12]
PARAM_KS = [1, 6, 12]


def params():
    """PENA_LAGR (E = 5.8e9) and E (PENA_LAGR = 100; SIGM_C and GC scaled with E, a change of the stress
    unit) on the quadratic cells, rows row12 and diag, k = 1, 6, 12: target/stability/params.csv and
    params.md (per value, the worst error and condition over the three k)."""
    cells = [c for c in ("QUAD8", "HEXA20") if c in CELLS]
    if not cells:
        return
    out = []
    with tempfile.TemporaryDirectory() as work:
        for cell in cells:
            dim, n, size, length = CELLS[cell]
            mesh = os.path.join(work, f"{cell}.med")
            subprocess.run([ASTER, "mesh", "box", "--cell", cell, "--n", n, "--size", size, "-o", mesh],
                           check=True, capture_output=True)
            for name, values in (("PENA_LAGR", PENAS), ("E", YOUNGS)):
                for v in values:
                    young, pena = (5.8e9, v) if name == "PENA_LAGR" else (v, 100.0)
                    for row in ("row12", "diag"):
                        for k in PARAM_KS:
                            r = run_case(work, cell, mesh, dim, length, row, k, young, pena)
                            r.update(param=name, value=v)
                            print(f'{cell:7} {row:6} k={k:<3} {name}={v:.0e} {r["diagnostic"]:16} '
                                  f'err {r["error"]:.2e} cond {r["condition"]:.1e} {r["message"]}', flush=True)
                            out.append(r)
    with open(os.path.join(DATA, "params.csv"), "w", newline="") as f:
        wr = csv.DictWriter(f, fieldnames=list(out[0].keys()))
        wr.writeheader()
        wr.writerows(out)
    series = [(c, rw) for c in cells for rw in ("row12", "diag")]
    lines = []
    for name, values in (("PENA_LAGR", PENAS), ("E", YOUNGS)):
        lines.append(f"{name}: worst node error / U, and largest condition estimate, over k = "
                     + ", ".join(map(str, PARAM_KS)) + "\n")
        lines.append(f"| {name} | " + " | ".join(f"{c} {rw}" for c, rw in series) + " |")
        lines.append("|---" * (len(series) + 1) + "|")
        for v in values:
            cells_md = []
            for c, rw in series:
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
