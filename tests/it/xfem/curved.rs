//! Curved interfaces (issue 22): seeded random circles (2D) and spheres (3D) of radii 0.5·h … 10·h cut
//! boxes of every quadratic and linear family, their centres anywhere, within 10⁻ᵏ·h of a node, or at a
//! distance that puts the interface 10⁻ᵏ·h from a node. Every cut runs the property test's glued scene
//! (equal compression along every axis: the answer is the uncracked linear field on both sides, whatever
//! the interface's shape, because the traction on it is a pressure) and every node of the mesh and of
//! the visual mesh must be within 1e-8·U of it, with no refusal.
//!
//! The seed is printed; `ASTER_PROPTEST_SEED` replays a run and `ASTER_PROPTEST_CASES` scales the
//! random tests (the default counts are a bounded share of the runs docs/stability.md reports).

use super::property::{cases, scene_on, seed, Rng};
use aster::mesh::generate::box_mesh;
use aster::mesh::{CellType, Mesh};
use aster::runner::export::Dir;
use aster::runner::{self, RunOptions};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// A box of `n` cells of size 1 per axis, written to `dir`: its path, its vertices (the nodes at a
/// cell's vertex) and the mesh.
fn make_box(dir: &Path, t: CellType, n: usize) -> (PathBuf, Vec<[f64; 3]>, Mesh) {
    let dim = t.dim();
    let m = box_mesh(t, &vec![n; dim], &vec![n as f64; dim]).unwrap();
    let path = dir.join(format!("{}.med", t.name()));
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

/// What one run gave.
struct Outcome {
    ok: bool,
    worst: f64,
    message: String,
}

/// Run the command file `text` on the mesh at `mesh` (unit 20) in `dir/tag`: OK with every check of
/// the scene passing, and the worst ANALYTIQUE error.
fn run_scene(dir: &Path, mesh: &Path, text: &str, tag: &str, expected: usize) -> Outcome {
    let comm = dir.join(format!("{tag}.comm"));
    std::fs::write(&comm, text).unwrap();
    let out = dir.join(tag);
    let opts = RunOptions { out_dir: Some(out.clone()), units: vec![(20, mesh.to_path_buf(), Dir::In)], echo: false };
    let o = runner::run_comm(&comm, &opts);
    let resu = std::fs::read_to_string(out.join(format!("{tag}.resu"))).unwrap_or_default();
    let mut worst = 0.0f64;
    for l in resu.lines() {
        let w: Vec<&str> = l.split_whitespace().collect();
        if w.len() >= 5 && w[1] == "ANALYTIQUE" {
            if let Ok(v) = w[4].parse::<f64>() {
                worst = worst.max(v.abs());
            }
        }
    }
    let ok = o.diagnostic == "OK" && o.ok_count() == expected && o.nook_count() == 0;
    let message = format!(
        "{} ({} OK, {} NOOK) {}",
        o.diagnostic,
        o.ok_count(),
        o.nook_count(),
        o.error.unwrap_or_default().lines().next().unwrap_or("")
    );
    let _ = std::fs::remove_dir_all(&out);
    let _ = std::fs::remove_file(&comm);
    Outcome { ok, worst, message }
}

/// The level set of a circle or sphere as a Python expression of X, Y (, Z).
fn sphere(dim: usize, c: &[f64; 3], r: f64) -> String {
    let names = ["X", "Y", "Z"];
    let sum: Vec<String> = (0..dim).map(|k| format!("({}-{:?})**2", names[k], c[k])).collect();
    format!("sqrt({})-{r:?}", sum.join("+"))
}

/// A random unit vector of dimension `dim`.
fn unit(rng: &mut Rng, dim: usize) -> [f64; 3] {
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

/// 10⁻ᵏ·h with k drawn in 1 …= `kmax`, or 0 (k = ∞), with a random sign.
fn tiny(rng: &mut Rng, kmax: usize) -> (f64, String) {
    let k = 1 + rng.below(kmax + 1);
    if k > kmax {
        (0.0, "0".into())
    } else {
        (rng.sign() * 10f64.powi(-(k as i32)), format!("1e-{k}·h"))
    }
}

/// A random circle or sphere crossing the box of side `l` whose vertices are `vertices`: radius
/// 0.5·h … 10·h (log-uniform), centre anywhere, within 10⁻ᵏ·h of a node, or at r + 10⁻ᵏ·h of a node
/// (the interface passing 10⁻ᵏ·h from it). Some vertex is at least 0.1·h inside and another outside.
fn random_sphere(rng: &mut Rng, dim: usize, l: f64, nodes: &[[f64; 3]], vertices: &[[f64; 3]]) -> (String, String) {
    loop {
        let r = 10f64.powf(rng.range(0.5f64.log10(), 1.0));
        let (c, label) = match rng.below(3) {
            0 => {
                let mut c = [0.0; 3];
                for x in c.iter_mut().take(dim) {
                    *x = rng.range(-r, l + r);
                }
                (c, format!("r = {r:.3}, centre anywhere"))
            }
            1 => {
                let p = nodes[rng.below(nodes.len())];
                let (d, k) = tiny(rng, 12);
                let u = unit(rng, dim);
                (std::array::from_fn(|i| p[i] + d * u[i]), format!("r = {r:.3}, centre {k} from a node"))
            }
            _ => {
                let p = nodes[rng.below(nodes.len())];
                let (d, k) = tiny(rng, 12);
                let u = unit(rng, dim);
                (std::array::from_fn(|i| p[i] + (r + d) * u[i]), format!("r = {r:.3}, interface {k} from a node"))
            }
        };
        let f = |x: &[f64; 3]| (0..dim).map(|k| (x[k] - c[k]).powi(2)).sum::<f64>().sqrt() - r;
        let (lo, hi) = vertices.iter().map(f).fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
        if lo < -0.1 && hi > 0.1 {
            return (sphere(dim, &c, r), label);
        }
    }
}

/// Run `count` random cuts over the cell types `types` in turn (boxes of `n` cells per axis): every
/// one must pass.
fn random_spheres(types: &[CellType], n: usize, count: usize, tag: &str) {
    let seed = seed();
    let mut rng = Rng(seed);
    let dir = scratch!(tag);
    let start = Instant::now();
    let meshes: Vec<_> = types.iter().map(|&t| make_box(&dir, t, n)).collect();
    let (mut failures, mut worst, mut worst_cut) = (Vec::new(), 0.0f64, String::new());
    for i in 0..count {
        let t = types[i % types.len()];
        let (path, vertices, m) = &meshes[i % types.len()];
        let dim = t.dim();
        let (phi, label) = random_sphere(&mut rng, dim, n as f64, &m.coords, vertices);
        let o = run_scene(&dir, path, &scene_on(dim, &phi, 1e-8, n as f64), &format!("cut{i}"), 8 * dim);
        if o.worst > worst {
            (worst, worst_cut) = (o.worst, format!("{} {label}: {phi}", t.name()));
        }
        if !o.ok {
            failures.push(format!("{} {label}: phi = {phi}: {}", t.name(), o.message));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    let names: Vec<&str> = types.iter().map(|t| t.name()).collect();
    println!(
        "seed {seed}: {count} cuts on {} in {:.1} s, {} failing, worst node error {worst:.2e}·U ({worst_cut})",
        names.join("/"),
        start.elapsed().as_secs_f64(),
        failures.len()
    );
    assert!(failures.is_empty(), "seed {seed} (replay with ASTER_PROPTEST_SEED={seed}):\n{}", failures.join("\n"));
}

/// Random circles on 4 × 4 boxes of QUAD8, TRIA6, QUAD4 and TRIA3 (40 by default; docs/stability.md
/// gives the full runs' seeds and counts).
#[test]
fn random_circles() {
    random_spheres(&[CellType::Quad8, CellType::Tria6, CellType::Quad4, CellType::Tria3], 4, cases(40), "circles");
}

/// Random spheres on 3 × 3 × 3 boxes of HEXA20, TETRA10, HEXA8 and TETRA4 (8 by default).
#[test]
fn random_spheres_3d() {
    random_spheres(&[CellType::Hexa20, CellType::Tetra10, CellType::Hexa8, CellType::Tetra4], 3, cases(8), "spheres");
}
