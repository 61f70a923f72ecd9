#!/usr/bin/python3
"""Independent view of a MED file through MED-fichier's Python API (python3-med).

Run with /usr/bin/python3 (python3-med imports only there). Used by
tests/med_roundtrip.rs to cross-check aster-rs's MED reader and writer.

    med_check.py mesh FILE          -> one line per fact (see below)
    med_check.py field FILE NAME    -> steps of a node field
    med_check.py cells FILE         -> localizations and every field's values on every support

`mesh` output lines (values separated by single spaces):
    MESH <name> <space dim> <nnodes>
    COOR <x> [<y> [<z>]]              one per node, Python repr (exact)
    TYPE <MED name> <count>
    CONN <MED name> <n1> ...          one per cell, MED node order, 1-based
    NGROUP <group> <size>             node groups (from families)
    CGROUP <group> <size>             cell groups (from families)
`field` output lines:
    COMP <c1> <c2> ...
    STEP <numdt> <time> <v1> <v2> ...  values interlaced per node
`cells` output lines:
    LOC <name> <geometry type> <dim> <points> <x1> [<y1> [<z1>]] ... <w1> ...  (coordinates then weights)
    FIELD <name> <steps> <c1> <c2> ...
    VALUES <field> <numdt> <numit> <NODE|CELL|NODE_ELEMENT> <geometry type> <localization or -> <profile or ->
           <entities> <values per entity> <v1> <v2> ...   values full-interlace (entity, point, component)
"""
import os
import sys

from med.medenum import *  # noqa: F401,F403
from med.medfamily import MEDfamilyInfo, MEDnFamily, MEDnFamilyGroup
from med.medfield import (MEDfieldComputingStepInfo, MEDfieldInfo, MEDfieldnComponent,
                          MEDfieldValueRd, MEDnField, MEDfieldnValue, MEDfieldnValueWithProfile,
                          MEDfieldValueWithProfileRd)
from med.medlocalization import MEDlocalizationInfo, MEDlocalizationRd, MEDnLocalization
from med.medfile import MEDCHAR, MEDFLOAT, MEDINT, MEDfileClose, MEDfileOpen
from med.medmesh import (MEDmeshElementConnectivityRd, MEDmeshEntityFamilyNumberRd,
                         MEDmeshInfo, MEDmeshnEntity, MEDmeshNodeCoordinateRd, MEDnMesh)

TYPES = [("PO1", MED_POINT1, 1), ("SE2", MED_SEG2, 2), ("SE3", MED_SEG3, 3), ("SE4", MED_SEG4, 4),
         ("TR3", MED_TRIA3, 3), ("QU4", MED_QUAD4, 4), ("TR6", MED_TRIA6, 6), ("TR7", MED_TRIA7, 7),
         ("QU8", MED_QUAD8, 8), ("QU9", MED_QUAD9, 9), ("TE4", MED_TETRA4, 4),
         ("PY5", MED_PYRA5, 5), ("PE6", MED_PENTA6, 6), ("HE8", MED_HEXA8, 8),
         ("T10", MED_TETRA10, 10), ("P13", MED_PYRA13, 13), ("P15", MED_PENTA15, 15),
         ("P18", MED_PENTA18, 18), ("H20", MED_HEXA20, 20), ("H27", MED_HEXA27, 27)]


def groups_of_families(fid, mesh):
    fams = {}
    for i in range(1, MEDnFamily(fid, mesh) + 1):
        ng = MEDnFamilyGroup(fid, mesh, i)
        buf = MEDCHAR(80 * ng + 1)
        _, num, _ = MEDfamilyInfo(fid, mesh, i, buf)
        text = "".join(buf)
        names = [text[80 * k:80 * (k + 1)].rstrip(" \x00") for k in range(ng)]
        fams.setdefault(num, []).extend(n for n in names if n)
    return fams


def mesh_report(path):
    fid = MEDfileOpen(path, MED_ACC_RDONLY)
    out = []
    if MEDnMesh(fid) < 1:
        raise SystemExit("no mesh")
    info = MEDmeshInfo(fid, 1)
    mesh, dim = info[0], info[1]
    nn = MEDmeshnEntity(fid, mesh, MED_NO_DT, MED_NO_IT, MED_NODE, MED_NONE,
                        MED_COORDINATE, MED_NO_CMODE)[0]
    out.append("MESH %s %d %d" % (mesh, dim, nn))
    coo = MEDFLOAT(nn * dim)
    MEDmeshNodeCoordinateRd(fid, mesh, MED_NO_DT, MED_NO_IT, MED_FULL_INTERLACE, coo)
    coo = list(coo)
    for i in range(nn):
        out.append("COOR " + " ".join(repr(float(x)) for x in coo[i * dim:(i + 1) * dim]))
    fams = groups_of_families(fid, mesh)
    ngroups, cgroups = {}, {}
    if MEDmeshnEntity(fid, mesh, MED_NO_DT, MED_NO_IT, MED_NODE, MED_NONE,
                      MED_FAMILY_NUMBER, MED_NO_CMODE)[0] > 0:
        nfam = MEDINT(nn)
        MEDmeshEntityFamilyNumberRd(fid, mesh, MED_NO_DT, MED_NO_IT, MED_NODE, MED_NONE, nfam)
        for f in nfam:
            for g in fams.get(f, []) if f != 0 else []:
                ngroups[g] = ngroups.get(g, 0) + 1
    for name, geo, nno in TYPES:
        nc = MEDmeshnEntity(fid, mesh, MED_NO_DT, MED_NO_IT, MED_CELL, geo,
                            MED_CONNECTIVITY, MED_NODAL)[0]
        if nc <= 0:
            continue
        out.append("TYPE %s %d" % (name, nc))
        conn = MEDINT(nc * nno)
        MEDmeshElementConnectivityRd(fid, mesh, MED_NO_DT, MED_NO_IT, MED_CELL, geo, MED_NODAL,
                                     MED_FULL_INTERLACE, conn)
        conn = list(conn)
        for i in range(nc):
            out.append("CONN %s %s" % (name, " ".join(str(n) for n in conn[i * nno:(i + 1) * nno])))
        if MEDmeshnEntity(fid, mesh, MED_NO_DT, MED_NO_IT, MED_CELL, geo,
                          MED_FAMILY_NUMBER, MED_NODAL)[0] > 0:
            cfam = MEDINT(nc)
            MEDmeshEntityFamilyNumberRd(fid, mesh, MED_NO_DT, MED_NO_IT, MED_CELL, geo, cfam)
            for f in cfam:
                for g in fams.get(f, []) if f != 0 else []:
                    cgroups[g] = cgroups.get(g, 0) + 1
    for g in sorted(ngroups):
        out.append("NGROUP %s %d" % (g, ngroups[g]))
    for g in sorted(cgroups):
        out.append("CGROUP %s %d" % (g, cgroups[g]))
    MEDfileClose(fid)
    return out


def field_report(path, field):
    fid = MEDfileOpen(path, MED_ACC_RDONLY)
    out = []
    for i in range(1, MEDnField(fid) + 1):
        ncomp = MEDfieldnComponent(fid, i)
        info = MEDfieldInfo(fid, i)
        name, comps, nstep = info[0], info[4], info[7]
        if name != field:
            continue
        out.append("COMP " + " ".join(comps[16 * k:16 * (k + 1)].strip() for k in range(ncomp)))
        for s in range(1, nstep + 1):
            numdt, numit, dt = MEDfieldComputingStepInfo(fid, name, s)
            n = MEDfieldnValue(fid, name, numdt, numit, MED_NODE, MED_NONE)
            vals = MEDFLOAT(n * ncomp)
            MEDfieldValueRd(fid, name, numdt, numit, MED_NODE, MED_NONE, MED_FULL_INTERLACE,
                            MED_ALL_CONSTITUENT, vals)
            out.append("STEP %d %r %s" % (numdt, float(dt), " ".join(repr(float(v)) for v in vals)))
    MEDfileClose(fid)
    return out


def cells_report(path):
    fid = MEDfileOpen(path, MED_ACC_RDONLY)
    out = []
    for i in range(1, MEDnLocalization(fid) + 1):
        name, geo, dim, npts = MEDlocalizationInfo(fid, i)[:4]
        nno = int(geo) % 100
        ref, gau, wg = MEDFLOAT(nno * dim), MEDFLOAT(npts * dim), MEDFLOAT(npts)
        MEDlocalizationRd(fid, name, MED_FULL_INTERLACE, ref, gau, wg)
        out.append("LOC %s %d %d %d %s %s" % (name, int(geo), dim, npts, " ".join(repr(float(x)) for x in gau),
                                              " ".join(repr(float(w)) for w in wg)))
    geos = [g for _, g, _ in TYPES]
    for i in range(1, MEDnField(fid) + 1):
        ncomp = MEDfieldnComponent(fid, i)
        info = MEDfieldInfo(fid, i)
        name, comps, nstep = info[0], info[4], info[7]
        out.append("FIELD %s %d %s" % (name, nstep, " ".join(comps[16 * k:16 * (k + 1)].strip()
                                                            for k in range(ncomp))))
        for s in range(1, nstep + 1):
            numdt, numit, dt = MEDfieldComputingStepInfo(fid, name, s)
            for label, etype, gts in [("NODE", MED_NODE, [MED_NONE]), ("CELL", MED_CELL, geos),
                                      ("NODE_ELEMENT", MED_NODE_ELEMENT, geos)]:
                for geo in gts:
                    n, pfl, _, loc, npts = MEDfieldnValueWithProfile(fid, name, numdt, numit, etype, geo, 1,
                                                                     MED_COMPACT_PFLMODE)
                    if n <= 0:
                        continue
                    vals = MEDFLOAT(n * npts * ncomp)
                    MEDfieldValueWithProfileRd(fid, name, numdt, numit, etype, geo, MED_COMPACT_STMODE, pfl,
                                               MED_FULL_INTERLACE, MED_ALL_CONSTITUENT, vals)
                    out.append("VALUES %s %d %d %s %d %s %s %d %d %s" % (
                        name, numdt, numit, label, int(geo), loc or "-", pfl or "-", n, npts,
                        " ".join(repr(float(v)) for v in vals)))
    MEDfileClose(fid)
    return out


def main():
    if len(sys.argv) >= 3 and sys.argv[1] == "cells":
        lines = cells_report(sys.argv[2])
    elif len(sys.argv) >= 3 and sys.argv[1] == "mesh":
        lines = mesh_report(sys.argv[2])
    elif len(sys.argv) >= 4 and sys.argv[1] == "field":
        lines = field_report(sys.argv[2], sys.argv[3])
    else:
        sys.stderr.write(__doc__)
        sys.exit(2)
    sys.stdout.write("\n".join(lines) + "\n")
    sys.stdout.flush()
    # The SWIG bindings may crash at interpreter teardown: leave at once.
    os._exit(0)


if __name__ == "__main__":
    main()
