//! The VERSION2 multiplier packets of WTNV149 (hm-xfem-formulation.md §4.6):
//! contact cells, cut edges, vital edges and packets of FISS1 and FISS2 on
//! the real meshes (`../shared/astest/wtnv145a.mmed`, `wtnv145b.mmed`, read
//! in place), and the HYDR2 node lists of `wtnv149a.comm` / `wtnv149b.comm`
//! blocking the interface unknowns of every packet exactly once.
//! Every test prints a message and passes when `../shared` is absent.

use aster::mesh::Mesh;
use aster::xfem::mortar::{contact_cells, cut_edges, vital_edges, CrackTopo, CutEdge, Packets};
use aster::xfem::Crack;
use std::collections::BTreeSet;
use std::path::Path;
use std::rc::Rc;

use crate::common::*;

/// Per crack: its cut edges and packets, plus the enrichment status of each.
struct Case {
    mesh: Rc<Mesh>,
    edges: [Vec<CutEdge>; 2],
    packets: [Packets; 2],
    enriched: [Vec<bool>; 2],
    /// Contact cells (names) of each crack, in Code_Aster's list order.
    contact: [Vec<String>; 2],
    /// FISS2 edges cut by φ2 in its contact cells but beyond the junction.
    beyond: usize,
}

fn build(mesh: Rc<Mesh>, c1: &Rc<Crack>, c2: &Rc<Crack>) -> Case {
    let k1 = c1.clone();
    let k2 = c2.clone();
    let topo = [
        CrackTopo { lsn: &k1.lsn, status: &k1.status, heaviside_cells: &k1.heaviside_cells },
        CrackTopo { lsn: &k2.lsn, status: &k2.status, heaviside_cells: &k2.heaviside_cells },
    ];
    let cont = contact_cells(&mesh, &topo);
    let (master, coef) = k2.master().unwrap();
    assert!(Rc::ptr_eq(master, c1));
    let e1 = cut_edges(&mesh, &cont[0], &k1.lsn, None);
    let e2 = cut_edges(&mesh, &cont[1], &k2.lsn, Some((&k1.lsn, coef)));
    let all2 = cut_edges(&mesh, &cont[1], &k2.lsn, None);
    let contact = [names_of_cells(&mesh, &cont[0]), names_of_cells(&mesh, &cont[1])];
    let beyond = all2.len() - e2.len();
    println!(
        "contact cells: FISS1 {:?}, FISS2 {:?}; FISS2 edges beyond the junction: {beyond}",
        contact[0], contact[1]
    );
    let p1 = vital_edges(&e1, &Default::default());
    let p2 = vital_edges(&e2, &Default::default());
    let nn = mesh.nnodes();
    let enriched = [(0..nn).map(|n| k1.enriched(n)).collect(), (0..nn).map(|n| k2.enriched(n)).collect()];
    drop((k1, k2));
    Case { mesh, edges: [e1, e2], packets: [p1, p2], enriched, contact, beyond }
}

fn names_of_cells(mesh: &Mesh, cells: &[usize]) -> Vec<String> {
    cells.iter().map(|&c| mesh.cell_names[c].clone()).collect()
}

fn names(mesh: &Mesh, nodes: &[usize]) -> Vec<String> {
    nodes.iter().map(|&n| mesh.node_names[n].clone()).collect()
}

fn packet_names(mesh: &Mesh, p: &Packets) -> BTreeSet<BTreeSet<String>> {
    p.packets.iter().map(|q| names(mesh, q).into_iter().collect()).collect()
}

fn set(groups: &[&[&str]]) -> BTreeSet<BTreeSet<String>> {
    groups.iter().map(|g| g.iter().map(|s| s.to_string()).collect()).collect()
}

fn show(case: &Case) {
    for f in 0..2 {
        let m = &case.mesh;
        let e: Vec<String> = case.edges[f]
            .iter()
            .map(|e| format!("{}-{} @{:?}", m.node_names[e.a], m.node_names[e.b], &e.point[..m.dim]))
            .collect();
        println!("FISS{}: {} cut edges {e:?}", f + 1, e.len());
        println!("  packets {:?}", case.packets[f].packets.iter().map(|q| names(m, q)).collect::<Vec<_>>());
    }
}

/// The Heaviside block crack f uses at a node: 1 + the number of earlier
/// cracks enriching it (the node's Heaviside numbering).
fn block(case: &Case, f: usize, node: usize) -> usize {
    1 + (0..f).filter(|&g| case.enriched[g][node]).count()
}

/// The nodes where HYDR2 blocks the flux multipliers of block 1 and block 2.
fn hydr2_nodes(comm: &Path) -> (Vec<String>, Vec<String>) {
    let src = std::fs::read_to_string(comm).unwrap();
    let start = src.find("HYDR2=AFFE_CHAR_MECA").expect("no HYDR2 in the command file");
    let body = &src[start..];
    let end = body.find("INFO").unwrap();
    let body = &body[..end];
    let mut b1 = Vec::new();
    let mut b2 = Vec::new();
    for occ in body.split("_F(").skip(1) {
        let list = occ.split("NOEUD=").nth(1).unwrap();
        let list = &list[..list.find(')').unwrap()];
        let nodes: Vec<String> = list
            .split(',')
            .map(|s| s.trim().trim_matches(['(', '\'', '"']).to_string())
            .filter(|s| !s.is_empty())
            .collect();
        if occ.contains("LAG_FLI") {
            assert!(occ.contains("LAG_FLS") && occ.contains("PRE_FLU"));
            b1.extend(nodes);
        } else if occ.contains("LA2_FLI") {
            assert!(occ.contains("LA2_FLS"));
            b2.extend(nodes);
        } else {
            panic!("unexpected HYDR2 occurrence {occ}");
        }
    }
    (b1, b2)
}

/// Every packet of both cracks gets exactly one blocked node: a node blocked
/// in block k covers the packet, of the crack using block k at that node,
/// that contains it.
fn check_hydr2(case: &Case, comm: &Path) {
    let (b1, b2) = hydr2_nodes(comm);
    let m = &case.mesh;
    let idx = |name: &str| m.node_names.iter().position(|n| n == name).unwrap_or_else(|| panic!("no node {name}"));
    let mut hits: [Vec<usize>; 2] = [vec![0; case.packets[0].packets.len()], vec![0; case.packets[1].packets.len()]];
    for (blk, list) in [(1, &b1), (2, &b2)] {
        for name in list {
            let n = idx(name);
            let mut covered = 0;
            for (f, hit) in hits.iter_mut().enumerate() {
                if !case.enriched[f][n] || block(case, f, n) != blk {
                    continue;
                }
                if let Some(&p) = case.packets[f].packet_of_node.get(&n) {
                    hit[p] += 1;
                    covered += 1;
                }
            }
            assert_eq!(covered, 1, "{name} (block {blk}) covers {covered} packets");
        }
    }
    for (f, hit) in hits.iter().enumerate() {
        for (p, &h) in hit.iter().enumerate() {
            assert_eq!(h, 1, "FISS{} packet {:?} blocked {h} times", f + 1, names(m, &case.packets[f].packets[p]));
        }
    }
    let total: usize = hits.iter().map(|h| h.len()).sum();
    println!("HYDR2: {} + {} blocked nodes, {total} packets covered once each", b1.len(), b2.len());
}

#[test]
fn wtnv149a_packets() {
    let Some(m) = mesh("wtnv145a.mmed") else { return };
    let (c1, c2) = two_cracks(&m, |x| x[1] - 0.2 - 0.5 * x[0], |x| x[1] + 0.5 * x[0] + 0.2, &[2.0, -5.0]);
    let case = build(m.clone(), &c1, &c2);
    show(&case);
    // FISS1's list ends with M29, M30: Heaviside cells of FISS1 met first without
    // contact, put back when FISS2 makes them contact cells (xtyele).
    let cells = |l: &[&str]| l.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    assert_eq!(case.contact[0], cells(&["M26", "M27", "M32", "M33", "M34", "M39", "M40", "M29", "M30"]));
    assert_eq!(case.contact[1], cells(&["M27", "M29", "M30", "M32", "M33", "M34", "M39", "M40"]));
    assert_eq!(case.edges[0].len(), 8);
    assert_eq!(case.edges[1].len(), 4);
    assert_eq!(case.beyond, 2);
    assert_eq!(
        packet_names(&m, &case.packets[0]),
        set(&[&["N19", "N20"], &["N21", "N25"], &["N26", "N30"], &["N27", "N31"], &["N32", "N36"], &["N11", "N12"]])
    );
    assert_eq!(packet_names(&m, &case.packets[1]), set(&[&["N27", "N31"], &["N24", "N28"], &["N9", "N10"]]));
    // Each packet is one vital edge here.
    for f in 0..2 {
        assert_eq!(case.packets[f].vital.len(), case.packets[f].packets.len());
    }
    // N27 (on the edge x = 1 cut by both cracks) carries FISS2 in its second block.
    let n27 = m.node_names.iter().position(|n| n == "N27").unwrap();
    assert_eq!((block(&case, 0, n27), block(&case, 1, n27)), (1, 2));
    if let Some(comm) = astest("wtnv149a.comm") {
        check_hydr2(&case, &comm);
    }
}

#[test]
fn wtnv149b_packets() {
    let Some(m) = mesh("wtnv145b.mmed") else { return };
    let (c1, c2) = two_cracks(&m, |x| x[2] - 0.5 * x[0] - 2.7, |x| x[2] - 7.3 + 0.5 * x[0], &[10.0, 0.0, 2.0]);
    let case = build(m.clone(), &c1, &c2);
    show(&case);
    assert_eq!(case.edges[0].len(), 16);
    assert_eq!(case.edges[1].len(), 8);
    assert_eq!(case.beyond, 4);
    assert_eq!(case.packets[0].packets.len(), 12);
    assert_eq!(case.packets[1].packets.len(), 6);
    // Every packet lies on one vertical (Z) edge at Y = 0 or Y = 2: no tying across Y.
    for f in 0..2 {
        for q in &case.packets[f].packets {
            let c0 = m.coords[q[0]];
            let vertical = q.iter().all(|&n| (0..2).all(|k| (m.coords[n][k] - c0[k]).abs() < 1e-9));
            assert!(vertical, "FISS{} packet {:?} is not on one Z line", f + 1, names(&m, q));
            assert!(c0[1].abs() < 1e-9 || (c0[1] - 2.0).abs() < 1e-9);
        }
    }
    for name in ["N50", "N62"] {
        let n = m.node_names.iter().position(|x| x == name).unwrap();
        assert_eq!((block(&case, 0, n), block(&case, 1, n)), (1, 2), "{name}");
    }
    if let Some(comm) = astest("wtnv149b.comm") {
        check_hydr2(&case, &comm);
    }
}
