//! Straight interfaces on distorted meshes (issue 22, acceptance 2): boxes of every quadratic and
//! linear family whose vertices are moved by up to 0.2·h and whose quadratic edges are bent by up to
//! 0.05·h (`mesh::generate::distort`, a fresh distortion per cut), cut by planes 10⁻ᵏ·h (k = 1 … 12)
//! from a vertex or exactly through it, on either side, at any angle. Every cut runs the property
//! test's glued scene (equal compression along every axis: the exact field is linear, which the
//! isoparametric cells reproduce whatever their shape) and every node of the mesh and of the visual
//! mesh must be within 1e-8·U of it, with no refusal.
//!
//! The seed is printed; `ASTER_PROPTEST_SEED` replays a run and `ASTER_PROPTEST_CASES` scales it
//! (the default counts are a bounded share of the runs docs/stability.md reports).

use super::property::{cases, run_scene, scene_on, seed, Rng};
use aster::mesh::generate::{box_mesh, distort, Distortion};
use aster::mesh::{CellType, Mesh};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// A box of `n` cells of size 1 per axis with its nodes moved (`shift`, `bend` in cell sizes, from
/// `seed`), written to `dir`: its path and its vertices (the nodes at a cell's vertex).
pub(super) fn distorted_box(
    dir: &Path,
    t: CellType,
    n: usize,
    shift: f64,
    bend: f64,
    seed: u64,
) -> (PathBuf, Vec<[f64; 3]>, Mesh) {
    let dim = t.dim();
    let (counts, sizes) = (vec![n; dim], vec![n as f64; dim]);
    let mut m = box_mesh(t, &counts, &sizes).unwrap();
    distort(&mut m, &counts, &sizes, Distortion { shift, bend, seed }).unwrap();
    assert!(aster::fem::geometry::inverted_cells(&m).is_empty(), "{} seed {seed}: an inverted cell", t.name());
    let path = dir.join(format!("{}_{seed}.med", t.name()));
    aster::med::write_mesh(&path, &m, "MAIL").unwrap();
    let mut vertices: Vec<usize> = Vec::new();
    for (c, nodes) in m.cells.iter().enumerate() {
        let ct = m.cell_types[c];
        if ct.dim() == dim {
            vertices.extend(&nodes[..ct.nvertices()]);
        }
    }
    vertices.sort();
    vertices.dedup();
    let coords = vertices.iter().map(|&v| m.coords[v]).collect();
    (path, coords, m)
}

/// A random unit vector of dimension `dim`.
pub(super) fn unit(rng: &mut Rng, dim: usize) -> [f64; 3] {
    loop {
        let mut u = [0.0; 3];
        for c in u.iter_mut().take(dim) {
            *c = rng.range(-1.0, 1.0);
        }
        let r = u.iter().map(|c| c * c).sum::<f64>().sqrt();
        if r > 0.1 && r <= 1.0 {
            return u.map(|c| c / r);
        }
    }
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

/// Run `count` random planes over the cell types `types` in turn, each on a box of `n` cells per
/// axis distorted afresh: every one must pass.
fn random_planes(types: &[CellType], n: usize, count: usize, tag: &str) {
    let seed = seed();
    let mut rng = Rng(seed);
    let dir = scratch!(tag);
    let start = Instant::now();
    let (mut failures, mut worst, mut worst_cut) = (Vec::new(), 0.0f64, String::new());
    for i in 0..count {
        let t = types[i % types.len()];
        let dim = t.dim();
        let quadratic = t.nnodes() > t.nvertices();
        let mesh_seed = rng.next() % 1_000_000;
        let (path, vertices, _) = distorted_box(&dir, t, n, 0.2, if quadratic { 0.05 } else { 0.0 }, mesh_seed);
        let (phi, label) = random_plane(&mut rng, dim, &vertices);
        let what = format!("{} (distortion seed {mesh_seed}) {label}: phi = {phi}", t.name());
        let text = scene_on(dim, &phi, 1e-8, n as f64);
        let o = run_scene(&dir, &path, &text, &format!("cut{i}"), 8 * dim);
        let _ = std::fs::remove_file(&path);
        if o.worst > worst {
            (worst, worst_cut) = (o.worst, what.clone());
        }
        if !o.ok {
            failures.push(format!("{what}: {}", o.message));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    let names: Vec<&str> = types.iter().map(|t| t.name()).collect();
    println!(
        "seed {seed}: {count} cuts on distorted {} in {:.1} s, {} failing, worst node error {worst:.2e}·U ({worst_cut})",
        names.join("/"),
        start.elapsed().as_secs_f64(),
        failures.len()
    );
    assert!(failures.is_empty(), "seed {seed} (replay with ASTER_PROPTEST_SEED={seed}):\n{}", failures.join("\n"));
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
