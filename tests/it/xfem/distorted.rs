//! Straight interfaces on distorted meshes (issue 22, acceptance 2): boxes of every quadratic and
//! linear family whose vertices are moved by up to 0.2·h and whose quadratic edges are bent by up to
//! 0.05·h (`mesh::generate::distort`, a fresh distortion per cut), cut by planes 10⁻ᵏ·h (k = 1 … 12)
//! from a vertex or exactly through it, on either side, at any angle. Every cut runs the property
//! test's glued scene (equal compression along every axis: the exact field is linear, which the
//! isoparametric cells reproduce whatever their shape) and every node of the mesh and of the visual
//! mesh must be within 1e-8·U of it, with no refusal.
//!
//! Also a junction whose branch meets the first interface 10⁻ᵏ·h from a vertex of a distorted mesh.
//!
//! The seed is printed; `ASTER_PROPTEST_SEED` replays a run and `ASTER_PROPTEST_CASES` scales it
//! (the default counts are a bounded share of the runs docs/stability.md reports).

use super::curved::{random_cuts, unit, written, Written};
use super::property::{cases, junction_on, run_scene, Rng};
use aster::mesh::generate::{box_mesh, distort, Distortion};
use aster::mesh::CellType;
use std::path::Path;

/// A box of `n` cells of size 1 per axis with its nodes moved (`shift`, `bend` in cell sizes, from
/// `seed`), written to `dir`: its path and its vertices (the nodes at a cell's vertex).
pub(super) fn distorted_box(dir: &Path, t: CellType, n: usize, shift: f64, bend: f64, seed: u64) -> Written {
    let dim = t.dim();
    let (counts, sizes) = (vec![n; dim], vec![n as f64; dim]);
    let mut m = box_mesh(t, &counts, &sizes).unwrap();
    distort(&mut m, &counts, &sizes, Distortion { shift, bend, seed }).unwrap();
    assert!(aster::fem::geometry::inverted_cells(&m).is_empty(), "{} seed {seed}: an inverted cell", t.name());
    written(&dir.join(format!("{}_{seed}.med", t.name())), m)
}

/// The plane n·(x − p) = d as a Python expression of X, Y (, Z).
pub(super) fn plane(dim: usize, n: &[f64; 3], p: &[f64; 3], d: f64) -> String {
    let names = ["X", "Y", "Z"];
    let terms: Vec<String> = (0..dim).map(|k| format!("{:?}*({}-{:?})", n[k], names[k], p[k])).collect();
    format!("{}-({d:?})", terms.join("+"))
}

/// A random plane 10⁻ᵏ·h (k = 1 … 12, either side) from a random vertex, or through it, at any
/// angle, which leaves some vertex at least 0.1·h on each side.
fn random_plane(rng: &mut Rng, dim: usize, vertices: &[[f64; 3]]) -> (String, String) {
    loop {
        let p = vertices[rng.below(vertices.len())];
        let n = unit(rng, dim);
        let k = 1 + rng.below(13);
        let (d, label) = if k > 12 {
            (0.0, "through a vertex".to_string())
        } else {
            (rng.sign() * 10f64.powi(-(k as i32)), format!("1e-{k}·h from a vertex"))
        };
        let f = |x: &[f64; 3]| (0..dim).map(|a| n[a] * (x[a] - p[a])).sum::<f64>() - d;
        let (lo, hi) = vertices.iter().map(f).fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
        if lo < -0.1 && hi > 0.1 {
            return (plane(dim, &n, &p, d), label);
        }
    }
}

/// Random planes ([`random_plane`]) over the cell types `types` in turn, each on a box of `n` cells per
/// axis distorted afresh.
fn random_planes(types: &[CellType], n: usize, count: usize, tag: &str) {
    random_cuts(types, n as f64, count, tag, |dir, rng, t| {
        let quadratic = t.nnodes() > t.nvertices();
        let mesh_seed = rng.next() % 1_000_000;
        let (path, vertices, _) = distorted_box(dir, t, n, 0.2, if quadratic { 0.05 } else { 0.0 }, mesh_seed);
        let (phi, label) = random_plane(rng, t.dim(), &vertices);
        (path, phi, format!("(distortion seed {mesh_seed}) {label}"))
    });
}

/// Random planes on distorted 3 × 3 boxes of QUAD8, TRIA6, QUAD4 and TRIA3 (40 by default).
#[test]
fn random_planes_on_distorted_2d_meshes() {
    random_planes(&[CellType::Quad8, CellType::Tria6, CellType::Quad4, CellType::Tria3], 3, cases(40), "distorted2d");
}

/// Random planes on distorted 2 × 2 × 2 boxes of HEXA20, TETRA10, HEXA8 and TETRA4 (4 by default: the
/// curved HEXA20's rules are of degree 21, ~10 s a cut).
#[test]
fn random_planes_on_distorted_3d_meshes() {
    random_planes(
        &[CellType::Hexa20, CellType::Tetra10, CellType::Hexa8, CellType::Tetra4],
        2,
        cases(4),
        "distorted3d",
    );
}

/// A junction near a vertex of distorted 2 × 2 (× 2) boxes of every quadratic and linear family: FISS1
/// and FISS2 (branching off it on its + side) both pass through the moved vertex of the box's centre at
/// slopes ½ and −0.7 (3D: planes containing the y axis through it), shifted by 10⁻ᵏ·h along their
/// normals, so that the junction point (3D: line) passes ~10⁻ᵏ·h from the vertex; every node of the mesh
/// and of the visual mesh within 1e-8·U. `ks` are the k (0: through the vertex).
fn junctions_near_a_vertex(types: &[CellType], ks: &[i32]) {
    let dir = scratch!("junction");
    let mut failures = Vec::new();
    for (i, &t) in types.iter().enumerate() {
        let dim = t.dim();
        let quadratic = t.nnodes() > t.nvertices();
        let (path, vertices, _) = distorted_box(&dir, t, 2, 0.2, if quadratic { 0.05 } else { 0.0 }, 17 + i as u64);
        // The vertex nearest the box's centre (the only one inside the box).
        let centre = [1.0, 1.0, if dim == 3 { 1.0 } else { 0.0 }];
        let d2 = |p: &[f64; 3]| (0..3).map(|a| (p[a] - centre[a]).powi(2)).sum::<f64>();
        let v = *vertices.iter().min_by(|a, b| d2(a).total_cmp(&d2(b))).unwrap();
        let up = if dim == 2 { 1 } else { 2 };
        let names = ["X", "Y", "Z"];
        let (x, z) = (names[0], names[up]);
        let f1 = format!("(({z}-{:?})-0.5*({x}-{:?}))/1.118033988749895", v[up], v[0]);
        let f2 = format!("(({z}-{:?})+0.7*({x}-{:?}))/1.2206555615733703", v[up], v[0]);
        let mut p = v;
        p[up] += 1.0;
        let point = format!("({})", p[..dim].iter().map(|c| format!("{c:?}")).collect::<Vec<_>>().join(", "));
        for &k in ks {
            let d = if k == 0 { 0.0 } else { 10f64.powi(-k) };
            let text = junction_on(dim, &f1, &f2, &point, d, false, 2.0);
            let o = run_scene(&dir, &path, &text, &format!("{}_{k}", t.name()), 8 * dim);
            println!("{} k = {k}: worst node error {:.2e}·U", t.name(), o.worst);
            if !o.ok {
                failures.push(format!("{} k = {k}: {}", t.name(), o.message));
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The junction near a vertex of distorted 2D meshes (QUAD8, TRIA6, QUAD4, TRIA3), k = 1 … 12 and
/// through it. Before the master side's pieces of a slave face were found on the face's own map
/// (`discrete::pieces_of`: reference coordinates for linear faces, the quadratic side's parameter for
/// quadratic ones), the real chord missed the junction point: QUAD4 1.2e-2·U at k = 1, QUAD8 6.0e-2·U at
/// k = 1 and 9.5e-7·U at k = 6, TRIA6 4.0e-2·U at k = 1.
#[test]
fn a_junction_near_a_vertex_of_distorted_2d_meshes() {
    let ks: Vec<i32> = (0..=12).collect();
    junctions_near_a_vertex(&[CellType::Quad8, CellType::Tria6, CellType::Quad4, CellType::Tria3], &ks);
}

/// The same on a distorted TETRA4 box, k = 2, 6, 10 and through the vertex (HEXA8, HEXA20 and TETRA10
/// are not exact yet: docs/stability.md).
#[test]
fn a_junction_near_a_vertex_of_a_distorted_tetra4_mesh() {
    junctions_near_a_vertex(&[CellType::Tetra4], &[2, 6, 10, 0]);
}
