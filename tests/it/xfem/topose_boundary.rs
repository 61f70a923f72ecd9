//! TOPOSE cutting of QUADRATIC boundary cells (`te0514` with `ndime < ndim`,
//! `topose::topose_boundary`): a SEG3 of a 2D mesh, TRIA6 and QUAD8 faces of
//! a 3D mesh, and their orientation (`xoripe`, `orient_boundary`). The
//! point numbering and the sub-cell order are what POST_MAIL_XFEM's node
//! counter follows (wtnv143a: SEG3, wtnv143c: QUAD8 faces).

use aster::mesh::CellType;
use aster::xfem::topose::{tiling_defect, topose, topose_boundary, CrackInCell, Cutting};
use aster::xfem::topose_linear::orient_boundary;

fn one(lsn: Vec<f64>) -> Vec<CrackInCell> {
    vec![CrackInCell { lsn, master: None }]
}

/// Code_Aster's numbers of the points of every sub-cell.
fn ids(cut: &Cutting) -> Vec<Vec<u32>> {
    cut.subcells.iter().map(|s| s.nodes.iter().map(|&i| cut.points[i].id.number()).collect()).collect()
}

fn close(a: &[f64; 3], b: &[f64; 3]) -> bool {
    (0..3).all(|k| (a[k] - b[k]).abs() < 1e-12)
}

/// The point of a cutting with Code_Aster's number `n`.
fn at(cut: &Cutting, n: u32) -> [f64; 3] {
    cut.points.iter().find(|p| p.id.number() == n).unwrap_or_else(|| panic!("no point {n}")).x
}

/// The SEG3 (0,0) → (0,2) of a 2D mesh, mid-node (0,1).
fn seg3() -> Vec<[f64; 3]> {
    vec![[0.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.0, 1.0, 0.0]]
}

/// A SEG3 cut at an inner point P: (P, 1, mid(P, 1)) and (P, 2, mid(P, 2)),
/// the mid-points archived as mid(P, 2) = 2001 then mid(P, 1) = 2002
/// (`xalgo2` with ndime = 1, `xdecqv`); `xoripe` swaps the ends of the
/// sub-cell whose normal points into the support cell, never its mid-node.
#[test]
fn seg3_cut_at_an_inner_point() {
    let c = seg3();
    let lsn = c.iter().map(|p| p[1] - 0.6).collect();
    let mut cut = topose_boundary(CellType::Seg3, 2, &c, &one(lsn)).unwrap();
    assert_eq!(ids(&cut), vec![vec![1001, 1, 2002], vec![1001, 2, 2001]]);
    let he: Vec<Vec<i32>> = cut.subcells.iter().map(|s| s.he.clone()).collect();
    assert_eq!(he, vec![vec![-1], vec![1]]);
    assert!(close(&at(&cut, 1001), &[0.0, 0.6, 0.0]));
    assert!(close(&at(&cut, 2001), &[0.0, 1.3, 0.0]));
    assert!(close(&at(&cut, 2002), &[0.0, 0.3, 0.0]));
    assert!(cut.points.iter().find(|p| p.id.number() == 1001).unwrap().lsn[0].abs() < 1e-14);
    assert!(tiling_defect(CellType::Seg3, &cut) < 1e-13);
    // Support cell on the side x > 0: outward is −x. (P, 1) has the normal
    // (−0.6, 0), outward; (P, 2) has (1.4, 0) and is turned.
    assert_eq!(orient_boundary(&mut cut, 2, &[-1.0, 0.0, 0.0]), 1);
    assert_eq!(ids(&cut), vec![vec![1001, 1, 2002], vec![2, 1001, 2001]]);
}

/// The interface through the SEG3's mid-node: the crossing point is an
/// intersection point (1001) at the mid-node, not the node itself.
#[test]
fn seg3_cut_at_its_mid_node() {
    let c = seg3();
    let lsn = c.iter().map(|p| p[1] - 1.0).collect();
    let cut = topose_boundary(CellType::Seg3, 2, &c, &one(lsn)).unwrap();
    assert_eq!(ids(&cut), vec![vec![1001, 1, 2002], vec![1001, 2, 2001]]);
    assert!(close(&at(&cut, 1001), &[0.0, 1.0, 0.0]));
    assert!(close(&at(&cut, 2001), &[0.0, 1.5, 0.0]));
    assert!(close(&at(&cut, 2002), &[0.0, 0.5, 0.0]));
}

/// An uncut SEG3 is its own sub-cell; one lying in the interface (Code_Aster
/// gives it the Heaviside value 99 for `xoripe` to fix) is refused by name,
/// and so is a SEG3 of a 3D mesh that is cut (`xalgo3` has no such case).
#[test]
fn seg3_uncut_in_the_interface_and_in_3d() {
    let c = seg3();
    let cut = topose_boundary(CellType::Seg3, 2, &c, &one(c.iter().map(|p| p[1] + 1.0).collect())).unwrap();
    assert_eq!(ids(&cut), vec![vec![1, 2, 3]]);
    assert_eq!(cut.subcells[0].he, vec![1]);
    let e = topose_boundary(CellType::Seg3, 2, &c, &one(c.iter().map(|p| p[0]).collect())).unwrap_err();
    assert!(e.contains("lies in the interface"), "{e}");
    let cut = topose_boundary(CellType::Seg3, 3, &c, &one(c.iter().map(|p| p[1] + 1.0).collect())).unwrap();
    assert_eq!(ids(&cut), vec![vec![1, 2, 3]]);
    let e = topose_boundary(CellType::Seg3, 3, &c, &one(c.iter().map(|p| p[1] - 0.6).collect())).unwrap_err();
    assert!(e.contains("xalgo3"), "{e}");
}

/// A level set of the position.
type Ln = fn(&[f64; 3]) -> f64;

/// The QUAD8 [0,2]×[0,1] of a 2D mesh in Code_Aster order.
fn quad8() -> Vec<[f64; 3]> {
    let v = [[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]];
    let mut c: Vec<[f64; 3]> = v.iter().map(|p| [p[0], p[1], 0.0]).collect();
    for i in 0..4 {
        let (a, b) = (v[i], v[(i + 1) % 4]);
        c.push([(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0, 0.0]);
    }
    c
}

/// A QUAD8 face of a 3D mesh is cut in its own reference plane exactly as
/// a QUAD8 of a 2D mesh (`xdivte` with its centre node, `xalg20` = `xalgo2`,
/// the children of `xdecqv` with ndime = 2): the same points, numbers,
/// sub-cells and Heaviside values, the face placed in the plane y = 0.3 of
/// a 3D mesh. One straight interface, one through two vertices, and two
/// crossing ones.
#[test]
fn quad8_face_is_cut_as_the_2d_quad8() {
    let c2 = quad8();
    let c3: Vec<[f64; 3]> = c2.iter().map(|p| [p[0], 0.3, p[1]]).collect();
    let scenes: Vec<Vec<Ln>> = vec![
        vec![|p| p[1] - 0.3 - 0.15 * p[0]],
        vec![|p| p[1] - 0.5 * p[0]],
        vec![|p| p[1] - 0.4 - 0.1 * p[0], |p| p[0] - 1.3 + 0.2 * p[1]],
        vec![|p| p[1] + 3.0],
    ];
    for (k, lns) in scenes.iter().enumerate() {
        let cracks: Vec<CrackInCell> =
            lns.iter().map(|f| CrackInCell { lsn: c2.iter().map(f).collect(), master: None }).collect();
        let bulk = topose(CellType::Quad8, &c2, &cracks).unwrap_or_else(|e| panic!("scene {k}: {e}"));
        let face = topose_boundary(CellType::Quad8, 3, &c3, &cracks).unwrap_or_else(|e| panic!("scene {k}: {e}"));
        assert_eq!(ids(&face), ids(&bulk), "scene {k}");
        assert!(face.subcells.iter().zip(&bulk.subcells).all(|(a, b)| a.he == b.he), "scene {k}");
        assert_eq!(face.points.len(), bulk.points.len());
        for (p, q) in face.points.iter().zip(&bulk.points) {
            assert_eq!(p.id, q.id);
            assert!(close(&p.xi, &q.xi), "scene {k}: {:?} {:?}", p.xi, q.xi);
            assert!(close(&p.x, &[q.x[0], 0.3, q.x[1]]), "scene {k}: {:?} {:?}", p.x, q.x);
        }
        assert!(tiling_defect(CellType::Quad8, &face) < 1e-12, "scene {k}");
    }
}

/// `xoripe` on TRIA6 sub-cells of a face: vertices 2↔3 and mid-nodes 4↔6
/// of every sub-cell whose normal (b − a) × (c − a) points into the
/// support cell, the others left as they are (the children of `xdecqv` are
/// not reoriented in 2D, so a cut face has sub-cells of both orientations).
#[test]
fn quad8_face_orientation_swaps_the_mid_nodes() {
    let c3: Vec<[f64; 3]> = quad8().iter().map(|p| [p[0], p[1], 5.0]).collect();
    let cracks = one(c3.iter().map(|p| p[1] - 0.3 - 0.15 * p[0]).collect());
    let cut = topose_boundary(CellType::Quad8, 3, &c3, &cracks).unwrap();
    let normal_z = |s: &aster::xfem::topose::SubCell| {
        let p = |k: usize| cut.points[s.nodes[k]].x;
        let (a, b, c) = (p(0), p(1), p(2));
        (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    };
    let down: Vec<bool> = cut.subcells.iter().map(|s| normal_z(s) < 0.0).collect();
    assert!(down.iter().any(|&d| d) && down.iter().any(|&d| !d), "{down:?}");
    for (outward, turned) in [(1.0, down.clone()), (-1.0, down.iter().map(|d| !d).collect())] {
        let mut o = cut.clone();
        let n = orient_boundary(&mut o, 3, &[0.0, 0.0, outward]);
        assert_eq!(n, turned.iter().filter(|&&t| t).count());
        for ((d, c), t) in ids(&o).iter().zip(ids(&cut)).zip(&turned) {
            let expected = if *t { vec![c[0], c[2], c[1], c[5], c[4], c[3]] } else { c };
            assert_eq!(d, &expected);
        }
    }
}

/// A TRIA6 face cut by a straight interface across two of its edges: three
/// TRIA6 sub-cells with straight sides (affine face), the two crossing
/// points, the four type-1 mid-points, the one on the interface and the
/// one between a point and the far vertex; every sub-cell on one side.
#[test]
fn tria6_face_cut_by_a_line() {
    let v = [[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]];
    let mut c: Vec<[f64; 3]> = v.to_vec();
    for (a, b) in [(0, 1), (1, 2), (2, 0)] {
        c.push([0, 1, 2].map(|j| (v[a][j] + v[b][j]) / 2.0));
    }
    let cut = topose_boundary(CellType::Tria6, 3, &c, &one(c.iter().map(|p| p[0] - 0.3).collect())).unwrap();
    assert_eq!(cut.subcells.len(), 3);
    assert!(close(&at(&cut, 1001), &[0.3, 0.0, 1.0]));
    assert!(close(&at(&cut, 1002), &[0.3, 0.7, 1.0]));
    assert_eq!(cut.points.iter().filter(|p| p.id.number() > 2000).count(), 6);
    for s in &cut.subcells {
        for (m, a, b) in [(3, 0, 1), (4, 1, 2), (5, 2, 0)] {
            let (pm, pa, pb) = (cut.points[s.nodes[m]].x, cut.points[s.nodes[a]].x, cut.points[s.nodes[b]].x);
            assert!(close(&pm, &[0, 1, 2].map(|j| (pa[j] + pb[j]) / 2.0)));
        }
        for &i in &s.nodes {
            assert!(cut.points[i].lsn[0] * f64::from(s.he[0]) >= -1e-12);
        }
    }
    assert!(tiling_defect(CellType::Tria6, &cut) < 1e-12);
}
