//! Seeded property test of the X-FEM pipeline (issue 10, point 5): random
//! straight interfaces cut small box meshes (2×2 QUAD8 or QUAD4 cells in 2D,
//! 2×2×2 HEXA20 or HEXA8 in 3D) and each cut runs end to end in this process —
//! DEFI_FISS_XFEM, MODI_MODELE_XFEM (TOPOSE), STAT_NON_LINE with the glued
//! cohesive interface (facet rule of degree 7 in 2D, 5 in 3D), POST_MAIL_XFEM and POST_CHAM_XFEM. The load is an
//! equal compression along every axis: the stress is isotropic in the plane
//! (2D) or hydrostatic (3D), so no interface carries shear and the answer is
//! the uncracked linear field u_i = U (1 − X_i / L) at every node of the mesh
//! and of the visual mesh, checked by the command file to 1e-8·U.
//!
//! Half the interfaces are anywhere at any angle; the other half pass at
//! δ = ±10⁻ᵏ·h (k = 1 … 14) from, or exactly through, a node of the mesh
//! (vertex or mid-node) at angles that line them up with rows of nodes
//! (axes, diagonals, 1:2 slopes) or tilt them from those by 10⁻⁸ … 10⁻² rad.
//!
//! The seed is printed; `ASTER_PROPTEST_SEED=<seed>` replays a run (the
//! default is a fixed seed, `random` draws one from the clock), and
//! `ASTER_PROPTEST_CASES=<n>` scales the number of cuts (default: 500 in 2D,
//! 200 in 3D). Failures are listed with their level set and message.

use aster::mesh::CellType;
use aster::runner::export::Dir;
use aster::runner::{self, RunOptions};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// SplitMix64: a small, seedable generator (the crate has no `rand`).
pub(super) struct Rng(pub(super) u64);

impl Rng {
    pub(super) fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub(super) fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    pub(super) fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    pub(super) fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    pub(super) fn sign(&mut self) -> f64 {
        if self.next() & 1 == 0 {
            1.0
        } else {
            -1.0
        }
    }
}

/// The seed: `ASTER_PROPTEST_SEED` (a number, or `random` for one drawn
/// from the clock), else [`DEFAULT_SEED`]. A fixed default keeps the suite
/// deterministic; random seeds explore (docs/stability.md lists what they
/// found).
pub(super) fn seed() -> u64 {
    match std::env::var("ASTER_PROPTEST_SEED").ok().as_deref() {
        Some("random") => {
            std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map(|d| d.as_nanos() as u64).unwrap_or(1)
        }
        Some(s) => s.parse().unwrap_or_else(|_| panic!("ASTER_PROPTEST_SEED={s}: a number or `random`")),
        None => DEFAULT_SEED,
    }
}

/// The seed of `cargo test`.
const DEFAULT_SEED: u64 = 3;

/// Cells per axis and cell size of the meshes.
const N: usize = 2;
const H: f64 = 1.0;
const L: f64 = N as f64 * H;
const U: f64 = 1.0e-4;

/// Every cell family of `aster mesh box`.
const FAMILIES: [CellType; 10] = [
    CellType::Quad8,
    CellType::Quad4,
    CellType::Tria3,
    CellType::Tria6,
    CellType::Hexa20,
    CellType::Hexa8,
    CellType::Tetra4,
    CellType::Tetra10,
    CellType::Penta6,
    CellType::Penta15,
];

/// The command file of one cut: `phi` is the level set (a Python
/// expression of X, Y, Z).
fn scene(dim: usize, phi: &str, tol: f64) -> String {
    scene_on(dim, phi, tol, L)
}

/// [`scene`] on a box of side `l`.
pub(super) fn scene_on(dim: usize, phi: &str, tol: f64, l: f64) -> String {
    let (model, group, bounds, comps, para) = if dim == 2 {
        (
            "D_PLAN",
            "SURFACE",
            r#"_F(GROUP_MA="GAUCHE", DX=U, H1X=0.0), _F(GROUP_MA="DROITE", DX=0.0, H1X=0.0),
                                          _F(GROUP_MA="BAS", DY=U, H1Y=0.0), _F(GROUP_MA="HAUT", DY=0.0, H1Y=0.0)"#,
            vec![("X", "DX"), ("Y", "DY")],
            r#"["X", "Y"]"#,
        )
    } else {
        (
            "3D",
            "VOLUME",
            r#"_F(GROUP_MA="XMIN", DX=U, H1X=0.0), _F(GROUP_MA="XMAX", DX=0.0, H1X=0.0),
                                          _F(GROUP_MA="YMIN", DY=U, H1Y=0.0), _F(GROUP_MA="YMAX", DY=0.0, H1Y=0.0),
                                          _F(GROUP_MA="ZMIN", DZ=U, H1Z=0.0), _F(GROUP_MA="ZMAX", DZ=0.0, H1Z=0.0)"#,
            vec![("X", "DX"), ("Y", "DY"), ("Z", "DZ")],
            r#"["X", "Y", "Z"]"#,
        )
    };
    let mut checks = String::new();
    for (x, d) in &comps {
        checks += &format!(
            "E{x} = FORMULE(VALE=\"({d} - U*(1.0 - COOR_{x}/L))/U\", U=U, L=L, NOM_PARA=[\"{d}\", \"COOR_{x}\"])\n"
        );
    }
    let opers: Vec<String> =
        comps.iter().map(|(x, _)| format!("_F(OPERATION=\"OPER\", FORMULE=E{x}, NOM_PARA=\"ERR_{x}\")")).collect();
    let cmps: Vec<String> = comps.iter().map(|(_, d)| format!("\"{d}\"")).collect();
    let errs: Vec<String> = comps.iter().map(|(x, _)| format!("\"ERR_{x}\"")).collect();
    format!(
        r#"DEBUT(CODE="OUI")
U = {U:e}
L = {l:?}
MA = LIRE_MAILLAGE(FORMAT="MED", UNITE=20)
MA = DEFI_GROUP(reuse=MA, MAILLAGE=MA, CREA_GROUP_NO=_F(GROUP_MA="{group}"))
MO0 = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(GROUP_MA="{group}", PHENOMENE="MECANIQUE", MODELISATION="{model}"))
LN = FORMULE(VALE="{phi}", NOM_PARA={para})
FISS = DEFI_FISS_XFEM(MAILLAGE=MA, TYPE_DISCONTINUITE="INTERFACE", DEFI_FISS=_F(FONC_LN=LN))
MO = MODI_MODELE_XFEM(MODELE_IN=MO0, FISSURE=FISS, DECOUPE_FACETTE="SOUS_ELEMENTS", CONTACT="MORTAR")
CTX = DEFI_CONTACT(MODELE=MO, FORMULATION="XFEM",
                   ZONE=_F(FISS_MAIT=FISS, INTEGRATION="GAUSS", ORDRE_INT={order}, ALGO_CONT="CZM",
                           ALGO_LAGR="VERSION2", RELATION="CZM_LIN_MIX"))
ROCHE = DEFI_MATERIAU(ELAS=_F(E=5.8e9, NU=0.2), RUPT_FRAG=_F(GC=9.0e3, SIGM_C=5.0e5, PENA_LAGR=100.0))
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
            TEST_TABLE(TABLE=DEP, NOM_PARA=cmp, TYPE_TEST=typ, CRITERE="ABSOLU", PRECISION={tol:e},
                       VALE_CALC=0.0, VALE_REFE=0.0, REFERENCE="ANALYTIQUE", ORDRE_GRANDEUR=1.0)
FIN()
"#,
        // The facet rule: in 2D 4 Gauss points (degree 7); in 3D FPG7 (degree 5): a QUAD8 or HEXA20 shape
        // function on a flat facet times a linear multiplier is of degree 3 or 5 (HEXA20's x²yz on a
        // plane inclined to every axis), which FPG6 (ORDRE_INT=4, degree 4) misses by up to 1e-7·U.
        order = if dim == 2 { 4 } else { 5 },
        cmps = cmps.join(", "),
        opers = opers.join(", "),
        errs = errs.join(", "),
    )
}

/// A unit vector: any direction, or one lined up with rows of nodes
/// (axes, diagonals, 1:2 slopes), possibly tilted by 10⁻⁸ … 10⁻² rad.
fn direction(rng: &mut Rng, dim: usize, special: bool) -> ([f64; 3], bool) {
    let mut n = [0.0; 3];
    if !special {
        loop {
            for c in n.iter_mut().take(dim) {
                *c = rng.range(-1.0, 1.0);
            }
            let r = n.iter().map(|c| c * c).sum::<f64>().sqrt();
            if r > 0.1 && r <= 1.0 {
                return (n.map(|c| c / r), false);
            }
        }
    }
    let pick = [0.0, 1.0, -1.0, 0.5, 2.0];
    loop {
        for c in n.iter_mut().take(dim) {
            *c = pick[rng.below(pick.len())];
        }
        if n.iter().any(|&c| c != 0.0) {
            break;
        }
    }
    if rng.below(2) == 0 {
        let tilt = 10f64.powf(-rng.range(2.0, 8.0));
        let k = rng.below(dim);
        n[k] += rng.sign() * tilt;
    }
    let r = n.iter().map(|c| c * c).sum::<f64>().sqrt();
    let n = n.map(|c| c / r);
    // Within 1e-4 rad of an axis.
    let axis = n.iter().any(|c| c.abs() >= 1.0 - 5e-9);
    (n, axis)
}

/// What a cut is.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Class {
    /// Anywhere, at any angle.
    Anywhere,
    /// At 10⁻ᵏ·h from a node or through it, not parallel to the axes.
    NearNode,
    /// At 10⁻ᵏ·h from a node or through it, within 1e-4 rad of an axis:
    /// along a row (2D) or plane (3D) of nodes.
    AlongRow,
}

/// One cut: the level set as a Python expression, and a label. The
/// interface crosses the inside of the box: some node is at least h/10 on
/// either side (an interface on or along the boundary cuts nothing, which
/// DEFI_FISS_XFEM or STAT_NON_LINE refuse by name).
fn interface(rng: &mut Rng, dim: usize, nodes: &[[f64; 3]]) -> (String, String, Class) {
    loop {
        let (phi, label, class, f) = candidate(rng, dim, nodes);
        let (lo, hi) = nodes.iter().map(&f).fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
        if lo < -0.1 * H && hi > 0.1 * H {
            return (phi, label, class);
        }
    }
}

/// A candidate cut: its level set as a Python expression, a label, and as a
/// function.
fn candidate(rng: &mut Rng, dim: usize, nodes: &[[f64; 3]]) -> (String, String, Class, impl Fn(&[f64; 3]) -> f64) {
    let special = rng.below(2) == 0;
    let (n, axis) = direction(rng, dim, special);
    let class = match (special, axis) {
        (false, _) => Class::Anywhere,
        (true, false) => Class::NearNode,
        (true, true) => Class::AlongRow,
    };
    let (p, delta, label) = if special {
        let p = nodes[rng.below(nodes.len())];
        let k = 1 + rng.below(15);
        let delta = if k == 15 { 0.0 } else { rng.sign() * 10f64.powi(-(k as i32)) * H };
        (p, delta, if k == 15 { "through a node".to_string() } else { format!("1e-{k}·h from a node") })
    } else {
        let mut p = [0.0; 3];
        for c in p.iter_mut().take(dim) {
            *c = rng.range(0.1 * L, 0.9 * L);
        }
        (p, 0.0, "anywhere".to_string())
    };
    let names = ["X", "Y", "Z"];
    let mut phi = String::new();
    for k in 0..dim {
        phi += &format!("{:+e}*({}-{:e})", n[k], names[k], p[k]);
    }
    phi += &format!("{:+e}", -delta);
    let f = move |x: &[f64; 3]| (0..dim).map(|k| n[k] * (x[k] - p[k])).sum::<f64>() - delta;
    (phi, label, class, f)
}

/// The mesh of one cell type in `dir`, with its node coordinates.
/// Run the command file `text` on the mesh at `path` (unit 20) and check that every analytic check of
/// the scene passes (mesh and visual nodes, every component, MAX and MIN); `what` names the case.
fn assert_exact(dir: &Path, path: &Path, text: &str, dim: usize, what: &str) {
    let comm = dir.join("case.comm");
    std::fs::write(&comm, text).unwrap();
    let opts =
        RunOptions { out_dir: Some(dir.join("out")), units: vec![(20, path.to_path_buf(), Dir::In)], echo: false };
    let o = runner::run_comm(&comm, &opts);
    let what = format!("{what}: {:?}", o.error);
    assert_eq!(o.diagnostic, "OK", "{what}");
    assert_eq!((o.ok_count(), o.nook_count()), (2 * 2 * 2 * dim, 0), "{what}");
}

/// Every scene `scenes(t)` gives — (what, command file) — on the box of each cell type of `types`, run in
/// a scratch folder named `tag`, matches the analytic field ([`assert_exact`]).
fn assert_exact_on(tag: &str, types: &[CellType], scenes: impl Fn(CellType) -> Vec<(String, String)>) {
    let dir = scratch!(tag);
    for &t in types {
        let (path, _) = mesh(&dir, t);
        for (what, text) in scenes(t) {
            assert_exact(&dir, &path, &text, t.dim(), &format!("{} {what}", t.name()));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

fn mesh(dir: &Path, t: CellType) -> (PathBuf, Vec<[f64; 3]>) {
    let dim = t.dim();
    let m = aster::mesh::generate::box_mesh(t, &vec![N; dim], &vec![L; dim]).unwrap();
    let path = dir.join(format!("{}.med", t.name()));
    aster::med::write_mesh(&path, &m, "MAIL").unwrap();
    (path, m.coords.clone())
}

/// The tolerance of a cut on the analytic field, relative to U: `None`
/// skips the cut (a known failure, see docs/stability.md).
type Tolerance = fn(CellType, Class) -> Option<f64>;

/// Run `cases` random cuts over the cell types in turn: every cut `tol`
/// keeps must pass its checks.
fn run(types: &[CellType], cases: usize, tag: &str, tol: Tolerance) {
    let seed = seed();
    let mut rng = Rng(seed);
    let dir = scratch!(tag);
    let start = Instant::now();
    let mut failures = Vec::new();
    let mut worst = 0.0f64;
    let mut worst_cut = String::new();
    let (mut count, mut skipped, mut along) = (0, 0, 0);
    let meshes: Vec<(PathBuf, Vec<[f64; 3]>)> = types.iter().map(|&t| mesh(&dir, t)).collect();
    let mut i = 0;
    while count < cases {
        let (t, (path, nodes)) = (types[i % types.len()], &meshes[i % types.len()]);
        i += 1;
        let dim = t.dim();
        let (phi, label, class) = interface(&mut rng, dim, nodes);
        let Some(tol) = tol(t, class) else {
            skipped += 1;
            continue;
        };
        along += usize::from(class == Class::AlongRow);
        let o = run_scene(&dir, path, &scene(dim, &phi, tol), &format!("cut{i}"), 2 * 2 * 2 * dim);
        if o.worst > worst {
            worst = o.worst;
            worst_cut = format!("{} {label}: phi = {phi}", t.name());
        }
        if !o.ok {
            failures.push(format!("{} {label} ({class:?}, tolerance {tol:e}·U): phi = {phi}: {}", t.name(), o.message));
        }
        count += 1;
    }
    let _ = std::fs::remove_dir_all(&dir);
    let names: Vec<&str> = types.iter().map(|t| t.name()).collect();
    println!(
        "seed {seed}: {count} cuts on {} in {:.1} s ({along} along a row or plane of nodes, {skipped} drawn in \
         skipped classes), {} failing, worst node error {worst:.2e}·U ({worst_cut})",
        names.join("/"),
        start.elapsed().as_secs_f64(),
        failures.len()
    );
    assert!(failures.is_empty(), "seed {seed} (replay with ASTER_PROPTEST_SEED={seed}):\n{}", failures.join("\n"));
}

/// What one run gave.
pub(super) struct Outcome {
    pub(super) ok: bool,
    pub(super) worst: f64,
    pub(super) message: String,
}

/// Run the command file `text` on the mesh at `mesh` (unit 20) in `dir/tag`: OK with every check of
/// the scene passing, and the worst ANALYTIQUE error.
pub(super) fn run_scene(dir: &Path, mesh: &Path, text: &str, tag: &str, expected: usize) -> Outcome {
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

/// The number of cuts: `ASTER_PROPTEST_CASES` or the default.
pub(super) fn cases(default: usize) -> usize {
    std::env::var("ASTER_PROPTEST_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(default)
}

/// QUAD8: every class to 1e-8·U.
#[test]
fn random_straight_interfaces_2d() {
    run(&[CellType::Quad8], cases(500), "p2d", |_, _| Some(1e-8));
}

/// HEXA20: every class to 1e-8·U.
#[test]
fn random_straight_interfaces_3d() {
    run(&[CellType::Hexa20], cases(200), "p3d", |_, _| Some(1e-8));
}

/// Linear cells (QUAD4, HEXA8; 250 cuts each by default): every class to
/// 1e-8·U. Where the interface
/// meets the faces whose jumps the scene prescribes, multiplier components
/// and combinations of components that test only those jumps are removed
/// (`xfem::discrete::dead_components`, `null_multipliers`); before, the cuts
/// whose faces meet the interface at an angle left a null space.
#[test]
fn random_straight_interfaces_linear_cells() {
    run(&[CellType::Quad4, CellType::Hexa8], cases(500), "plin", |_, _| Some(1e-8));
}

/// Every cell type the box generator makes, in turn, and every class, to
/// 1e-8·U (400 cuts by default).
#[test]
fn random_straight_interfaces_everywhere() {
    let types = [CellType::Quad8, CellType::Quad4, CellType::Hexa20, CellType::Hexa8];
    run(&types, cases(400), "pall", |_, _| Some(1e-8));
}

/// TRIA3, TRIA6, TETRA4, TETRA10, PENTA6 and PENTA15 boxes, in turn, and every class, to 1e-8·U (360
/// cuts by default). TETRA4 and PENTA6 were left out until multiplier directions were weighed by their
/// pivot and a near-sliver jump went with its multiplier (`discrete::NULL_SCHUR`, `SLIVER_PIVOT`): seed 3
/// failed a PENTA6 plane (4.65e-7·U) and a TETRA4 plane through a node (1.29e-8·U), the three cuts of
/// `near_sliver_jumps_are_held_with_their_multipliers`. Now 6 × 1800 cuts of the six families (seeds 3,
/// 77, 12345, 999, 31337, 1795574619857666044) pass, worst 2.2e-9·U.
#[test]
fn random_straight_interfaces_simplices_and_prisms() {
    let types =
        [CellType::Tria3, CellType::Tria6, CellType::Tetra4, CellType::Tetra10, CellType::Penta6, CellType::Penta15];
    run(&types, cases(360), "psim", |_, _| Some(1e-8));
}

/// Three linear cuts of the random test's seed 3 whose multiplier block has a direction on the jump of a
/// near-sliver set — σ small and the bulk's stiffness against that jump k ≪ 1, a pivot σ²/k between
/// 1e-15 and 1e-10: a TETRA4 plane 1e-2·h from a node (σ = 8.5e-10, k = 3.9e-6), a TETRA4 plane through
/// a node (σ = 2.0e-11, k = 1.8e-7) and a PENTA6 plane (σ = 1.2e-10, k = 1.9e-8). Removing μ along it
/// alone left the nodes 1.1e-7, 1.3e-8 and 4.7e-7·U off, keeping it 8.6e-9, 4.5e-8 (condition 1.5e17)
/// and 8.2e-12·U; removed with the jump it tests held at zero (`discrete::SLIVER_PIVOT`) every node of
/// the mesh and of the visual mesh is within 1e-10·U, and the log says so.
#[test]
fn near_sliver_jumps_are_held_with_their_multipliers() {
    let dir = scratch!("sliver_jumps");
    for (t, phi) in [
        (
            CellType::Tetra4,
            "+8.16497933377896e-1*(X-2e0)-4.08248966688948e-1*(Y-1e0)+4.082449093216364e-1*(Z-0e0)+1e-2",
        ),
        (CellType::Tetra4, "-6.68235646423845e-1*(X-1e0)-6.647002339856909e-1*(Y-2e0)+3.341178232119225e-1*(Z-1e0)"),
        (
            CellType::Penta6,
            "-8.947334955423786e-1*(X-1.6111403097677754e0)-3.9810212354062724e-1*(Y-1.344220394430403e0)\
             +2.0240225094341108e-1*(Z-1.5071405272042806e0)",
        ),
    ] {
        let (path, _) = mesh(&dir, t);
        assert_exact(&dir, &path, &scene(3, phi, 1e-10), 3, &format!("{} {phi}", t.name()));
        let mess = std::fs::read_to_string(dir.join("out/case.mess")).unwrap();
        assert!(mess.contains("with the near-sliver jump they test held at zero)"), "{}: {mess}", t.name());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// An interface along a row (2D) or plane (3D) of nodes — X = 1 through the
/// middle of the box, exactly, and 1e-7·h, 1e-9·h and 1e-14·h from it, which
/// xajuls snaps onto it — cuts no cell: its facets are the faces on the level
/// set of the cells on its − side, with one multiplier packet per vertex of the
/// row (Code_Aster's `xtyele` / `xcface` / `xlagsp`); an interface that follows
/// the row over half its length and then cuts cells mixes both. Before, its Heaviside sets
/// separated the sides with no facet to glue them and the run stopped by name.
/// Every cell type, every node of the mesh and of the visual mesh to 1e-8·U.
#[test]
fn an_interface_along_a_row_of_nodes_is_glued() {
    let dir = scratch!("row");
    for t in [CellType::Quad8, CellType::Quad4, CellType::Hexa20, CellType::Hexa8] {
        let dim = t.dim();
        let (path, _) = mesh(&dir, t);
        // Along the row, near it, and along it over half its length then across cells (a kink).
        for phi in ["X-1.0", "X-1.0-1.0e-7", "X-1.0+1.0e-9", "X-1.0-1.0e-14", "X-1.0-0.5*max(0.0, Y-1.0)"] {
            let comm = dir.join("row.comm");
            std::fs::write(&comm, scene(dim, phi, 1e-8)).unwrap();
            let opts =
                RunOptions { out_dir: Some(dir.join("out")), units: vec![(20, path.clone(), Dir::In)], echo: false };
            let o = runner::run_comm(&comm, &opts);
            let what = format!("{} {phi}: {:?}", t.name(), o.error);
            assert_eq!(o.diagnostic, "OK", "{what}");
            assert_eq!((o.ok_count(), o.nook_count()), (2 * 2 * 2 * dim, 0), "{what}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Linear cells (QUAD4, HEXA8) cut by an interface that meets faces where the
/// scene prescribes the jump (`H1Y=0` where it crosses Y = 0 and Y = L): the
/// VERSION2 multipliers of the packets there test only prescribed jumps, so
/// with P1 jumps they were a null space of the tangent (condition 1e25–1e30,
/// Newton wandering on an arbitrary tensile λ). Those components are removed
/// (`xfem::discrete::dead_components`) and every node matches the analytic
/// field to 1e-8·U.
#[test]
fn linear_cells_with_jumps_prescribed_where_the_interface_meets_the_boundary() {
    let dir = scratch!("linjump");
    let h = L / N as f64;
    for (t, dim, phi) in [
        (CellType::Quad4, 2, format!("X-{}", 0.5 * L + 0.01 * h)),
        (CellType::Hexa8, 3, format!("{}-{}", planes(3).row12, 1e-3 * h)),
    ] {
        let (path, _) = mesh(&dir, t);
        let comm = dir.join("lin.comm");
        std::fs::write(&comm, scene(dim, &phi, 1e-8)).unwrap();
        let out = dir.join(t.name());
        let opts = RunOptions { out_dir: Some(out.clone()), units: vec![(20, path.clone(), Dir::In)], echo: false };
        let o = runner::run_comm(&comm, &opts);
        assert_eq!(o.diagnostic, "OK", "{} {phi}: {:?}", t.name(), o.error);
        let resu = std::fs::read_to_string(out.join("lin.resu")).unwrap();
        let checks = resu.lines().filter(|l| l.contains("ANALYTIQUE")).count();
        assert!(checks > 0, "{} {phi}: no check ran", t.name());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Simplices and prisms (`aster mesh box --cell TRIA3|TRIA6|TETRA4|TETRA10|PENTA6|PENTA15`; TRIA6 and
/// TETRA10 parents are their own single sub-cell in TOPOSE): interfaces through a row of vertices (the
/// diagonal X + Y (+ Z) = L), 1e-5·h, 1e-6·h and 1e-7·h from it (where `xajuls` snaps part of the row:
/// PENTA15 was 5.5e-7·U off at 1e-6·h and PENTA6 7.9e-9·U at 1e-7·h before the prisms' split was made
/// conforming, `cutting::prism_relabel`) and 1e-3·h from the 1:2 row: every node of the mesh and of the
/// visual mesh matches the analytic field to 1e-8·U.
#[test]
fn simplex_and_prism_cells_near_and_through_nodes() {
    let h = L / N as f64;
    let types =
        [CellType::Tria3, CellType::Tria6, CellType::Tetra4, CellType::Tetra10, CellType::Penta6, CellType::Penta15];
    assert_exact_on("simplex", &types, |t| {
        let dim = t.dim();
        let Planes { diag, through: d0, row12: row, .. } = planes(dim);
        [
            format!("{diag}-{d0}"),
            format!("{diag}-{}", d0 + 1e-5 * h),
            format!("{diag}-{}", d0 + 1e-6 * h),
            format!("{diag}-{}", d0 + 1e-7 * h),
            format!("{row}-{}", 1e-3 * h),
        ]
        .into_iter()
        .map(|phi| (phi.clone(), scene(dim, &phi, 1e-8)))
        .collect()
    });
}

/// The planes the deterministic scenes cut along, as level sets of unit gradient: the diagonal
/// X + Y (+ Z) = 0 (the row of vertices X + Y (+ Z) = L lies `through` from it), the 1:2 row Y = X/2
/// (3D: Z = X/2, vertices and mid-side nodes alternately) and a plane inclined to every axis.
struct Planes {
    diag: String,
    through: f64,
    row12: String,
    anywhere: &'static str,
}

fn planes(dim: usize) -> Planes {
    let (sum, up, anywhere) =
        if dim == 2 { ("X+Y", "Y", "X+0.37*Y-1.13") } else { ("X+Y+Z", "Z", "X+0.37*Y+0.61*Z-1.13") };
    Planes {
        diag: format!("({sum})/{:?}", (dim as f64).sqrt()),
        through: L / (dim as f64).sqrt(),
        row12: format!("({up}-0.5*X)/{:?}", 1.25f64.sqrt()),
        anywhere,
    }
}

/// [`scene`] with free lips (no contact) loaded by the pressure `p` (PRES_REP FISSURE).
fn lips_scene(dim: usize, phi: &str, p: f64) -> String {
    let glued = scene(dim, phi, 1e-8);
    let contact = glued.find("CTX = DEFI_CONTACT").unwrap();
    let end = contact + glued[contact..].find("))\n").unwrap() + 3;
    let text = format!("{}{}", &glued[..contact], &glued[end..])
        .replace(", CONTACT=\"MORTAR\")", ")")
        .replace(
            "BLOC = AFFE_CHAR_MECA(",
            &format!("PR = AFFE_CHAR_MECA(MODELE=MO, PRES_REP=_F(FISSURE=FISS, PRES={p:e}))\nBLOC = AFFE_CHAR_MECA("),
        )
        .replace("EXCIT=_F(CHARGE=BLOC), CONTACT=CTX,", "EXCIT=(_F(CHARGE=BLOC), _F(CHARGE=PR)),");
    assert!(text.contains("PRES_REP") && !text.contains("CTX"), "{text}");
    text
}

/// The same scene with free lips loaded by the pressure of the exact field (PRES_REP FISSURE, no
/// contact): u = U(1 − X/L) on both sides is then the solution, and the discrete one reproduces it only
/// when the sub-cells, their Heaviside signs, the facets and the lips' load agree — the glued scene is
/// blind to a facet integral that its multipliers can absorb. Every family of `aster mesh box`, through
/// the diagonal row, 1e-6·h and 1e-7·h from it (where `xajuls` snaps part of it), 1e-3·h from the 1:2
/// row and on a plane inclined to every axis. Before the prisms' split was made conforming PENTA15 was
/// 1.8e-6·U off and PENTA6 3.8e-7·U at 1e-6·h; before FPG7 on 3D lips HEXA8 was 1.5e-3·U off on
/// every plane inclined to two axes.
#[test]
fn pressurised_lips_are_exact_on_every_cell_type() {
    let h = L / N as f64;
    assert_exact_on("lips", &FAMILIES, |t| {
        let dim = t.dim();
        let Planes { diag, through: d0, row12: row, anywhere: tilted } = planes(dim);
        // σ = −p I: p = E/((1+ν)(1−2ν))·U/L in plane strain, E/(1−2ν)·U/L in 3D (E = 5.8e9, ν = 0.2).
        let p = if dim == 2 { 5.8e9 / (1.2 * 0.6) } else { 5.8e9 / 0.6 } * U / L;
        [
            format!("{diag}-{d0}"),
            format!("{diag}-{}", d0 + 1e-6 * h),
            format!("{diag}-{}", d0 + 1e-7 * h),
            format!("{row}-{}", 1e-3 * h),
            tilted.to_string(),
        ]
        .into_iter()
        .map(|phi| (phi.clone(), lips_scene(dim, &phi, p)))
        .collect()
    });
}

/// The glued scene under unequal strains, u_i = s_i U (1 − X_i/L) with s = 1 : 2 : 3 along X, Y, Z: the
/// stress is not a pressure, so the traction on an inclined interface has a tangential part, which the
/// multipliers must carry (the other scenes' equal compression loads every interface with the same
/// pressure, whatever its shape or local basis).
fn unequal_strains(text: &str) -> String {
    let mut text = text.to_string();
    for (x, s) in [("X", 1.0), ("Y", 2.0), ("Z", 3.0)] {
        text = text
            .replace(&format!("(D{x} - U*(1.0 - COOR_{x}/L))"), &format!("(D{x} - {s:?}*U*(1.0 - COOR_{x}/L))"))
            .replace(&format!("D{x}=U, "), &format!("D{x}={s:?}*U, "));
    }
    text
}

/// Unequal strains (`unequal_strains`) on every cell type, the interface on the rows row12 and diag
/// 10⁻ᵏ·h from their nodes (k = 1, 3, 5) and on a plane anywhere: every node of the mesh and of the
/// visual mesh within 1e-8·U. Closer to a row, where `xajuls` sets near-zero nodal values to zero, the
/// interface bends by the distance and the P1 multipliers cannot carry a traction that turns with it:
/// quadratic cells are then off by ~0.3 of the distance (3.6e-7·U at 1e-6·h on PENTA15,
/// docs/stability.md "Unequal strains"), which is left out here.
#[test]
fn unequal_strains_are_exact_where_nothing_is_snapped() {
    let h = L / N as f64;
    assert_exact_on("unequal", &FAMILIES, |t| {
        let dim = t.dim();
        let Planes { diag, through, row12, anywhere } = planes(dim);
        let mut cuts = vec![anywhere.to_string()];
        for k in [1, 3, 5] {
            let d = 10f64.powi(-k) * h;
            cuts.push(format!("{row12}-{d:e}"));
            cuts.push(format!("{diag}-{}", through + d));
        }
        cuts.into_iter()
            .map(|phi| {
                let text = unequal_strains(&scene(dim, &phi, 1e-8));
                assert!(text.contains("2.0*U") && text.contains("(DY - 2.0*U*"), "{text}");
                (phi, text)
            })
            .collect()
    });
}

/// Two glued interfaces meeting 10⁻ᵏ·h from a node (a junction, FISS2 branching off FISS1 on its + side;
/// in 3D the junction line runs 10⁻ᵏ·h from a row of nodes), and through it: both level sets are shifted
/// by the same 10⁻ᵏ·h, so the junction point lies at ~10⁻ᵏ·h from the node and ~10⁻ᵏ⁺¹·h from a cell
/// edge. Every node of the mesh and of the visual mesh matches the analytic field to 1e-8·U. Before the
/// facets of a face split by the junction took the master side of each piece (`discrete::facets`), a
/// junction point near a cell edge gave errors proportional to its distance (QUAD8 1.6e-2·U at k = 1,
/// 6.7e-8·U at k = 6); before the linear TOPOSE stopped snapping a branch onto an earlier crack's
/// intersection points from 1e-4·lonref (`xdecou`), QUAD4 was 9.3e-6·U off at k = 4; with the zones
/// of DEFI_CONTACT not in the model's crack order (FISS2's first here) TRIA3 did not converge; before
/// the null multiplier directions were sought across the cracks (`discrete::null_multipliers`), the
/// TETRA4 junction at k = 3 had an exactly singular first tangent (FISS and FISS2 multipliers testing
/// the same jumps) and did not converge, and before they were weighed by their pivot it was 1.3e-8·U off
/// at k = 7.
#[test]
fn a_junction_near_a_node_is_exact() {
    let h = L / N as f64;
    assert_exact_on("junction_node", &FAMILIES, |t| {
        [1, 2, 3, 4, 6, 7, 0]
            .into_iter()
            .map(|k| (format!("k = {k}"), junction_scene(t.dim(), if k == 0 { 0.0 } else { 10f64.powi(-k) * h }, true)))
            .collect()
    });
}

/// The glued scene with FISS2 branching off FISS1 on its + side, both through the node (1, 1) (in 3D
/// the row (1, y, 1)) shifted by `d` along their normals; FISS2's zone first in DEFI_CONTACT when
/// `fiss2_first`.
fn junction_scene(dim: usize, d: f64, fiss2_first: bool) -> String {
    let (f1, f2, point) = if dim == 2 {
        ("(Y-0.5*X-0.5)/1.118033988749895", "(Y+0.7*X-1.7)/1.2206555615733703", "(1.0, 2.0)")
    } else {
        ("(Z-0.5*X-0.5)/1.118033988749895", "(Z+0.7*X-1.7)/1.2206555615733703", "(1.0, 1.0, 2.0)")
    };
    junction_on(dim, f1, f2, point, d, fiss2_first, L)
}

/// The glued scene on a box of side `l` with FISS2 (level set `f2`) branching off FISS1 (`f1`) on the
/// side of FISS1 that holds `point`, both shifted by `d`; FISS2's zone first when `fiss2_first`.
pub(super) fn junction_on(dim: usize, f1: &str, f2: &str, point: &str, d: f64, fiss2_first: bool, l: f64) -> String {
    let para = if dim == 2 { r#"["X", "Y"]"# } else { r#"["X", "Y", "Z"]"# };
    let zone2 = r#"_F(FISS_MAIT=FISS2, INTEGRATION="GAUSS", ORDRE_INT=4, ALGO_CONT="CZM", ALGO_LAGR="VERSION2", RELATION="CZM_LIN_MIX")"#;
    let single = scene_on(dim, &format!("{f1}-{d:e}"), 1e-8, l);
    let zones = single.replace("ZONE=_F(FISS_MAIT=FISS,", "ZONE=(_F(FISS_MAIT=FISS,");
    let zones = if fiss2_first {
        zones.replace("ZONE=(_F(FISS_MAIT=FISS,", &format!("ZONE=({zone2}, _F(FISS_MAIT=FISS,")).replacen(
            "RELATION=\"CZM_LIN_MIX\"))",
            "RELATION=\"CZM_LIN_MIX\")))",
            1,
        )
    } else {
        zones.replacen("RELATION=\"CZM_LIN_MIX\"))", &format!("RELATION=\"CZM_LIN_MIX\"), {zone2}))"), 1)
    };
    let two = zones
        .replace(
            "FISS = DEFI_FISS_XFEM(MAILLAGE=MA, TYPE_DISCONTINUITE=\"INTERFACE\", DEFI_FISS=_F(FONC_LN=LN))",
            &format!(
                "FISS = DEFI_FISS_XFEM(MAILLAGE=MA, TYPE_DISCONTINUITE=\"INTERFACE\", DEFI_FISS=_F(FONC_LN=LN))\n\
                 LN2 = FORMULE(VALE=\"{f2}-{d:e}\", NOM_PARA={para})\n\
                 FISS2 = DEFI_FISS_XFEM(MAILLAGE=MA, TYPE_DISCONTINUITE=\"INTERFACE\", DEFI_FISS=_F(FONC_LN=LN2), \
                 JONCTION=_F(FISSURE=FISS, POINT={point}))"
            ),
        )
        .replace("FISSURE=FISS, DECOUPE", "FISSURE=(FISS, FISS2), DECOUPE")
        .replace("H1X=0.0)", "H1X=0.0, H2X=0.0)")
        .replace("H1Y=0.0)", "H1Y=0.0, H2Y=0.0)")
        .replace("H1Z=0.0)", "H1Z=0.0, H2Z=0.0)");
    assert!(two.contains("FISS2 = ") && two.contains("FISS_MAIT=FISS2") && two.contains("H2X"), "{two}");
    two
}

/// DEFI_CONTACT's zones in either order give the same answer: the zones are taken in the model's crack
/// order. With FISS2's zone first, a TRIA3 junction 0.1·h from a node did not converge (relative
/// residual 3.6e-2 after 10 iterations).
#[test]
fn contact_zones_in_any_order() {
    let dir = scratch!("zone_order");
    let (path, _) = mesh(&dir, CellType::Tria3);
    for first in [false, true] {
        assert_exact(&dir, &path, &junction_scene(2, 0.1 * L / N as f64, first), 2, &format!("FISS2 first: {first}"));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The cut the property test's seed 1795568946461677518 drew: a line 1e-6·h from the vertex (1, 0) and
/// 2.2e-6 rad from the diagonal along which TOPOSE splits the QUAD8 into two sub-triangles. `xajuls`
/// bends it onto that diagonal and a sub-triangle map folds (TOPOSE refused the cell: "the sub-cells of
/// the QUAD8 do not tile it"); the cell is now split along its other diagonal, and every node of the mesh
/// and of the visual mesh matches the analytic field to 1e-8·U.
#[test]
fn a_quad8_cut_along_its_split_diagonal_is_split_along_the_other() {
    let dir = scratch!("quad8_fold");
    let (path, _) = mesh(&dir, CellType::Quad8);
    let phi = "+7.071075594181181e-1*(X-1e0)+7.071060029541203e-1*(Y-0e0)+1e-6";
    assert_exact(&dir, &path, &scene(2, phi, 1e-8), 2, phi);
    let _ = std::fs::remove_dir_all(&dir);
}
