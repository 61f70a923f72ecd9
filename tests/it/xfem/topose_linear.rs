//! TOPOSE sub-cell cutting of LINEAR X-FEM parents (`topose_linear`) on the
//! meshes of the linear X-FEM tests, read in place from `../shared/astest`:
//! ssnv173f (QUAD4, LN = Y−2.5), ssnv173b / wtnv143c (HEXA8, LN = Z−12.5),
//! ssnv511a / ssnv511c (QUAD4 / HEXA8, three interfaces with junctions as in
//! ssnv513a / ssnv513c), ssnv186c (TRIA3, LN = Y−17.5) and ssnp118t (QUAD4,
//! inclined interface, GROUP_MA_ENRI). For every X-FEM parent: the
//! sub-cells fill the parent, every sub-cell lies on one side of each crack
//! it sees (he ≠ 0), tetrahedra are positive.
//! Every test prints a message and passes when `../shared` is absent.

use crate::common::*;
use aster::fem::reference::jacobian_det;
use aster::mesh::{CellType, Mesh};
use aster::xfem::postmail::base36;
use aster::xfem::topose::{CrackInCell, Cutting, PointId};
use aster::xfem::topose_linear::topose_linear;
use aster::xfem::{build_interface, Crack};
use std::collections::{BTreeMap, HashMap};
use std::rc::Rc;

/// One DEFI_FISS_XFEM: the level set, and JONCTION (index of the master in
/// the list, POINT).
struct Fiss {
    ln: fn(&[f64; 3]) -> f64,
    junction: Option<(usize, [f64; 3])>,
}

struct Case {
    mesh: Rc<Mesh>,
    /// Per X-FEM parent: the level sets of its cracks at its nodes.
    lsn: BTreeMap<usize, Vec<Vec<f64>>>,
    cuttings: BTreeMap<usize, Cutting>,
}

fn run(file: &str, enri_group: Option<&str>, fiss: &[Fiss]) -> Option<Case> {
    let m = mesh(file)?;
    let enri = enri_group.map(|g| m.cell_groups[g].clone());
    let mut cracks: Vec<Rc<Crack>> = Vec::new();
    for (i, f) in fiss.iter().enumerate() {
        let l = m.coords.iter().map(f.ln).collect();
        let (masters, point) = match &f.junction {
            Some((k, p)) => (vec![(format!("FISS{}", k + 1), cracks[*k].clone())], Some(&p[..m.dim])),
            None => (vec![], None),
        };
        let k = build_interface("MA".into(), m.clone(), l, enri.clone(), &masters, point)
            .unwrap_or_else(|e| panic!("{file}: FISS{}: {}", i + 1, e.msg));
        cracks.push(Rc::new(k));
    }
    let refs: Vec<_> = cracks.clone();
    // The first declared master of each crack, as MODI_MODELE_XFEM sees it.
    let masters: Vec<Option<(usize, f64)>> = refs
        .iter()
        .map(|k| k.master().map(|(mm, coef)| (cracks.iter().position(|g| Rc::ptr_eq(g, mm)).unwrap(), coef)))
        .collect();
    let mut cuttings = BTreeMap::new();
    let mut lsns = BTreeMap::new();
    for c in (0..m.ncells()).filter(|&c| m.cell_types[c].dim() == m.dim) {
        let seen: Vec<usize> =
            (0..cracks.len()).filter(|&g| refs[g].heaviside_cells.binary_search(&c).is_ok()).collect();
        if seen.is_empty() {
            continue;
        }
        let nodes = &m.cells[c];
        let cic: Vec<CrackInCell> = seen
            .iter()
            .map(|&g| CrackInCell {
                lsn: nodes.iter().map(|&n| refs[g].lsn[n]).collect(),
                master: masters[g].and_then(|(mm, coef)| seen.iter().position(|&s| s == mm).map(|p| (p, coef))),
            })
            .collect();
        let coords: Vec<[f64; 3]> = nodes.iter().map(|&n| m.coords[n]).collect();
        let cut = topose_linear(m.cell_types[c], &coords, &cic)
            .unwrap_or_else(|e| panic!("{file}: {}: {e}", m.cell_names[c]));
        lsns.insert(c, cic.into_iter().map(|k| k.lsn).collect());
        cuttings.insert(c, cut);
    }
    drop(refs);
    Some(Case { mesh: m, lsn: lsns, cuttings })
}

fn sub(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [b[0] - a[0], b[1] - a[1], b[2] - a[2]]
}

/// Signed area (TRIA3) or volume (TETRA4) of a sub-cell.
fn measure(p: &[[f64; 3]]) -> f64 {
    let (u, v) = (sub(&p[0], &p[1]), sub(&p[0], &p[2]));
    if p.len() == 3 {
        (u[0] * v[1] - u[1] * v[0]) / 2.0
    } else {
        let w = sub(&p[0], &p[3]);
        let c = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
        (c[0] * w[0] + c[1] * w[1] + c[2] * w[2]) / 6.0
    }
}

/// Area or volume of a parent: Gauss rule exact for the (bi/tri)linear map.
fn parent_measure(m: &Mesh, c: usize) -> f64 {
    let t = m.cell_types[c];
    let x: Vec<[f64; 3]> = m.cells[c].iter().map(|&n| m.coords[n]).collect();
    let g = 1.0 / 3f64.sqrt();
    match t {
        CellType::Tria3 => measure(&x).abs(),
        CellType::Quad4 => {
            let mut s = 0.0;
            for (a, b) in [(-g, -g), (g, -g), (g, g), (-g, g)] {
                s += jacobian_det(t, &x, &[a, b, 0.0], 2);
            }
            s.abs()
        }
        CellType::Hexa8 => {
            let mut s = 0.0;
            for k in 0..8 {
                let xi =
                    [if k & 1 == 0 { -g } else { g }, if k & 2 == 0 { -g } else { g }, if k & 4 == 0 { -g } else { g }];
                s += jacobian_det(t, &x, &xi, 3);
            }
            s.abs()
        }
        _ => panic!("{}: unexpected parent type {}", m.cell_names[c], t.name()),
    }
}

/// The checks of every X-FEM parent; returns (parents, cut parents, sub-cells).
fn check(case: &Case) -> (usize, usize, usize) {
    let m = &case.mesh;
    let mut ncut = 0;
    for (&c, cut) in &case.cuttings {
        let name = &m.cell_names[c];
        let mut total = 0.0;
        for s in &cut.subcells {
            let p: Vec<[f64; 3]> = s.nodes.iter().map(|&i| cut.points[i].x).collect();
            assert_eq!(p.len(), m.dim + 1, "{name}: sub-cell with {} nodes", p.len());
            let v = measure(&p);
            if m.dim == 3 {
                assert!(v > 0.0, "{name}: sub-tetrahedron of volume {v}");
            }
            total += v.abs();
        }
        let vol = parent_measure(m, c);
        assert!((total - vol).abs() <= 1e-12 * vol, "{name}: {total} vs {vol}");
        for (k, s) in cut.subcells.iter().enumerate() {
            for (f, &h) in s.he.iter().enumerate() {
                if h == 0 {
                    continue;
                }
                for &i in &s.nodes {
                    let v = cut.points[i].lsn[f];
                    assert!(v * h as f64 >= -1e-10, "{name}: sub-cell {k}, crack {f}: lsn {v} against he {h}");
                }
            }
        }
        for p in &cut.points {
            if let Some(k) = p.id.node() {
                for (f, l) in case.lsn[&c].iter().enumerate() {
                    assert_eq!(p.lsn[f], l[k]);
                }
            }
        }
        if cut.subcells.len() > if m.dim == 2 { 2 } else { 6 }
            || cut.points.iter().any(|p| matches!(p.id, PointId::Intersection(_)))
        {
            ncut += 1;
        }
    }
    let nsub = case.cuttings.values().map(|c| c.subcells.len()).sum();
    (case.cuttings.len(), ncut, nsub)
}

/// The new nodes of POST_MAIL_XFEM for the X-FEM parents (`xpomax` /
/// `xpoajm` / `xpoajn`, as `postmail::visual_mesh` does for quadratic
/// parents): one node per (point, Heaviside tuple) of a parent, a global
/// counter in base 36, NM / NP on a crack (side of the nearest crack active
/// on the sub-cell), NX elsewhere. Only the X-FEM parents of the mesh's
/// dimension are counted. Returns (name, coordinates, in NFISSU).
fn names(case: &Case) -> Vec<(String, [f64; 3], bool)> {
    let mut out = Vec::new();
    for cut in case.cuttings.values() {
        let mut seen: HashMap<(usize, Vec<i32>), ()> = HashMap::new();
        for s in &cut.subcells {
            for &pi in &s.nodes {
                if seen.insert((pi, s.he.clone()), ()).is_some() {
                    continue;
                }
                let p = &cut.points[pi];
                let on = matches!(p.id, PointId::Intersection(_)) || p.lsn.contains(&0.0);
                let prefix = if !on {
                    "NX"
                } else {
                    let mut best = None;
                    let mut min = f64::MAX;
                    for (k, (&v, &h)) in p.lsn.iter().zip(&s.he).enumerate() {
                        if v.abs() < min && h != 0 {
                            min = v.abs();
                            best = Some(k);
                        }
                    }
                    match best {
                        Some(k) if s.he[k] == -1 => "NM",
                        _ => "NP",
                    }
                };
                out.push((format!("{prefix}{}", base36(out.len() + 1)), p.x, on));
            }
        }
    }
    out
}

fn report(file: &str, case: &Case) {
    let (n, ncut, nsub) = check(case);
    let types: Vec<&str> = {
        let mut t: Vec<&str> = case.cuttings.keys().map(|&c| case.mesh.cell_types[c].name()).collect();
        t.dedup();
        t
    };
    println!("{file}: {n} X-FEM parents {types:?}, {ncut} cut, {nsub} sub-cells");
}

#[test]
fn ssnv173f_quad4_one_interface() {
    let Some(case) = run("ssnv173f.mmed", None, &[Fiss { ln: |x| x[1] - 2.5, junction: None }]) else { return };
    report("ssnv173f", &case);
    assert!(case.cuttings.keys().all(|&c| case.mesh.cell_types[c] == CellType::Quad4));
    let nodes = names(&case);
    let nfissu: Vec<&(String, [f64; 3], bool)> = nodes.iter().filter(|n| n.2).collect();
    assert!(!nfissu.is_empty());
    // Every node on the interface is at y = 2.5, NM below / NP above it: as many of each.
    for (name, x, _) in &nfissu {
        assert!((x[1] - 2.5).abs() < 1e-12, "{name} at {x:?}");
        assert!(name.starts_with("NM") || name.starts_with("NP"));
    }
    let nm = nfissu.iter().filter(|n| n.0.starts_with("NM")).count();
    assert_eq!(2 * nm, nfissu.len());
    println!(
        "ssnv173f: {} new nodes, NFISSU {} (NM {nm}): {:?}",
        nodes.len(),
        nfissu.len(),
        nfissu.iter().map(|n| (n.0.as_str(), n.1[0])).collect::<Vec<_>>()
    );
}

#[test]
fn ssnv173b_hexa8_one_interface() {
    let Some(case) = run("ssnv173b.mmed", None, &[Fiss { ln: |x| x[2] - 12.5, junction: None }]) else { return };
    report("ssnv173b", &case);
}

/// wtnv143c itself goes quadratic (LINE_QUAD) before DEFI_FISS_XFEM
/// (LN = Z−2.5): its linear HEXA8 mesh is only a geometry check here.
#[test]
fn wtnv143c_linear_mesh_hexa8_one_interface() {
    let Some(case) = run("wtnv143c.mmed", None, &[Fiss { ln: |x| x[2] - 2.5, junction: None }]) else { return };
    report("wtnv143c (linear mesh)", &case);
}

/// The three interfaces of ssnv513a / ssnv513c: FISS2 branches on FISS1
/// (POINT (0,−5)), FISS3 on FISS2 (POINT (5,0)).
fn three_cracks() -> [Fiss; 3] {
    [
        Fiss { ln: |x| x[1] - 1.0 - 0.5 * x[0], junction: None },
        Fiss { ln: |x| x[0], junction: Some((0, [0.0, -5.0, 0.0])) },
        Fiss { ln: |x| x[1], junction: Some((1, [5.0, 0.0, 0.0])) },
    ]
}

/// The sub-domains of a junction cell: the tuples of Heaviside values.
fn tuples(case: &Case) -> BTreeMap<Vec<i32>, usize> {
    let mut t = BTreeMap::new();
    for cut in case.cuttings.values() {
        for s in &cut.subcells {
            if s.he.len() == 3 {
                *t.entry(s.he.clone()).or_insert(0) += 1;
            }
        }
    }
    t
}

#[test]
fn ssnv511a_quad4_three_interfaces_with_junctions() {
    let Some(case) = run("ssnv511a.mmed", None, &three_cracks()) else { return };
    report("ssnv511a", &case);
    let t = tuples(&case);
    println!("ssnv511a: sub-cells per (he1, he2, he3) in cells seeing the 3 cracks: {t:?}");
    // Four regions: above FISS1; below it, x < 0; x > 0 above FISS3; x > 0 below it.
    for he in t.keys() {
        assert!(
            [vec![1, 0, 0], vec![-1, -1, 0], vec![-1, 1, 1], vec![-1, 1, -1]].contains(he),
            "unexpected Heaviside tuple {he:?}"
        );
    }
    let nodes = names(&case);
    let nfissu: Vec<&(String, [f64; 3], bool)> = nodes.iter().filter(|n| n.2).collect();
    println!("ssnv511a (ssnv513a): {} new nodes, NFISSU {}", nodes.len(), nfissu.len());
    // The ssnv513a filters: NP nodes with x > 0.2, y < 0.2 (on FISS3, upper lip) ...
    let np_f3: Vec<&&(String, [f64; 3], bool)> =
        nfissu.iter().filter(|n| n.0.starts_with("NP") && n.1[0] > 0.2 && n.1[1] < 0.2).collect();
    let nm_f3: Vec<&&(String, [f64; 3], bool)> =
        nfissu.iter().filter(|n| n.0.starts_with("NM") && n.1[0] > 0.02 && n.1[1] < 0.2).collect();
    println!("  NP, x > 0.2, y < 0.2: {:?}", np_f3.iter().map(|n| (n.0.as_str(), n.1[0], n.1[1])).collect::<Vec<_>>());
    println!("  NM, x > 0.02, y < 0.2: {:?}", nm_f3.iter().map(|n| (n.0.as_str(), n.1[0], n.1[1])).collect::<Vec<_>>());
    for n in np_f3.iter().chain(&nm_f3) {
        assert!(n.1[1].abs() < 1e-12, "{} at {:?} is not on FISS3", n.0, n.1);
    }
    let lips = |p: &str| nfissu.iter().filter(|n| n.0.starts_with(p)).count();
    println!("  NFISSU: NP {}, NM {}", lips("NP"), lips("NM"));
}

#[test]
fn ssnv511c_hexa8_three_interfaces_with_junctions() {
    let Some(case) = run("ssnv511c.mmed", None, &three_cracks()) else { return };
    report("ssnv511c", &case);
    let t = tuples(&case);
    println!("ssnv511c: sub-cells per (he1, he2, he3) in cells seeing the 3 cracks: {t:?}");
    for he in t.keys() {
        assert!(
            [vec![1, 0, 0], vec![-1, -1, 0], vec![-1, 1, 1], vec![-1, 1, -1]].contains(he),
            "unexpected Heaviside tuple {he:?}"
        );
    }
}

#[test]
fn ssnv186c_tria3_one_interface() {
    let Some(case) = run("ssnv186c.mmed", None, &[Fiss { ln: |x| x[1] - 17.5, junction: None }]) else { return };
    report("ssnv186c", &case);
    assert!(case.cuttings.keys().all(|&c| case.mesh.cell_types[c] == CellType::Tria3));
}

#[test]
fn ssnp118t_quad4_inclined_interface() {
    let Some(case) = run(
        "ssnp118t.mmed",
        Some("G_CUBE"),
        &[Fiss {
            ln: |x| {
                let t = 30f64.to_radians();
                x[0] * t.cos() + x[1] * t.sin() - 0.4
            },
            junction: None,
        }],
    ) else {
        return;
    };
    report("ssnp118t", &case);
}

/// The model of ssnv245a / ssnv173f on TOUT of ssnv173f.mmed: the X-FEM
/// parents are the QUAD4 cells and the boundary SEG2 cells with a
/// Heaviside node (te0514 with ndime < ndim), all in one ascending
/// traversal of POST_MAIL_XFEM.
fn visual_tout(ln: fn(&[f64; 3]) -> f64) -> Option<aster::xfem::postmail::VisualMesh> {
    use aster::xfem::postmail::{visual_mesh, Prefixes};
    use aster::xfem::topose_linear::{orient_boundary, topose_linear_boundary};
    let m = mesh("ssnv173f.mmed")?;
    let l = m.coords.iter().map(ln).collect();
    let k = build_interface("MA".into(), m.clone(), l, None, &[], None).unwrap_or_else(|e| panic!("{}", e.msg));
    let mut cuttings = BTreeMap::new();
    let model: Vec<usize> = (0..m.ncells()).filter(|&c| m.cell_types[c] != CellType::Poi1).collect();
    for &c in &model {
        if k.heaviside_cells.binary_search(&c).is_err() {
            continue;
        }
        let nodes = &m.cells[c];
        let cic = [CrackInCell { lsn: nodes.iter().map(|&n| k.lsn[n]).collect(), master: None }];
        let coords: Vec<[f64; 3]> = nodes.iter().map(|&n| m.coords[n]).collect();
        let cut = if m.cell_types[c].dim() < m.dim {
            topose_linear_boundary(m.cell_types[c], m.dim, &coords, &cic)
        } else {
            topose_linear(m.cell_types[c], &coords, &cic)
        }
        .unwrap_or_else(|e| panic!("{}: {e}", m.cell_names[c]));
        let mut cut = cut;
        if m.cell_types[c].dim() < m.dim {
            // xoripe: outward of the support cell.
            let v = (0..m.ncells())
                .find(|&v| m.cell_types[v].dim() == m.dim && nodes.iter().all(|n| m.cells[v].contains(n)))
                .unwrap();
            let g = |cs: &[usize]| [0, 1, 2].map(|j| cs.iter().map(|&n| m.coords[n][j]).sum::<f64>() / cs.len() as f64);
            let (gb, gp) = (g(nodes), g(&m.cells[v]));
            orient_boundary(&mut cut, m.dim, &[0, 1, 2].map(|j| gb[j] - gp[j]));
        }
        cuttings.insert(c, cut);
    }
    Some(visual_mesh(&m, &model, &cuttings, &Prefixes::default()).unwrap())
}

/// ssnv245a (D_PLAN on TOUT of ssnv173f.mmed, LN = Y − 2.6): the boundary
/// SEG2 cells come first in the mesh (MED type order), M8 (uncut, on the
/// enriched node N6) makes NX1, NX2; M9 (N6 → N7, x = 1) is cut at
/// (1, 2.6) into (101, N6) and (101, N7), and xoripe turns the first one
/// outward, (N6, 101): NX3, NM4, NP5, NX6 — the NP5 (DX = −0.024, upper
/// lip) and NM4 (DX = +0.026, lower lip) that ssnv245a tests. On LIG4 (x = 0)
/// M15 (N10 → N11) is turned too, (N10, 101), (101, N11): NX11, NPC, NMD,
/// NX14; the QUAD4 parents follow.
#[test]
fn ssnv245a_boundary_parents_name_np5_and_nm4() {
    let Some(v) = visual_tout(|x| x[1] - 2.6) else { return };
    let at = |name: &str| {
        let n = v.mesh.node_names.iter().position(|s| s == name).unwrap_or_else(|| panic!("{name} missing"));
        v.mesh.coords[n]
    };
    for name in ["NM4", "NP5"] {
        let x = at(name);
        assert!((x[0] - 1.0).abs() < 1e-12 && (x[1] - 2.6).abs() < 1e-12, "{name} at {x:?}");
    }
    for name in ["NPC", "NMD"] {
        let x = at(name);
        assert!(x[0].abs() < 1e-12 && (x[1] - 2.6).abs() < 1e-12, "{name} at {x:?}");
    }
    // Parents: M8, M9, M10 (LIG2), M14, M15, M16 (LIG4), then M2, M3, M4.
    let order: Vec<usize> = v.parents.iter().map(|p| p.cell).collect();
    assert_eq!(order, vec![2, 3, 4, 8, 9, 10, 13, 14, 15]);
    assert_eq!(v.parents[1].node_counters, 3..7);
    let g = &v.mesh.node_groups["NFISSU"];
    let names: Vec<&str> = g.iter().map(|&n| v.mesh.node_names[n].as_str()).collect();
    assert_eq!(&names[..4], &["NM4", "NP5", "NPC", "NMD"]);
    for &n in g {
        assert!((v.mesh.coords[n][1] - 2.6).abs() < 1e-12);
    }
}

/// ssnv173f's LN = Y − 2.5 on the model of ssnv245a (TOUT): the same
/// traversal; the boundary lip nodes are NM4 / NP5 (x = 1) and NPC / NMD
/// (x = 0), then the QUAD4 parent M3's.
#[test]
fn ssnv173f_level_set_with_boundary_parents() {
    let Some(v) = visual_tout(|x| x[1] - 2.5) else { return };
    let g = &v.mesh.node_groups["NFISSU"];
    let named: Vec<(&str, [f64; 3])> = g.iter().map(|&n| (v.mesh.node_names[n].as_str(), v.mesh.coords[n])).collect();
    assert_eq!(named[0].0, "NM4");
    assert_eq!(named[1].0, "NP5");
    assert_eq!(named[2].0, "NPC");
    assert_eq!(named[3].0, "NMD");
    for (name, x) in &named {
        assert!((x[1] - 2.5).abs() < 1e-12, "{name} at {x:?}");
    }
    let nm = named.iter().filter(|n| n.0.starts_with("NM")).count();
    assert_eq!(2 * nm, named.len());
}

/// The regions of ssnv513a's "F" (three interfaces, a junction chain
/// FISS3 → FISS2 → FISS1) are the same in every cell, also in cells that
/// cut a branch as a full interface because its master is not among their
/// cracks: exactly one region code per piece of the block, matching the
/// piece the sub-cell's centroid lies in.
#[test]
fn ssnv511a_regions_are_consistent_across_cells() {
    let Some(m) = mesh("ssnv511a.mmed") else { return };
    let ls = |f: &dyn Fn(&[f64; 3]) -> f64| -> Vec<f64> { m.coords.iter().map(f).collect() };
    let l1 = ls(&|x| x[1] - 1.0 - 0.5 * x[0]);
    let l2 = ls(&|x| x[0]);
    let l3 = ls(&|x| x[1]);
    let mk = |l: Vec<f64>, masters: &[(String, Rc<Crack>)], point: Option<&[f64]>| {
        Rc::new(build_interface("MA".into(), m.clone(), l, None, masters, point).unwrap())
    };
    let c1 = mk(l1.clone(), &[], None);
    let c2 = mk(l2.clone(), &[("FISS1".into(), c1.clone())], Some(&[0.0, -5.0]));
    let c3 = mk(l3.clone(), &[("FISS2".into(), c2.clone())], Some(&[5.0, 0.0]));
    let cracks = vec![c1.clone(), c2.clone(), c3.clone()];
    let coef = |c: &Rc<Crack>| c.master().unwrap().1;
    let masters = vec![None, Some((0, coef(&c2))), Some((1, coef(&c3)))];
    let lsn = vec![l1, l2, l3];
    let model_cells: Vec<usize> = (0..m.ncells()).filter(|&c| m.cell_types[c].dim() == 2).collect();
    let mut cuts = BTreeMap::new();
    for &c in &model_cells {
        let seen: Vec<usize> = (0..3).filter(|&g| cracks[g].heaviside_cells.binary_search(&c).is_ok()).collect();
        if seen.is_empty() {
            continue;
        }
        let nodes = &m.cells[c];
        let cic: Vec<CrackInCell> = seen
            .iter()
            .map(|&g| CrackInCell {
                lsn: nodes.iter().map(|&n| lsn[g][n]).collect(),
                master: masters[g].and_then(|(mm, k)| seen.iter().position(|&s| s == mm).map(|p| (p, k))),
            })
            .collect();
        let coords: Vec<[f64; 3]> = nodes.iter().map(|&n| m.coords[n]).collect();
        cuts.insert(c, (seen, topose_linear(m.cell_types[c], &coords, &cic).unwrap()));
    }
    let enriched: Vec<Vec<bool>> = cracks.iter().map(|c| (0..m.nnodes()).map(|n| c.enriched(n)).collect()).collect();
    let names = vec!["FISS1".into(), "FISS2".into(), "FISS3".into()];
    let xm = aster::xfem::model::XfemModel::new(
        &m,
        &model_cells,
        cracks,
        names,
        lsn,
        masters,
        enriched,
        aster::xfem::model::ContactKind::Sans,
        cuts,
        "AUTO",
    )
    .unwrap();
    let mut codes: BTreeMap<&str, std::collections::BTreeSet<i32>> = BTreeMap::new();
    for xc in xm.cells.values() {
        for (s, sc) in xc.cutting.subcells.iter().enumerate() {
            let centroid =
                |k: usize| sc.nodes.iter().map(|&p| xc.cutting.points[p].x[k]).sum::<f64>() / sc.nodes.len() as f64;
            let (x, y) = (centroid(0), centroid(1));
            let piece = if y > 0.5 * x + 1.0 {
                "A"
            } else if x < 0.0 {
                "B"
            } else if y > 0.0 {
                "C"
            } else {
                "D"
            };
            codes.entry(piece).or_default().insert(xc.regions[s]);
        }
    }
    // (+1, 0, 0) → 58, (−1, −1, 0) → 22, (−1, +1, +1) → 31, (−1, +1, −1) → 29.
    let expect: BTreeMap<&str, std::collections::BTreeSet<i32>> =
        [("A", 58), ("B", 22), ("C", 31), ("D", 29)].into_iter().map(|(p, c)| (p, [c].into())).collect();
    assert_eq!(codes, expect);
}
