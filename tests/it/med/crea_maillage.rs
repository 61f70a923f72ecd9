//! CREA_MAILLAGE: LINE_QUAD's numbering checked against the node names WTNV144A refers to, LINE_QUAD
//! and QUAD_LINE run through the `aster` binary with their meshes written to MED and read back, a
//! solve on a LINE_QUAD mesh printed to MED, and the located errors.

use crate::common::*;
use aster::med;
use aster::mesh::convert::{line_to_quad, quad_to_line};
use aster::mesh::generate::box_mesh;
use aster::mesh::{CellType, Mesh};
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use std::process::Output;

/// Run a command file with unit mappings.
fn run_comm(dir: &Path, name: &str, src: &str, units: &[(i64, &Path)]) -> Output {
    let comm = dir.join(format!("{name}.comm"));
    std::fs::write(&comm, src).unwrap();
    let mut cmd = aster();
    cmd.arg("run").arg(&comm).arg("--out").arg(dir.join(format!("{name}.out"))).arg("-q");
    for (u, p) in units {
        cmd.arg("--unit").arg(format!("{u}={}", p.display()));
    }
    cmd.output().unwrap()
}

fn run_ok(dir: &Path, name: &str, src: &str, units: &[(i64, &Path)]) -> String {
    let o = run_comm(dir, name, src, units);
    let (out, err) = text(&o);
    assert!(o.status.success(), "{name} failed:\nstdout:\n{out}\nstderr:\n{err}");
    std::fs::read_to_string(dir.join(format!("{name}.out")).join(format!("{name}.mess"))).unwrap()
}

/// The text of every `_F(...)` occurrence of a command file.
fn occurrences(src: &str) -> Vec<&str> {
    let mut out = Vec::new();
    for (start, _) in src.match_indices("_F(") {
        let body = &src[start + 3..];
        let mut depth = 1;
        for (i, ch) in body.char_indices() {
            match ch {
                '(' => depth += 1,
                ')' => depth -= 1,
                _ => {}
            }
            if depth == 0 {
                out.push(&body[..i]);
                break;
            }
        }
    }
    out
}

/// The text value of `KW="..."` in an occurrence.
fn value<'a>(occ: &'a str, kw: &str) -> Option<&'a str> {
    let at = occ.find(&format!("{kw}=\""))? + kw.len() + 2;
    occ[at..].split('"').next()
}

#[test]
fn wtnv144a_middle_nodes_lie_in_the_cells_its_checks_name() {
    let (Some(comm), Some(mesh)) = (astest("wtnv144a.comm"), mesh("wtnv144a.mmed")) else { return };
    assert_eq!(mesh.nnodes(), 85);
    let counts = mesh.cell_type_counts();
    assert_eq!((counts[&CellType::Seg2], counts[&CellType::Quad4]), (40, 64));
    let q = line_to_quad(&mesh, &(0..mesh.ncells()).collect::<Vec<_>>()).mesh;
    assert_eq!(q.nnodes(), 85 + 148);

    // The checks name nodes and cells of the X-FEM visual mesh through one-member groups
    // (NS16 = node N118, M37 = cell M41), whose classic nodes and cells keep the names of MAIL;
    // SIGM_ELNO checks pair them: the node must be a node of the cell.
    let src = std::fs::read_to_string(comm).unwrap();
    let occs = occurrences(&src);
    let mut node_of: BTreeMap<&str, &str> = BTreeMap::new();
    let mut cell_of: BTreeMap<&str, &str> = BTreeMap::new();
    for o in &occs {
        if let (Some(g), Some(n)) = (value(o, "NOM"), value(o, "NOEUD")) {
            node_of.insert(g, n);
        }
        if let (Some(g), Some(c)) = (value(o, "NOM"), value(o, "MAILLE")) {
            cell_of.insert(g, c);
        }
    }
    let mut pairs = BTreeSet::new();
    for o in &occs {
        if let (Some(g), Some(m)) = (value(o, "GROUP_NO"), value(o, "GROUP_MA")) {
            if let (Some(n), Some(c)) = (node_of.get(g), cell_of.get(m)) {
                pairs.insert((*n, *c));
            }
        }
    }
    assert_eq!(pairs.len(), 34, "{pairs:?}");
    for (n, c) in pairs {
        let node = q.node_names.iter().position(|x| x == n).unwrap_or_else(|| panic!("no node {n}"));
        assert!(node >= 85, "{n} is a middle node");
        let cell = q.cell_names.iter().position(|x| x == c).unwrap_or_else(|| panic!("no cell {c}"));
        assert_eq!(q.cell_types[cell], CellType::Quad8);
        assert!(q.cells[cell].contains(&node), "{n} is not a node of {c}: {:?}", q.cells[cell]);
    }
}

/// A 2 x 1 box of 2 x 2 QUAD4 with its SEG2 boundaries, written for LIRE_MAILLAGE.
fn quad4_box(dir: &Path) -> (Mesh, std::path::PathBuf) {
    let m = box_mesh(CellType::Quad4, &[2, 2], &[2.0, 1.0]).unwrap();
    let p = dir.join("box.med");
    med::write_mesh(&p, &m, "MA").unwrap();
    (med::read_mesh(&p, None).unwrap(), p)
}

const NU: f64 = 0.3;

#[test]
fn line_quad_mesh_to_med_and_a_result_on_it() {
    let dir = scratch!("line_quad");
    let (input, box_med) = quad4_box(&dir);
    let mesh_out = dir.join("mq.med");
    let rmed = dir.join("resu.rmed");
    let mess = run_ok(
        &dir,
        "lq",
        r#"DEBUT()
MA = LIRE_MAILLAGE(UNITE=20)
MQ = CREA_MAILLAGE(MAILLAGE=MA, LINE_QUAD=_F(TOUT="OUI"))
IMPR_RESU(FORMAT="MED", UNITE=81, RESU=_F(MAILLAGE=MQ))
MQ = DEFI_GROUP(reuse=MQ, MAILLAGE=MQ, DETR_GROUP_NO=_F(NOM=("GAUCHE", "BAS", "DROITE")),
                CREA_GROUP_NO=_F(GROUP_MA=("GAUCHE", "BAS", "DROITE")))
MO = AFFE_MODELE(MAILLAGE=MQ, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN"))
MAT = DEFI_MATERIAU(ELAS=_F(E=1000.0, NU=0.3))
CM = AFFE_MATERIAU(MAILLAGE=MQ, AFFE=_F(TOUT="OUI", MATER=MAT))
CH = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=(_F(GROUP_NO="GAUCHE", DX=0.0), _F(GROUP_NO="BAS", DY=0.0),
                                         _F(GROUP_NO="DROITE", DX=0.02)))
RESU = MECA_STATIQUE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CH))
IMPR_RESU(FORMAT="MED", UNITE=80, RESU=_F(RESULTAT=RESU, NOM_CHAM="DEPL"))
FIN()
"#,
        &[(20, &box_med), (81, &mesh_out), (80, &rmed)],
    );
    assert!(
        mess.contains("CREA_MAILLAGE/LINE_QUAD on MA: 8 SEG2 -> SEG3, 4 QUAD4 -> QUAD8; 12 nodes created, N10 to N21")
    );

    // The mesh written by IMPR_RESU is the library's conversion, names and groups included.
    let want = line_to_quad(&input, &(0..input.ncells()).collect::<Vec<_>>()).mesh;
    let got = med::read_mesh(&mesh_out, Some("MQ")).unwrap();
    assert_eq!(got.coords, want.coords);
    assert_eq!(got.cells, want.cells);
    assert_eq!(got.cell_types, want.cell_types);
    assert_eq!(got.node_names, (1..=21).map(|i| format!("N{i}")).collect::<Vec<_>>());
    assert_eq!(got.cell_names, input.cell_names);
    assert_eq!(got.node_groups, input.node_groups);
    assert_eq!(got.cell_groups, input.cell_groups);

    // Uniaxial plane strain: exact on the QUAD8 mesh, middle nodes included.
    let depl = med::read_node_field(&rmed, "RESU____DEPL").unwrap();
    let mesh = med::read_mesh(&rmed, Some("MQ")).unwrap();
    assert_eq!(mesh.nnodes(), 21);
    let values = &depl.steps[0].2;
    let exx = 0.01;
    for (i, c) in mesh.coords.iter().enumerate() {
        let (ux, uy) = (exx * c[0], -NU / (1.0 - NU) * exx * c[1]);
        assert!((values[2 * i] - ux).abs() <= 1e-12, "DX at {}: {} vs {ux}", mesh.node_names[i], values[2 * i]);
        assert!((values[2 * i + 1] - uy).abs() <= 1e-12, "DY at {}", mesh.node_names[i]);
    }
}

#[test]
fn quad_line_undoes_line_quad() {
    let dir = scratch!("quad_line");
    let (input, box_med) = quad4_box(&dir);
    let out = dir.join("ml.med");
    let part = dir.join("mp.med");
    let mess = run_ok(
        &dir,
        "ql",
        r#"DEBUT()
MA = LIRE_MAILLAGE(UNITE=20)
MQ = CREA_MAILLAGE(MAILLAGE=MA, LINE_QUAD=_F(TOUT="OUI"))
ML = CREA_MAILLAGE(MAILLAGE=MQ, QUAD_LINE=_F(TOUT="OUI"))
MP = CREA_MAILLAGE(MAILLAGE=MQ, QUAD_LINE=_F(GROUP_MA="BAS"))
IMPR_RESU(FORMAT="MED", UNITE=81, RESU=_F(MAILLAGE=ML))
IMPR_RESU(FORMAT="MED", UNITE=82, RESU=_F(MAILLAGE=MP))
FIN()
"#,
        &[(20, &box_med), (81, &out), (82, &part)],
    );
    assert!(mess.contains("CREA_MAILLAGE/QUAD_LINE on MQ: 8 SEG3 -> SEG2, 4 QUAD8 -> QUAD4; 12 nodes removed, 9 left"));
    // Two of the 12 cells only: Code_Aster's alarm.
    assert!(mess.contains("<A> CREA_MAILLAGE: QUAD_LINE changes 2 of the 12 cells of mesh MQ"), "{mess}");
    let ml = med::read_mesh(&out, Some("ML")).unwrap();
    assert_eq!(
        (ml.coords.clone(), ml.cells.clone(), ml.cell_types.clone()),
        (input.coords, input.cells, input.cell_types)
    );
    assert_eq!(ml.node_groups, input.node_groups);
    // BAS only: its middle nodes are still used by the quadrangles.
    let mp = med::read_mesh(&part, Some("MP")).unwrap();
    assert_eq!(mp.nnodes(), 21);
    assert_eq!(mp.cell_type_counts()[&CellType::Seg2], 2);
}

#[test]
fn quad_line_of_a_quadratic_legacy_mesh_keeps_the_vertices_in_order() {
    let (Some(mesh),) = (mesh("sslp02b.mmed"),) else { return };
    let all: Vec<usize> = (0..mesh.ncells()).collect();
    let l = quad_to_line(&mesh, &all);
    let m = &l.mesh;
    // Every remaining node is a vertex of a cell; the numbering keeps the old order.
    let mut used = vec![false; m.nnodes()];
    m.cells.iter().flatten().for_each(|&n| used[n] = true);
    assert!(used.iter().all(|&u| u));
    let vertices: BTreeSet<usize> =
        mesh.cells.iter().zip(&mesh.cell_types).flat_map(|(c, t)| c[..t.nvertices()].to_vec()).collect();
    assert_eq!(m.nnodes(), vertices.len());
    assert_eq!(l.removed, mesh.nnodes() - vertices.len());
    let old: Vec<usize> = vertices.into_iter().collect();
    for (new, &o) in old.iter().enumerate() {
        assert_eq!(m.coords[new], mesh.coords[o]);
    }
    for (g, members) in &m.node_groups {
        let want: Vec<usize> = mesh.node_groups[g].iter().filter_map(|n| old.binary_search(n).ok()).collect();
        assert_eq!(members, &want, "group {g}");
    }
}

#[test]
fn crea_maillage_errors_are_located_and_name_what_they_refuse() {
    let dir = scratch!("errors");
    let (_, box_med) = quad4_box(&dir);
    let cases = [
        (
            "group",
            r#"MQ = CREA_MAILLAGE(MAILLAGE=MA, LINE_QUAD=_F(GROUP_MA="NOPE"))"#,
            "LINE_QUAD/GROUP_MA: group of cells 'NOPE' is not in mesh MA",
        ),
        (
            "coqu",
            r#"MQ = CREA_MAILLAGE(MAILLAGE=MA, COQU_VOLU=_F(NOM="V", GROUP_MA="SURFACE", EPAIS=1.0, PLAN="SUP"))"#,
            "COQU_VOLU: not supported yet",
        ),
        (
            "titre",
            r#"MQ = CREA_MAILLAGE(MAILLAGE=MA, LINE_QUAD=_F(TOUT="OUI"), TITRE="T")"#,
            "TITRE: not supported yet",
        ),
        (
            "long",
            r#"MQ = CREA_MAILLAGE(MAILLAGE=MA, LINE_QUAD=_F(TOUT="OUI", PREF_NOEUD="LONGNAME"))"#,
            "LINE_QUAD/PREF_NOEUD: node name 'LONGNAME1' would be longer than 8 characters",
        ),
        (
            "clash",
            r#"MQ = CREA_MAILLAGE(MAILLAGE=MA, LINE_QUAD=_F(TOUT="OUI", PREF_NOEUD="N", PREF_NUME=3))"#,
            "new node N3: a node of mesh MA already has this name",
        ),
    ];
    for (tag, call, want) in cases {
        let src = format!("DEBUT()\nMA = LIRE_MAILLAGE(UNITE=20)\n{call}\nFIN()\n");
        let o = run_comm(&dir, tag, &src, &[(20, &box_med)]);
        let (out, err) = text(&o);
        assert_eq!(o.status.code(), Some(2), "{tag}: {out}{err}");
        let all = format!("{out}{err}");
        assert!(all.contains(want), "{tag}: expected '{want}' in:\n{all}");
        assert!(all.contains(&format!("{tag}.comm:3:")), "{tag}: not located:\n{all}");
    }
}

#[test]
fn line_quad_with_2020_prefixes_names_nodes_from_pref_noeud() {
    let dir = scratch!("pref");
    let (_, box_med) = quad4_box(&dir);
    let out = dir.join("mq.med");
    run_ok(
        &dir,
        "pref",
        r#"DEBUT()
MA = LIRE_MAILLAGE(UNITE=20)
MQ = CREA_MAILLAGE(MAILLAGE=MA, LINE_QUAD=_F(TOUT="OUI", PREF_NOEUD="NS", PREF_NUME=5))
IMPR_RESU(FORMAT="MED", UNITE=81, RESU=_F(MAILLAGE=MQ))
FIN()
"#,
        &[(20, &box_med), (81, &out)],
    );
    let m = med::read_mesh(&out, None).unwrap();
    assert_eq!(m.node_names[9..], (5..17).map(|i| format!("NS{i}")).collect::<Vec<_>>()[..]);
}

/// A 2 x 1 box of QUAD8 cells (SEG3 boundaries M1..M6, QUAD8 M7, M8), written for LIRE_MAILLAGE.
fn quad8_box(dir: &Path) -> (Mesh, std::path::PathBuf) {
    let m = box_mesh(CellType::Quad8, &[2, 1], &[2.0, 1.0]).unwrap();
    let p = dir.join("box8.med");
    med::write_mesh(&p, &m, "MA").unwrap();
    (med::read_mesh(&p, None).unwrap(), p)
}

#[test]
fn crea_maille_crea_poi1_modi_maille_and_restreint_through_med() {
    let dir = scratch!("derive");
    let (input, box_med) = quad8_box(&dir);
    let units: Vec<(i64, std::path::PathBuf)> = (81..=84).map(|u| (u, dir.join(format!("u{u}.med")))).collect();
    let mut all_units: Vec<(i64, &Path)> = vec![(20, box_med.as_path())];
    all_units.extend(units.iter().map(|(u, p)| (*u, p.as_path())));
    let mess = run_ok(
        &dir,
        "derive",
        r#"DEBUT()
MA = LIRE_MAILLAGE(UNITE=20)
M1 = CREA_MAILLAGE(MAILLAGE=MA, CREA_MAILLE=(_F(NOM="COPIE", GROUP_MA="SURFACE"), _F(NOM="UN", MAILLE="M2")))
M2 = CREA_MAILLAGE(MAILLAGE=MA, CREA_POI1=(_F(NOM_GROUP_MA="PG", GROUP_NO="GAUCHE"), _F(NOEUD=("N1", "N13"))))
M3 = CREA_MAILLAGE(MAILLAGE=MA, MODI_MAILLE=_F(TOUT="OUI", OPTION="QUAD8_9"))
M4 = CREA_MAILLAGE(MAILLAGE=MA, RESTREINT=_F(GROUP_MA="DROITE", GROUP_NO="BAS", TOUT_GROUP_NO="OUI"))
# Code_Aster 2025: no TOUT / GROUP_MA means TOUT='OUI'.
M5 = CREA_MAILLAGE(MAILLAGE=MA, CREA_MAILLE=_F(NOM="TOUTES"))
M6 = CREA_MAILLAGE(MAILLAGE=MA, QUAD_LINE=_F())
IMPR_RESU(FORMAT="MED", UNITE=81, RESU=_F(MAILLAGE=M1))
IMPR_RESU(FORMAT="MED", UNITE=82, RESU=_F(MAILLAGE=M2))
IMPR_RESU(FORMAT="MED", UNITE=83, RESU=_F(MAILLAGE=M3))
IMPR_RESU(FORMAT="MED", UNITE=84, RESU=_F(MAILLAGE=M4))
FIN()
"#,
        &all_units,
    );
    assert!(mess.contains("CREA_MAILLAGE/CREA_MAILLE on MA: copies in COPIE (2 cells), UN (1 cells)"), "{mess}");
    assert!(mess.contains("CREA_MAILLAGE/CREA_MAILLE on MA: copies in TOUTES (8 cells)"), "{mess}");
    assert!(
        mess.contains("CREA_MAILLAGE/QUAD_LINE on MA: 6 SEG3 -> SEG2, 2 QUAD8 -> QUAD4; 7 nodes removed"),
        "{mess}"
    );
    assert!(!mess.contains("QUAD_LINE changes"), "{mess}");
    let read = |u: i64, name: &str| med::read_mesh(&units[(u - 81) as usize].1, Some(name)).unwrap();

    // Read back, cells come type by type: the names written by IMPR_RESU tell them apart.
    let cell = |m: &Mesh, name: &str| m.cell_names.iter().position(|n| n == name).unwrap();
    let names = |m: &Mesh, cells: &[usize]| cells.iter().map(|&c| m.cell_names[c].clone()).collect::<Vec<_>>();

    // CREA_MAILLE: M9, M10 copy M7, M8 (group COPIE), M11 copies M2 (group UN).
    let m1 = read(81, "M1");
    assert_eq!(m1.ncells(), 11);
    for (copy, of) in [("M9", 6), ("M10", 7), ("M11", 1)] {
        assert_eq!(m1.cells[cell(&m1, copy)], input.cells[of], "{copy}");
        assert_eq!(m1.cell_types[cell(&m1, copy)], input.cell_types[of], "{copy}");
    }
    assert_eq!(names(&m1, &m1.cell_groups["COPIE"]), ["M9", "M10"]);
    assert_eq!(names(&m1, &m1.cell_groups["UN"]), ["M11"]);

    // CREA_POI1: POI1 on the nodes of GAUCHE and N13, in node order, numbered after the 8 cells; the
    // POI1 cells come first when read back (POI1 is Code_Aster's first type).
    let m2 = read(82, "M2");
    let gauche = &input.node_groups["GAUCHE"];
    let mut on: Vec<usize> = gauche.clone();
    on.push(12);
    on.sort();
    on.dedup();
    assert_eq!(m2.ncells(), 8 + on.len());
    let pois: Vec<(String, usize)> = (0..m2.ncells())
        .filter(|&c| m2.cell_types[c] == CellType::Poi1)
        .map(|c| (m2.cell_names[c].clone(), m2.cells[c][0]))
        .collect();
    let want: Vec<(String, usize)> = on.iter().enumerate().map(|(k, &n)| (format!("M{}", 9 + k), n)).collect();
    assert_eq!(pois, want);
    let pg: Vec<usize> = m2.cell_groups["PG"].iter().map(|&c| m2.cells[c][0]).collect();
    assert_eq!(&pg, gauche);

    // MODI_MAILLE QUAD8_9: centres N14 (M7) and N15 (M8) at the middle of each square.
    let m3 = read(83, "M3");
    assert_eq!(m3.nnodes(), input.nnodes() + 2);
    assert_eq!(m3.cell_types[6..], [CellType::Quad9, CellType::Quad9]);
    assert_eq!((m3.cells[6][8], m3.cells[7][8]), (13, 14));
    assert_eq!(m3.node_names[13..], ["N14", "N15"]);
    assert_eq!(m3.coords[13], [0.5, 0.5, 0.0]);
    assert_eq!(m3.coords[14], [1.5, 0.5, 0.0]);

    // RESTREINT: the SEG3 of DROITE (nodes in its local order), then the nodes of BAS in increasing order.
    let m4 = read(84, "M4");
    assert_eq!(m4.ncells(), 1);
    assert_eq!(m4.cell_names, ["M1"]);
    let seg = &input.cells[input.cell_groups["DROITE"][0]];
    let mut order: Vec<usize> = seg.clone();
    order.extend(input.node_groups["BAS"].iter().filter(|n| !seg.contains(n)));
    let coords: Vec<[f64; 3]> = order.iter().map(|&n| input.coords[n]).collect();
    assert_eq!(m4.coords, coords);
    assert_eq!(m4.cell_groups.keys().collect::<Vec<_>>(), ["DROITE"]);
    // TOUT_GROUP_NO: every node group with a kept node, reduced to those (MED keeps no member order).
    for (g, members) in &input.node_groups {
        let mut kept: Vec<usize> = members.iter().filter_map(|n| order.iter().position(|o| o == n)).collect();
        kept.sort_unstable();
        assert_eq!(m4.node_groups.get(g).cloned().unwrap_or_default(), kept, "{g}");
    }
    assert_eq!(m4.node_groups["DROITE"], vec![0, 1, 2]);
}

#[test]
fn derived_meshes_refuse_2020_naming_and_missing_cell_types() {
    let dir = scratch!("derive_errors");
    let (_, box_med) = quad8_box(&dir);
    let cases = [
        (
            "pref",
            r#"M = CREA_MAILLAGE(MAILLAGE=MA, CREA_MAILLE=_F(NOM="C", TOUT="OUI", PREF_MAILLE="MS"))"#,
            "CREA_MAILLE/PREF_MAILLE: not supported yet",
        ),
        (
            "tria7",
            r#"M = CREA_MAILLAGE(MAILLAGE=MA, MODI_MAILLE=_F(TOUT="OUI", OPTION="TRIA6_7"))"#,
            "MODI_MAILLE/OPTION: OPTION='TRIA6_7' is not supported yet",
        ),
        (
            "exists",
            r#"M = CREA_MAILLAGE(MAILLAGE=MA, CREA_MAILLE=_F(NOM="SURFACE", TOUT="OUI"))"#,
            "CREA_MAILLE/NOM: group of cells 'SURFACE' already exists in mesh MA",
        ),
        (
            "twice",
            r#"M = CREA_MAILLAGE(MAILLAGE=MA, CREA_POI1=(_F(NOM_GROUP_MA="P", TOUT="OUI"), _F(NOM_GROUP_MA="P", NOEUD="N1")))"#,
            "CREA_POI1/NOM_GROUP_MA: group of cells 'P' already exists",
        ),
        (
            "nonode",
            r#"M = CREA_MAILLAGE(MAILLAGE=MA, CREA_POI1=_F(NOEUD="N99"))"#,
            "CREA_POI1/NOEUD: node 'N99' is not in mesh MA",
        ),
        (
            "hexa27",
            r#"M = CREA_MAILLAGE(MAILLAGE=MA, HEXA20_27=_F(TOUT="OUI", PREF_NOEUD="NS"))"#,
            "HEXA20_27/PREF_NOEUD: not supported yet",
        ),
        ("hho", r#"M = CREA_MAILLAGE(MAILLAGE=MA, MODI_HHO=_F(TOUT="OUI"))"#, "MODI_HHO: not supported yet"),
    ];
    for (tag, call, want) in cases {
        let src = format!("DEBUT()\nMA = LIRE_MAILLAGE(UNITE=20)\n{call}\nFIN()\n");
        let o = run_comm(&dir, tag, &src, &[(20, &box_med)]);
        let (out, err) = text(&o);
        assert_eq!(o.status.code(), Some(2), "{tag}: {out}{err}");
        let all = format!("{out}{err}");
        assert!(all.contains(want), "{tag}: expected '{want}' in:\n{all}");
        assert!(all.contains(&format!("{tag}.comm:3:")), "{tag}: not located:\n{all}");
    }
}

#[test]
fn hexa20_27_through_med() {
    let dir = scratch!("hexa27");
    let m = box_mesh(CellType::Hexa20, &[2, 1, 1], &[2.0, 1.0, 1.0]).unwrap();
    let p = dir.join("h20.med");
    med::write_mesh(&p, &m, "MA").unwrap();
    let input = med::read_mesh(&p, None).unwrap();
    let out = dir.join("h27.med");
    let mess = run_ok(
        &dir,
        "h27",
        r#"DEBUT()
MA = LIRE_MAILLAGE(UNITE=20)
MB = CREA_MAILLAGE(MAILLAGE=MA, HEXA20_27=_F())
IMPR_RESU(FORMAT="MED", UNITE=81, RESU=_F(MAILLAGE=MB))
FIN()
"#,
        &[(20, &p), (81, &out)],
    );
    assert!(
        mess.contains("CREA_MAILLAGE/HEXA20_27 on MA: 10 QUAD8 -> QUAD9, 2 HEXA20 -> HEXA27; 13 nodes created"),
        "{mess}"
    );
    let want = aster::mesh::convert::hexa20_to_27(&input, &(0..input.ncells()).collect::<Vec<_>>()).mesh;
    let got = med::read_mesh(&out, None).unwrap();
    assert_eq!(got.coords, want.coords);
    assert_eq!(got.cells, want.cells);
    assert_eq!(got.cell_types, want.cell_types);
    assert_eq!(got.node_names, want.node_names);
}

/// Code_Aster 2025 builds CREA_MAILLAGE's mesh without names: on a `.mail` mesh whose nodes are named
/// N8, N7, N6, N5 (the new nodes' numbers), LINE_QUAD's mesh numbers every node, and NOEUD='N1' then
/// designates its first node, the file's N8. In the 2020 syntax the names stay and a clash stops.
#[test]
fn crea_maillage_of_a_named_mesh_numbers_its_nodes_as_code_aster_2025() {
    let dir = scratch!("named");
    let mail = dir.join("named.mail");
    std::fs::write(
        &mail,
        "TITRE\nNAMED\nFINSF\nCOOR_2D\n  N8 0.0 0.0\n  N7 2.0 0.0\n  N6 2.0 1.0\n  N5 0.0 1.0\nFINSF\n\
         QUAD4\n  Q1 N8 N7 N6 N5\nFINSF\nSEG2\n  S1 N8 N7\nFINSF\nFIN\n",
    )
    .unwrap();
    let out = dir.join("mq.med");
    let mess = run_ok(
        &dir,
        "named",
        r#"DEBUT()
MA = LIRE_MAILLAGE(FORMAT="ASTER", UNITE=20)
MQ = CREA_MAILLAGE(MAILLAGE=MA, LINE_QUAD=_F(TOUT="OUI"))
MQ = DEFI_GROUP(reuse=MQ, MAILLAGE=MQ, INFO=2, CREA_GROUP_NO=(_F(NOM="FIRST", NOEUD="N1"), _F(NOM="MID", NOEUD="N5")),
                CREA_GROUP_MA=_F(NOM="SEG", MAILLE="M2"))
IMPR_RESU(FORMAT="MED", UNITE=81, RESU=_F(MAILLAGE=MQ))
FIN()
"#,
        &[(20, &mail), (81, &out)],
    );
    assert!(mess.contains("5 to N8") || mess.contains("N5 to N8"), "{mess}");
    let m = med::read_mesh(&out, None).unwrap();
    assert_eq!(m.nnodes(), 8);
    let at = |g: &str| m.coords[m.node_groups[g][0]];
    assert_eq!(at("FIRST"), [0.0, 0.0, 0.0], "N1 is the first node, the file's N8");
    // The first new node is the middle of the first edge of Q1 (N8-N7 in the file).
    assert_eq!(at("MID"), [1.0, 0.0, 0.0]);
    assert_eq!(m.cell_types[m.cell_groups["SEG"][0]], CellType::Seg3, "M2 is the second cell, S1");
    // The 2020 syntax keeps the names: PREF_NOEUD='N' from 5 clashes with the file's N5.
    let o = run_comm(
        &dir,
        "clash",
        "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='ASTER', UNITE=20)\n\
         MQ = CREA_MAILLAGE(MAILLAGE=MA, LINE_QUAD=_F(TOUT='OUI', PREF_NOEUD='N', PREF_NUME=5))\nFIN()\n",
        &[(20, &mail)],
    );
    let (o_out, o_err) = text(&o);
    assert!(
        !o.status.success() && o_err.contains("new node N5: a node of mesh MA already has this name"),
        "{o_out}{o_err}"
    );
}
