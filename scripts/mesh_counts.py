#!/usr/bin/env python3
"""Node and cell counts of mesh files, read by readers independent of aster-rs, one line per mesh:
`file<TAB>mesh<TAB>nodes<TAB>cells` (or `file<TAB>ERROR<TAB>message`), for tests/it/med/corpus_meshes.rs.

    /usr/bin/python3 scripts/mesh_counts.py med FILE...    # MED, with MED-fichier's own API (python3-med)
    python3 scripts/mesh_counts.py gmsh FILE...           # .msh and I-DEAS .unv/.msup, with gmsh's API
    python3 scripts/mesh_counts.py text FILE...           # .mail and .mgib, with the small parsers below

Counts follow what Code_Aster makes of a file where it drops entities: a Gmsh mesh keeps the nodes
its cells use (for an I-DEAS file, which Code_Aster keeps whole, the count is of the nodes its cells use
too, since gmsh drops the others: the test compares it with ours of the same) (not the centre of a 9-node quadrangle or of a 14-node pyramid); a Cast3M file keeps
the cells of its named meshes (and their parts), an identical cell once, and the nodes its points use.
"""
import os
import re
import sys
import tempfile


def emit(file, mesh="", nodes=0, cells=0, error=None):
    if error is not None:
        print(f"{file}\tERROR\t{' '.join(str(error).split())}", flush=True)
    else:
        print(f"{file}\t{mesh}\t{nodes}\t{cells}", flush=True)


def med_counts(files):
    from med import medenum, medfile, medmesh

    for path in files:
        try:
            fid = medfile.MEDfileOpen(path, medenum.MED_ACC_RDONLY)
            for i in range(1, medmesh.MEDnMesh(fid) + 1):
                name = medmesh.MEDmeshInfo(fid, i)[0]
                dt, it = medenum.MED_NO_DT, medenum.MED_NO_IT
                nodes = medmesh.MEDmeshnEntity(
                    fid, name, dt, it, medenum.MED_NODE, medenum.MED_NONE, medenum.MED_COORDINATE, medenum.MED_NO_CMODE
                )[0]
                ntypes = medmesh.MEDmeshnEntity(
                    fid, name, dt, it, medenum.MED_CELL, medenum.MED_GEO_ALL, medenum.MED_CONNECTIVITY, medenum.MED_NODAL
                )[0]
                cells = 0
                for k in range(1, ntypes + 1):
                    geo = medmesh.MEDmeshEntityInfo(fid, name, dt, it, medenum.MED_CELL, k)[1]
                    cells += medmesh.MEDmeshnEntity(
                        fid, name, dt, it, medenum.MED_CELL, geo, medenum.MED_CONNECTIVITY, medenum.MED_NODAL
                    )[0]
                emit(file=os.path.basename(path), mesh=name, nodes=nodes, cells=cells)
            medfile.MEDfileClose(fid)
        except Exception as e:  # noqa: BLE001 - reported, not hidden
            emit(file=os.path.basename(path), error=str(e))


def gmsh_counts(files):
    """.msh with meshio, else (format 1, files meshio refuses) with gmsh; I-DEAS with gmsh. gmsh reads
    in a child process, which goes on past a file gmsh crashes on (gmsh 4.15 does on some valid
    files) with a new child."""
    import subprocess

    rest = []
    for path in files:
        if path.endswith(".msh"):
            try:
                emit(file=os.path.basename(path), mesh="", **meshio_msh(path))
                continue
            except BaseException:  # noqa: BLE001 - meshio exits on files it cannot read; gmsh's turn
                pass
        rest.append(path)
    while rest:
        out = subprocess.run([sys.executable, __file__, "gmsh-batch", *rest], capture_output=True, text=True)
        done = [line for line in out.stdout.splitlines() if "\t" in line]
        for line in done:
            print(line, flush=True)
        rest = rest[len(done) :]
        if rest:
            # The child died on rest[0].
            emit(file=os.path.basename(rest[0]), error=f"gmsh crashed: {out.stderr.strip()[-200:]}")
            rest = rest[1:]


def meshio_msh(path):
    import contextlib

    import meshio

    # meshio prints its warnings and errors on stdout, which carries our lines.
    with contextlib.redirect_stdout(sys.stderr):
        m = meshio.read(path, file_format="gmsh")
    used, cells = set(), 0
    for block in m.cells:
        keep = {"quad9": 8, "pyramid14": 13}.get(block.type, block.data.shape[1])
        used.update(block.data[:, :keep].ravel().tolist())
        cells += len(block.data)
    return {"nodes": len(used), "cells": cells}


def gmsh_batch(paths):
    import gmsh

    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    for path in paths:
        try:
            gmsh_one(gmsh, path)
        except Exception as e:  # noqa: BLE001
            emit(file=os.path.basename(path), error=str(e))
    gmsh.finalize()


def gmsh_one(gmsh, path):
    gmsh.clear()
    with tempfile.TemporaryDirectory() as tmp:
        src = path
        if path.endswith(".msup"):
            # gmsh knows I-DEAS files by their extension.
            src = os.path.join(tmp, os.path.basename(path)[:-5] + ".unv")
            os.symlink(os.path.abspath(path), src)
        gmsh.open(src)
        used, cells = set(), 0
        for etype, _tags, conn in zip(*gmsh.model.mesh.getElements()):
            n = gmsh.model.mesh.getElementProperties(etype)[3]
            keep = {10: 8, 14: 13}.get(etype, n) if path.endswith(".msh") else n
            for e in range(len(conn) // n):
                used.update(conn[e * n : e * n + keep])
            cells += len(conn) // n
    # gmsh drops the nodes of an I-DEAS file that no element uses: count the used ones in both formats.
    emit(file=os.path.basename(path), mesh="", nodes=len(used), cells=cells)


CELL_NODES = {
    "POI1": 1, "SEG2": 2, "SEG3": 3, "SEG4": 4, "TRIA3": 3, "TRIA6": 6, "TRIA7": 7, "QUAD4": 4,
    "QUAD8": 8, "QUAD9": 9, "TETRA4": 4, "TETRA10": 10, "PENTA6": 6, "PENTA15": 15, "PENTA18": 18,
    "PYRAM5": 5, "PYRAM13": 13, "HEXA8": 8, "HEXA20": 20, "HEXA27": 27,
}


def mail_counts(path):
    """Sections up to FINSF; words after `%` are comments; options `KEY = value` on the header line."""
    nodes = cells = 0
    section, header_line, body = None, -1, []
    for k, line in enumerate(open(path, encoding="latin-1")):
        words = line.split("%")[0].replace("=", " = ").split()
        for w in words:
            if section is None:
                section, header_line, body = w.upper(), k, []
                if section == "FIN":
                    return nodes, cells
                continue
            if w.upper() == "FINSF":
                if section in ("COOR_2D", "COOR_3D"):
                    nodes += len(body) // (int(section[5]) + 1)
                elif section in CELL_NODES:
                    cells += len(body) // (CELL_NODES[section] + 1)
                section = None
                continue
            if k == header_line:
                continue  # options of the header line
            body.append(w)
    return nodes, cells


def gibi_counts(path):
    lines = open(path, encoding="latin-1").read().split("\n")
    pos = 0
    level, dim = 0, 0
    objects, named, indirect, coords = [], [], None, 0

    def ints(n, width, per):
        nonlocal pos
        out = []
        while len(out) < n:
            line = lines[pos]
            pos += 1
            for k in range(min(per, n - len(out))):
                field = line[k * width : (k + 1) * width].strip()
                out.append(int(field) if field else 0)
        return out

    while pos < len(lines):
        line = lines[pos]
        pos += 1
        if not line.startswith(" ENREGISTREMENT DE TYPE"):
            continue
        kind = line.split()[-1]
        if kind == "4":
            w = lines[pos].split()
            level, dim = int(w[1]), int(w[-1])
            pos += 2
        elif kind == "5":
            break
        elif kind == "2":
            m = re.match(r"\s*PILE NUMERO\s*(\d+)NBRE OBJETS NOMMES\s*(\d+)NBRE OBJETS\s*(\d+)", lines[pos])
            pos += 1
            stack, nnamed, count = (int(g) for g in m.groups())
            width, per = (5, 16) if level == 3 else (8, 10)
            if stack == 1:
                pos += (nnamed + 7) // 8
                numbers = []
                while len(numbers) < nnamed:
                    numbers += [int(x) for x in lines[pos].split()]
                    pos += 1
                named += numbers
                for _ in range(count):
                    itypel, nsub, nref, nno, nele = ints(5, width, per)
                    if nsub:
                        objects.append(("parts", ints(nsub, width, per)))
                        ints(nref, width, per)
                    else:
                        ints(nref, width, per)
                        ints(nele, width, per)
                        conn = ints(nele * nno, width, per)
                        objects.append(("cells", [tuple(conn[e * nno : (e + 1) * nno]) for e in range(nele)]))
            elif stack == 32:
                pos += (nnamed + 7) // 8
                ints(nnamed, width, per)
                n = ints(1, width, per)[0]
                indirect = ints(n, width, per)
            elif stack == 0:
                # The older layout: named points, then the coordinates of `count` points.
                pos += (nnamed + 7) // 8
                ints(nnamed, width, per)
                indirect = list(range(1, count + 1))
            elif stack == 33:
                coords = int(lines[pos].split()[0])
                pos += 1
    kept = set()
    for n in named:
        kept.add(n)
        if objects[n - 1][0] == "parts":
            kept.update(objects[n - 1][1])
    distinct = set()
    for i, (what, content) in enumerate(objects, start=1):
        if what == "cells" and i in kept:
            distinct.update(content)
    return len(set(indirect)), len(distinct)


def text_counts(files):
    for path in files:
        try:
            n, c = gibi_counts(path) if path.endswith(".mgib") else mail_counts(path)
            emit(file=os.path.basename(path), mesh="", nodes=n, cells=c)
        except Exception as e:  # noqa: BLE001
            emit(file=os.path.basename(path), error=f"{type(e).__name__}: {e}")


if __name__ == "__main__":
    mode, files = sys.argv[1], sys.argv[2:]
    if mode == "gmsh-batch":
        gmsh_batch(files)
    else:
        {"med": med_counts, "gmsh": gmsh_counts, "text": text_counts}[mode](files)
