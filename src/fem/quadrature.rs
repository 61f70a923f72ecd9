//! Quadrature rules on the reference elements of [`super::reference`].
//!
//! Two kinds of rules live here:
//!
//! * **Code_Aster's named families** (`FPG1`, `FPG4`, `FPG27`, `NOEU`, ...),
//!   with the points in Code_Aster's order, so that Gauss-point fields
//!   (ELGA) match Code_Aster's numbering. Source: `bibfor/elements/elraga.F90`
//!   (coordinates and weights), `elraca.F90` (which families exist for each
//!   reference element), and the element catalogues
//!   `catalo/cataelem/Elements/meca_3d.py`, `meca_d_plan.py`,
//!   `meca_2d_skin.py` (which family is `RIGI`, `MASS`, ... by default).
//!   See [`aster_rule`], [`family_rule`], [`default_family`].
//! * **Generic rules of a requested polynomial degree** on each reference
//!   domain ([`rule_for_degree`]): Gauss–Legendre on segments
//!   ([`gauss_legendre`]), tensor products on quadrangles and hexahedra,
//!   tabulated symmetric rules on triangles and tetrahedra (falling back to
//!   collapsed "conical product" Gauss rules for higher degrees), triangle ×
//!   segment products on prisms, and conical product rules on pyramids.
//!
//! Every rule records its exact polynomial degree: all monomials of total
//! degree ≤ `degree` are integrated exactly (up to round-off), and the unit
//! tests check that some monomial of degree `degree + 1` is not.
//!
//! Reference domains are those of Code_Aster (see [`super::reference`]):
//! segment [-1,1]; triangle (0,0),(1,0),(0,1); quadrangle [-1,1]²;
//! tetrahedron x,y,z ≥ 0, x+y+z ≤ 1; prism x ∈ [-1,1] × triangle in (y,z);
//! pyramid 0 ≤ z ≤ 1, |x|+|y| ≤ 1-z; hexahedron [-1,1]³.

use super::reference::{node_coords, ref_centroid, ref_measure};
use crate::mesh::CellType;

/// A quadrature rule on a reference domain.
#[derive(Debug, Clone, PartialEq)]
pub struct QuadratureRule {
    /// Code_Aster family name (`"FPG9"`, `"NOEU"`, ...) or a descriptive
    /// name for generic rules (`"GAUSS3"`, `"TRI-DEG6"`, ...).
    pub name: String,
    /// Reference domain.
    pub domain: RefDomain,
    /// Points in reference coordinates (unused coordinates are 0).
    pub points: Vec<[f64; 3]>,
    /// Weights (they sum to the reference measure for a consistent rule).
    pub weights: Vec<f64>,
    /// Exact polynomial degree.
    pub degree: usize,
}

impl QuadratureRule {
    /// Number of points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// True when the rule has no point.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Σ w_i f(ξ_i).
    pub fn integrate<F: Fn(&[f64; 3]) -> f64>(&self, f: F) -> f64 {
        self.points.iter().zip(&self.weights).map(|(p, w)| w * f(p)).sum()
    }

    fn new(name: &str, domain: RefDomain, points: Vec<[f64; 3]>, weights: Vec<f64>, degree: usize) -> Self {
        debug_assert_eq!(points.len(), weights.len());
        QuadratureRule { name: name.to_string(), domain, points, weights, degree }
    }
}

/// The reference domains (one per family of cell types).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RefDomain {
    Point,
    Segment,
    Triangle,
    Quadrangle,
    Tetrahedron,
    Prism,
    Pyramid,
    Hexahedron,
}

impl RefDomain {
    /// Reference domain of a cell type.
    pub fn of(t: CellType) -> RefDomain {
        use CellType::*;
        match t {
            Poi1 => RefDomain::Point,
            Seg2 | Seg3 | Seg4 => RefDomain::Segment,
            Tria3 | Tria6 | Tria7 => RefDomain::Triangle,
            Quad4 | Quad8 | Quad9 => RefDomain::Quadrangle,
            Tetra4 | Tetra10 => RefDomain::Tetrahedron,
            Penta6 | Penta15 | Penta18 => RefDomain::Prism,
            Pyram5 | Pyram13 => RefDomain::Pyramid,
            Hexa8 | Hexa20 | Hexa27 => RefDomain::Hexahedron,
        }
    }

    /// Topological dimension.
    pub fn dim(self) -> usize {
        match self {
            RefDomain::Point => 0,
            RefDomain::Segment => 1,
            RefDomain::Triangle | RefDomain::Quadrangle => 2,
            _ => 3,
        }
    }

    /// Measure of the reference domain.
    pub fn measure(self) -> f64 {
        match self {
            RefDomain::Point => 1.0,
            RefDomain::Segment => 2.0,
            RefDomain::Triangle => 0.5,
            RefDomain::Quadrangle => 4.0,
            RefDomain::Tetrahedron => 1.0 / 6.0,
            RefDomain::Prism => 1.0,
            RefDomain::Pyramid => 2.0 / 3.0,
            RefDomain::Hexahedron => 8.0,
        }
    }
}

// ---------------------------------------------------------------------------
// Gauss–Legendre
// ---------------------------------------------------------------------------

/// Gauss–Legendre nodes (ascending) and weights on [-1, 1], computed by
/// Newton iterations on the Legendre polynomial P_n (three-term recurrence).
pub fn gauss_legendre_1d(n: usize) -> (Vec<f64>, Vec<f64>) {
    assert!(n >= 1, "Gauss–Legendre needs at least one point");
    let mut x = vec![0.0; n];
    let mut w = vec![0.0; n];
    let m = n.div_ceil(2);
    for i in 0..m {
        // Initial guess (Tricomi), root i counted from +1 downwards.
        let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (p, d) = legendre(n, z);
            dp = d;
            let dz = p / d;
            z -= dz;
            if dz.abs() < 1e-16 {
                break;
            }
        }
        let (_, d) = legendre(n, z);
        if d != 0.0 {
            dp = d;
        }
        let wi = 2.0 / ((1.0 - z * z) * dp * dp);
        x[n - 1 - i] = z;
        x[i] = -z;
        w[i] = wi;
        w[n - 1 - i] = wi;
    }
    if n % 2 == 1 {
        x[n / 2] = 0.0;
    }
    (x, w)
}

/// P_n(z) and P_n'(z).
fn legendre(n: usize, z: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, z);
    if n == 0 {
        return (1.0, 0.0);
    }
    for k in 2..=n {
        let k = k as f64;
        let p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
    }
    let d = n as f64 * (z * p1 - p0) / (z * z - 1.0);
    (p1, d)
}

/// Gauss–Legendre rule with `n` points on the segment [-1, 1], points in
/// ascending order; exact degree 2n - 1. Intended for n in 1..=10 (any
/// n ≥ 1 works).
pub fn gauss_legendre(n: usize) -> QuadratureRule {
    let (x, w) = gauss_legendre_1d(n);
    let pts = x.iter().map(|&v| [v, 0.0, 0.0]).collect();
    QuadratureRule::new(&format!("GAUSS{n}"), RefDomain::Segment, pts, w, 2 * n - 1)
}

/// Gauss–Legendre nodes in one of Code_Aster's orders. `order` lists signed
/// 1-based indices into the ascending positive roots (0 = the zero root).
fn gl_ordered(n: usize, order: &[i32]) -> (Vec<f64>, Vec<f64>) {
    let (x, w) = gauss_legendre_1d(n);
    let half = n / 2;
    // Positive roots ascending are x[n - half..].
    let pick = |k: i32| -> (f64, f64) {
        if k == 0 {
            (0.0, w[half])
        } else {
            let idx = n - half + (k.unsigned_abs() as usize - 1);
            (k.signum() as f64 * x[idx], w[idx])
        }
    };
    order.iter().map(|&k| pick(k)).unzip()
}

/// Order of the 1D points in Code_Aster's segment families `FPGn`
/// (`elraga.F90`, SE2/SE3).
fn aster_segment_order(n: usize) -> Vec<i32> {
    match n {
        1 => vec![0],
        2 => vec![1, -1],
        3 => vec![-1, 0, 1],
        4 => vec![1, -1, 2, -2],
        5 => vec![0, 1, -1, 2, -2],
        6 => vec![2, -2, 1, -1, 3, -3],
        7 => vec![0, 1, -1, 2, -2, 3, -3],
        8 => vec![1, -1, 2, -2, 3, -3, 4, -4],
        _ => ascending_order(n),
    }
}

/// Order of the 1D factor of Code_Aster's tensor families on quadrangles
/// and hexahedra (`FPG16`/`FPG64`: -r1, +r1, -r2, +r2; from 5 points on, the
/// segment order).
fn aster_tensor_order(n: usize) -> Vec<i32> {
    match n {
        1 => vec![0],
        2 => vec![-1, 1],
        3 => vec![-1, 0, 1],
        4 => vec![-1, 1, -2, 2],
        _ => aster_segment_order(n),
    }
}

fn ascending_order(n: usize) -> Vec<i32> {
    let half = (n / 2) as i32;
    let mut v: Vec<i32> = (1..=half).rev().map(|k| -k).collect();
    if n % 2 == 1 {
        v.push(0);
    }
    v.extend(1..=half);
    v
}

/// Tensor product of a 1D rule with itself, in `dim` dimensions, first
/// coordinate varying slowest (Code_Aster's loop order).
fn tensor(x: &[f64], w: &[f64], dim: usize) -> (Vec<[f64; 3]>, Vec<f64>) {
    let n = x.len();
    let mut pts = Vec::new();
    let mut wts = Vec::new();
    let total = n.pow(dim as u32);
    for idx in 0..total {
        let mut p = [0.0; 3];
        let mut wt = 1.0;
        let mut r = idx;
        for k in (0..dim).rev() {
            let i = r % n;
            r /= n;
            p[k] = x[i];
            wt *= w[i];
        }
        pts.push(p);
        wts.push(wt);
    }
    (pts, wts)
}

// ---------------------------------------------------------------------------
// Tabulated triangle and tetrahedron rules (Code_Aster's families)
// ---------------------------------------------------------------------------

/// Triangle rule from orbits. Points (x, y) and weights for the reference
/// triangle of area 1/2.
fn tri(name: &str, pts: &[(f64, f64)], w: &[f64], degree: usize) -> QuadratureRule {
    QuadratureRule::new(name, RefDomain::Triangle, pts.iter().map(|&(x, y)| [x, y, 0.0]).collect(), w.to_vec(), degree)
}

/// Code_Aster's triangle families (`elraga.F90`, TR3/TR6).
fn aster_triangle(name: &str) -> Option<QuadratureRule> {
    let s15 = 15f64.sqrt();
    Some(match name {
        // Centroid, degree 1.
        "FPG1" => tri("FPG1", &[(1.0 / 3.0, 1.0 / 3.0)], &[0.5], 1),
        // 3 interior points (Hammer–Stroud), degree 2.
        "FPG3" => {
            tri("FPG3", &[(1.0 / 6.0, 1.0 / 6.0), (2.0 / 3.0, 1.0 / 6.0), (1.0 / 6.0, 2.0 / 3.0)], &[1.0 / 6.0; 3], 2)
        }
        // 3 edge mid-points, degree 2.
        "COT3" => tri("COT3", &[(0.5, 0.5), (0.0, 0.5), (0.5, 0.0)], &[1.0 / 6.0; 3], 2),
        // 4 points with a negative weight (Hammer), degree 3.
        "FPG4" => tri(
            "FPG4",
            &[(0.2, 0.2), (0.6, 0.2), (0.2, 0.6), (1.0 / 3.0, 1.0 / 3.0)],
            &[25.0 / 96.0, 25.0 / 96.0, 25.0 / 96.0, -27.0 / 96.0],
            3,
        ),
        // 6 points (Strang–Fix / Dunavant), degree 4.
        "FPG6" => {
            let a = 0.445_948_490_915_964_9;
            let b = 0.091_576_213_509_770_74;
            let wa = 0.223_381_589_678_011_47 / 2.0;
            let wb = 0.109_951_743_655_321_87 / 2.0;
            tri(
                "FPG6",
                &[(b, b), (1.0 - 2.0 * b, b), (b, 1.0 - 2.0 * b), (a, 1.0 - 2.0 * a), (a, a), (1.0 - 2.0 * a, a)],
                &[wb, wb, wb, wa, wa, wa],
                4,
            )
        }
        // 7 points (Radon / Hammer–Marlowe–Stroud), degree 5, closed form.
        "FPG7" => {
            let a = (6.0 + s15) / 21.0;
            let b = (6.0 - s15) / 21.0;
            let wa = (155.0 + s15) / 2400.0;
            let wb = (155.0 - s15) / 2400.0;
            tri(
                "FPG7",
                &[
                    (1.0 / 3.0, 1.0 / 3.0),
                    (a, a),
                    (1.0 - 2.0 * a, a),
                    (a, 1.0 - 2.0 * a),
                    (b, b),
                    (1.0 - 2.0 * b, b),
                    (b, 1.0 - 2.0 * b),
                ],
                &[9.0 / 80.0, wa, wa, wa, wb, wb, wb],
                5,
            )
        }
        // 12 points (Dunavant 1985), degree 6.
        "FPG12" => {
            let a = 0.063_089_014_491_502_23;
            let b = 0.249_286_745_170_910_43;
            let c = 0.310_352_451_033_784_4;
            let d = 0.053_145_049_844_816_945;
            let e = 1.0 - c - d;
            let w1 = 0.050_844_906_370_206_82 / 2.0;
            let w2 = 0.116_786_275_726_379_37 / 2.0;
            let w3 = 0.082_851_075_618_373_57 / 2.0;
            tri(
                "FPG12",
                &[
                    (a, a),
                    (1.0 - 2.0 * a, a),
                    (a, 1.0 - 2.0 * a),
                    (b, b),
                    (1.0 - 2.0 * b, b),
                    (b, 1.0 - 2.0 * b),
                    (c, d),
                    (d, c),
                    (e, c),
                    (e, d),
                    (c, e),
                    (d, e),
                ],
                &[w1, w1, w1, w2, w2, w2, w3, w3, w3, w3, w3, w3],
                6,
            )
        }
        // 13 points with a negative weight (Cowper 1973; Bathe, Finite
        // Element Procedures, p. 280), degree 7. Data known to 13 digits.
        "FPG13" => {
            let (a, b) = (0.065_130_102_902_2, 0.869_739_794_195_6);
            let (c, d, e) = (0.312_865_496_004_9, 0.048_690_315_425_3, 0.638_444_188_569_8);
            let (f, g) = (0.260_345_966_079_0, 0.479_308_067_841_9);
            let w1 = 0.053_347_235_608_8 / 2.0;
            let w2 = 0.077_113_760_890_3 / 2.0;
            let w3 = 0.175_615_257_433_2 / 2.0;
            let w4 = -0.149_570_044_467_7 / 2.0;
            tri(
                "FPG13",
                &[
                    (a, a),
                    (b, a),
                    (a, b),
                    (c, d),
                    (e, c),
                    (d, e),
                    (e, d),
                    (c, e),
                    (d, c),
                    (f, f),
                    (g, f),
                    (f, g),
                    (1.0 / 3.0, 1.0 / 3.0),
                ],
                &[w1, w1, w1, w2, w2, w2, w2, w2, w2, w3, w3, w3, w4],
                7,
            )
        }
        // 16 points (Dunavant 1985), degree 8. Data known to 15 digits.
        "FPG16" => {
            let (a1, a2) = (0.081_414_823_414_554, 0.459_292_588_292_723);
            let (b1, b2) = (0.658_861_384_496_480, 0.170_569_307_751_760);
            let (c1, c2) = (0.898_905_543_365_938, 0.050_547_228_317_031);
            let (d1, d2, d3) = (0.008_394_777_409_958, 0.728_492_392_955_404, 0.263_112_829_634_638);
            let w = [
                0.144_315_607_677_787 / 2.0,
                0.095_091_634_267_285 / 2.0,
                0.103_217_370_534_718 / 2.0,
                0.032_458_497_623_198 / 2.0,
                0.027_230_314_174_435 / 2.0,
            ];
            tri(
                "FPG16",
                &[
                    (1.0 / 3.0, 1.0 / 3.0),
                    (a1, a2),
                    (a2, a1),
                    (a2, a2),
                    (b1, b2),
                    (b2, b1),
                    (b2, b2),
                    (c1, c2),
                    (c2, c1),
                    (c2, c2),
                    (d1, d2),
                    (d2, d1),
                    (d3, d1),
                    (d1, d3),
                    (d3, d2),
                    (d2, d3),
                ],
                &[w[0], w[1], w[1], w[1], w[2], w[2], w[2], w[3], w[3], w[3], w[4], w[4], w[4], w[4], w[4], w[4]],
                8,
            )
        }
        _ => return None,
    })
}

fn tet(name: &str, pts: Vec<[f64; 3]>, w: Vec<f64>, degree: usize) -> QuadratureRule {
    QuadratureRule::new(name, RefDomain::Tetrahedron, pts, w, degree)
}

/// Code_Aster's tetrahedron families (`elraga.F90`, TE4/T10).
fn aster_tetrahedron(name: &str) -> Option<QuadratureRule> {
    let s5 = 5f64.sqrt();
    let s15 = 15f64.sqrt();
    Some(match name {
        "FPG1" => tet("FPG1", vec![[0.25; 3]], vec![1.0 / 6.0], 1),
        // 4 points (Touzot p. 300), degree 2.
        "FPG4" => {
            let a = (5.0 - s5) / 20.0;
            let b = (5.0 + 3.0 * s5) / 20.0;
            tet("FPG4", vec![[a, a, a], [a, a, b], [a, b, a], [b, a, a]], vec![1.0 / 24.0; 4], 2)
        }
        // 5 points with a negative weight (Touzot p. 300), degree 3.
        "FPG5" => {
            let (a, b, c) = (0.25, 1.0 / 6.0, 0.5);
            tet(
                "FPG5",
                vec![[a, a, a], [b, b, b], [b, b, c], [b, c, b], [c, b, b]],
                vec![-2.0 / 15.0, 3.0 / 40.0, 3.0 / 40.0, 3.0 / 40.0, 3.0 / 40.0],
                3,
            )
        }
        // 15 points (Keast; Touzot p. 300), degree 5, closed form.
        "FPG15" => {
            let b1 = (7.0 + s15) / 34.0;
            let b2 = (7.0 - s15) / 34.0;
            let c1 = (13.0 - 3.0 * s15) / 34.0;
            let c2 = (13.0 + 3.0 * s15) / 34.0;
            let d = (5.0 - s15) / 20.0;
            let e = (5.0 + s15) / 20.0;
            let h1 = (2665.0 - 14.0 * s15) / 226_800.0;
            let h2 = (2665.0 + 14.0 * s15) / 226_800.0;
            let h3 = 5.0 / 567.0;
            tet(
                "FPG15",
                vec![
                    [0.25; 3],
                    [b1, b1, b1],
                    [b1, b1, c1],
                    [b1, c1, b1],
                    [c1, b1, b1],
                    [b2, b2, b2],
                    [b2, b2, c2],
                    [b2, c2, b2],
                    [c2, b2, b2],
                    [d, d, e],
                    [d, e, d],
                    [e, d, d],
                    [d, e, e],
                    [e, d, e],
                    [e, e, d],
                ],
                vec![8.0 / 405.0, h1, h1, h1, h1, h2, h2, h2, h2, h3, h3, h3, h3, h3, h3],
                5,
            )
        }
        // 24 points, degree 6 (Jaśkowiec & Sukumar, "High-order symmetric
        // cubature rules for tetrahedra and pyramids", IJNME 2021,
        // doi:10.1002/nme.6528), as tabulated in recent `elraga.F90`.
        "FPG24" => {
            let (a, a3) = (0.040_673_958_534_611_35, 0.877_978_124_396_166);
            let (b, b3) = (0.322_337_890_142_275_5, 0.032_986_329_573_173_47);
            let (c, c3) = (0.214_602_871_259_152_03, 0.356_191_386_222_543_9);
            let (d, e, f) = (0.603_005_664_791_649_2, 0.063_661_001_875_017_53, 0.269_672_331_458_315_8);
            let (wa, wb, wc, wd) = (
                0.001_679_535_175_886_774,
                0.009_226_196_923_942_455,
                0.006_653_791_709_694_583,
                0.008_035_714_285_714_287,
            );
            let mut pts = vec![[a, a, a], [a3, a, a], [a, a3, a], [a, a, a3]];
            pts.extend([[b, b, b], [b3, b, b], [b, b3, b], [b, b, b3]]);
            pts.extend([[c, c, c], [c3, c, c], [c, c3, c], [c, c, c3]]);
            pts.extend([
                [d, e, e],
                [e, d, e],
                [e, e, d],
                [f, e, e],
                [f, d, e],
                [f, e, d],
                [e, f, e],
                [d, f, e],
                [e, f, d],
                [e, e, f],
                [d, e, f],
                [e, d, f],
            ]);
            let mut w = vec![wa; 4];
            w.extend([wb; 4]);
            w.extend([wc; 4]);
            w.extend([wd; 12]);
            tet("FPG24", pts, w, 6)
        }
        _ => return None,
    })
}

// ---------------------------------------------------------------------------
// Prisms and pyramids (Code_Aster's families)
// ---------------------------------------------------------------------------

/// Prism rule: 1D rule along x (outer loop) × triangle rule in (y, z)
/// (inner loop), Code_Aster's order.
fn prism_product(name: &str, x: &[f64], wx: &[f64], t: &QuadratureRule, degree: usize) -> QuadratureRule {
    let mut pts = Vec::new();
    let mut w = Vec::new();
    for (xi, wi) in x.iter().zip(wx) {
        for (p, wt) in t.points.iter().zip(&t.weights) {
            pts.push([*xi, p[0], p[1]]);
            w.push(wi * wt);
        }
    }
    QuadratureRule::new(name, RefDomain::Prism, pts, w, degree)
}

/// Code_Aster's prism families (`elraga.F90`, PE6/P15).
fn aster_prism(name: &str) -> Option<QuadratureRule> {
    let (g2, w2) = gl_ordered(2, &[-1, 1]);
    let (g3, w3) = gl_ordered(3, &[-1, 0, 1]);
    Some(match name {
        "FPG1" => QuadratureRule::new("FPG1", RefDomain::Prism, vec![[0.0, 1.0 / 3.0, 1.0 / 3.0]], vec![1.0], 1),
        // 2 Gauss points along x × 3 mid-edge points, degree 2.
        "FPG6" => prism_product("FPG6", &g2, &w2, &aster_triangle("COT3")?, 2),
        // 2 Gauss points along x × 3 interior points, degree 2.
        "FPG6B" => prism_product("FPG6B", &g2, &w2, &aster_triangle("FPG3")?, 2),
        // 2 Gauss points × Hammer 4 points (Touzot p. 297), degree 3.
        "FPG8" => {
            let h = QuadratureRule::new(
                "H4",
                RefDomain::Triangle,
                vec![[1.0 / 3.0, 1.0 / 3.0, 0.0], [0.6, 0.2, 0.0], [0.2, 0.6, 0.0], [0.2, 0.2, 0.0]],
                vec![-27.0 / 96.0, 25.0 / 96.0, 25.0 / 96.0, 25.0 / 96.0],
                3,
            );
            prism_product("FPG8", &g2, &w2, &h, 3)
        }
        // 3 Gauss points × 7 Hammer points (Touzot p. 298), degree 5.
        "FPG21" => prism_product("FPG21", &g3, &w3, &aster_triangle("FPG7")?, 5),
        _ => return None,
    })
}

fn pyr(name: &str, pts: Vec<[f64; 3]>, w: Vec<f64>, degree: usize) -> QuadratureRule {
    QuadratureRule::new(name, RefDomain::Pyramid, pts, w, degree)
}

/// Code_Aster's pyramid families (`elraga.F90`, PY5/P13).
fn aster_pyramid(name: &str) -> Option<QuadratureRule> {
    Some(match name {
        // Centroid of the volume (Witherden–Vincent), degree 1.
        "FPG1B" => pyr("FPG1B", vec![[0.0, 0.0, 0.25]], vec![2.0 / 3.0], 1),
        // 5 points, equal weights 2/15, degree 2. z = 1/4 ∓ ... in closed form.
        "FPG5" => {
            let s15 = 15f64.sqrt();
            let h1 = 0.25 - s15 / 40.0;
            let h2 = 0.25 + s15 / 10.0;
            pyr(
                "FPG5",
                vec![[0.5, 0.0, h1], [0.0, 0.5, h1], [-0.5, 0.0, h1], [0.0, -0.5, h1], [0.0, 0.0, h2]],
                vec![2.0 / 15.0; 5],
                2,
            )
        }
        // 6 points (Witherden & Vincent, "On the identification of symmetric
        // quadrature rules for finite element methods", CAMWA 69, 2015),
        // degree 3. The tabulated data are accurate to about 1e-8.
        "FPG6" => {
            let a = 0.561_083_611_058_739_6;
            let h = 0.166_666_666_666_666_7;
            let w = 0.105_882_351_668_529_1;
            pyr(
                "FPG6",
                vec![
                    [0.0, 0.0, 0.571_428_570_386_068_3],
                    [0.0, 0.0, 5.675_85e-9],
                    [-a, 0.0, h],
                    [0.0, -a, h],
                    [0.0, a, h],
                    [a, 0.0, h],
                ],
                vec![0.168_137_255_948_507_1, 0.075_000_004_044_043_33, w, w, w, w],
                3,
            )
        }
        // 10 points (Witherden & Vincent 2015), degree 4.
        "FPG10" => {
            let a = 0.325_290_778_199_116_3;
            let ha = 0.322_384_149_578_213_7;
            let wa = 0.070_883_058_592_883_67;
            let b = 0.657_966_997_121_69;
            let hb = 0.039_248_283_898_815_4;
            let wb = 0.042_346_060_447_083_94;
            pyr(
                "FPG10",
                vec![
                    [0.0, 0.0, 0.677_232_788_886_137_4],
                    [0.0, 0.0, 0.125_136_953_108_746_5],
                    [-a, -a, ha],
                    [-a, a, ha],
                    [a, a, ha],
                    [a, -a, ha],
                    [-b, 0.0, hb],
                    [0.0, -b, hb],
                    [0.0, b, hb],
                    [b, 0.0, hb],
                ],
                vec![0.075_827_922_113_761_27, 0.137_922_268_393_034_9, wa, wa, wa, wa, wb, wb, wb, wb],
                4,
            )
        }
        _ => return None,
    })
}

// ---------------------------------------------------------------------------
// Code_Aster families by name
// ---------------------------------------------------------------------------

/// Families implemented for each cell type (a subset of `elraca.F90`'s
/// lists: `NOEU_S`-style "nodes plus Gauss points" families (`FPG4NOS`...),
/// shell/XFEM-specific families and a few high-order tables are missing).
pub fn aster_families(t: CellType) -> &'static [&'static str] {
    use CellType::*;
    match t {
        Poi1 => &["NOEU", "NOEU_S", "FPG1"],
        Seg2 | Seg3 | Seg4 => &["NOEU", "NOEU_S", "FPG1", "FPG2", "FPG3", "FPG4", "FPG5", "FPG6", "FPG7", "FPG8"],
        Tria3 => &["NOEU", "NOEU_S", "FPG1", "FPG3", "FPG4", "FPG6", "FPG7", "FPG12", "COT3", "FPG13", "FPG16"],
        Tria6 | Tria7 => &["NOEU", "NOEU_S", "FPG1", "FPG3", "FPG4", "FPG6", "FPG7", "FPG12", "FPG13", "FPG16"],
        Quad4 | Quad9 => &["NOEU", "NOEU_S", "FPG1", "FPG4", "FPG9", "FPG16", "FPG25", "FPG36", "FPG49", "FPG64"],
        Quad8 => &["NOEU", "NOEU_S", "FPG1", "FPG4", "FPG9"],
        Tetra4 => &["NOEU", "NOEU_S", "FPG1", "FPG4", "FPG5", "FPG15", "FPG24"],
        Tetra10 => &["NOEU", "NOEU_S", "FPG1", "FPG4", "FPG5", "FPG15"],
        Penta6 | Penta15 | Penta18 => &["NOEU", "NOEU_S", "FPG1", "FPG6", "FPG6B", "FPG8", "FPG21"],
        Pyram5 | Pyram13 => &["NOEU", "NOEU_S", "FPG1", "FPG1B", "FPG5", "FPG6", "FPG10"],
        Hexa8 | Hexa27 => &["NOEU", "NOEU_S", "FPG1", "FPG8", "FPG27", "FPG64", "FPG125", "FPG216", "FPG343", "FPG512"],
        Hexa20 => &["NOEU", "NOEU_S", "FPG1", "FPG8", "FPG27", "FPG64"],
    }
}

/// Rule on the nodes (`NOEU`, all nodes) or the vertices (`NOEU_S`) with
/// equal weights measure / count, or Code_Aster's generic `FPG1` (one point
/// at the average of the nodes, weight = measure). Degree 1 when the point
/// average is the domain's centroid, 0 otherwise (pyramids).
fn nodal_rule(t: CellType, name: &str) -> QuadratureRule {
    let nodes = node_coords(t);
    let vol = ref_measure(t);
    let domain = RefDomain::of(t);
    let avg_degree = |pts: &[[f64; 3]]| -> usize {
        let c = ref_centroid(t);
        let n = pts.len() as f64;
        let ok = (0..3).all(|k| (pts.iter().map(|p| p[k]).sum::<f64>() / n - c[k]).abs() < 1e-14);
        if t == CellType::Poi1 || !ok {
            0
        } else {
            1
        }
    };
    match name {
        "NOEU" => {
            let pts = nodes.to_vec();
            let d = avg_degree(&pts);
            QuadratureRule::new("NOEU", domain, pts, vec![vol / nodes.len() as f64; nodes.len()], d)
        }
        "NOEU_S" => {
            let pts = nodes[..t.nvertices()].to_vec();
            let d = avg_degree(&pts);
            let w = vec![vol / pts.len() as f64; pts.len()];
            QuadratureRule::new("NOEU_S", domain, pts, w, d)
        }
        _ => {
            let n = nodes.len() as f64;
            let mut p = [0.0; 3];
            for c in nodes {
                for k in 0..3 {
                    p[k] += c[k] / n;
                }
            }
            let d = avg_degree(nodes);
            QuadratureRule::new("FPG1", domain, vec![p], vec![vol], d)
        }
    }
}

/// Code_Aster's quadrature family `name` (`"FPG27"`, `"NOEU"`, `"COT3"`,
/// ...) on the reference element of `t`, with Code_Aster's point order and
/// weights (`elraga.F90`). `None` when the family does not exist for this
/// element or is not implemented (see [`aster_families`]).
pub fn aster_rule(t: CellType, name: &str) -> Option<QuadratureRule> {
    if !aster_families(t).contains(&name) {
        return None;
    }
    if name == "NOEU" || name == "NOEU_S" || name == "FPG1" {
        return Some(nodal_rule(t, name));
    }
    match RefDomain::of(t) {
        RefDomain::Point => None,
        RefDomain::Segment => {
            let n: usize = name.strip_prefix("FPG")?.parse().ok()?;
            let (x, w) = gl_ordered(n, &aster_segment_order(n));
            let pts = x.iter().map(|&v| [v, 0.0, 0.0]).collect();
            Some(QuadratureRule::new(name, RefDomain::Segment, pts, w, 2 * n - 1))
        }
        RefDomain::Quadrangle => {
            let a = 1.0 / 3f64.sqrt();
            let b = 0.6f64.sqrt();
            match name {
                // 2×2 Gauss, counter-clockwise like the vertices, degree 3.
                "FPG4" => Some(QuadratureRule::new(
                    name,
                    RefDomain::Quadrangle,
                    vec![[-a, -a, 0.0], [a, -a, 0.0], [a, a, 0.0], [-a, a, 0.0]],
                    vec![1.0; 4],
                    3,
                )),
                // 3×3 Gauss: corners, mid-sides, centre (node-like order), degree 5.
                "FPG9" => {
                    let (c, m, z) = (25.0 / 81.0, 40.0 / 81.0, 64.0 / 81.0);
                    Some(QuadratureRule::new(
                        name,
                        RefDomain::Quadrangle,
                        vec![
                            [-b, -b, 0.0],
                            [b, -b, 0.0],
                            [b, b, 0.0],
                            [-b, b, 0.0],
                            [0.0, -b, 0.0],
                            [b, 0.0, 0.0],
                            [0.0, b, 0.0],
                            [-b, 0.0, 0.0],
                            [0.0, 0.0, 0.0],
                        ],
                        vec![c, c, c, c, m, m, m, m, z],
                        5,
                    ))
                }
                // n×n Gauss tensor products, x varying slowest.
                _ => {
                    let nn: usize = name.strip_prefix("FPG")?.parse().ok()?;
                    let n = (nn as f64).sqrt().round() as usize;
                    let (x, w) = gl_ordered(n, &aster_tensor_order(n));
                    let (pts, wts) = tensor(&x, &w, 2);
                    Some(QuadratureRule::new(name, RefDomain::Quadrangle, pts, wts, 2 * n - 1))
                }
            }
        }
        RefDomain::Hexahedron => {
            // n×n×n Gauss tensor products, x slowest, z fastest.
            let nn: usize = name.strip_prefix("FPG")?.parse().ok()?;
            let n = (nn as f64).cbrt().round() as usize;
            let (x, w) = gl_ordered(n, &aster_tensor_order(n));
            let (pts, wts) = tensor(&x, &w, 3);
            Some(QuadratureRule::new(name, RefDomain::Hexahedron, pts, wts, 2 * n - 1))
        }
        RefDomain::Triangle => aster_triangle(name),
        RefDomain::Tetrahedron => aster_tetrahedron(name),
        RefDomain::Prism => aster_prism(name),
        RefDomain::Pyramid => aster_pyramid(name),
    }
}

/// Code_Aster's integration-point families ("locations") of an element.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Family {
    /// `RIGI`: rigidity (stiffness) integration; the location of stresses,
    /// strains and internal variables (SIEF_ELGA, VARI_ELGA).
    Rigi,
    /// `MASS`: mass-matrix integration.
    Mass,
    /// `NOEU`: the nodes.
    Noeu,
    /// `FPG1`: one point.
    Fpg1,
}

/// Name of the Code_Aster family used by default for `fam` on the standard
/// isoparametric mechanical elements built on `t`: 3D elements
/// (`MECA_HEXA8`...) for volume cells, plane elements (`MEDPQU4`,
/// `MECPTR6`...) for 2D cells, 2D skin elements (`MEPLSE2`/`MEPLSE3`) for
/// segments. Source: `catalo/cataelem/Elements/meca_3d.py`,
/// `meca_d_plan.py`, `meca_2d_skin.py` (recent code_aster; in releases
/// before the pyramid rules were updated, PYRAM13 used `FPG27`).
///
/// | cell    | RIGI  | MASS  |
/// |---------|-------|-------|
/// | POI1    | FPG1  | FPG1  |
/// | SEG2    | FPG2  | FPG2 (skin elements define no MASS; same as RIGI here) |
/// | SEG3    | FPG4  | FPG4 (idem) |
/// | TRIA3   | FPG1  | FPG3  |
/// | TRIA6   | FPG3  | FPG6  |
/// | QUAD4   | FPG4  | FPG4  |
/// | QUAD8   | FPG9  | FPG9  |
/// | QUAD9   | FPG9  | FPG9  |
/// | TETRA4  | FPG1  | FPG4  |
/// | TETRA10 | FPG5  | FPG15 |
/// | PENTA6  | FPG6  | FPG6  |
/// | PENTA15 | FPG21 | FPG21 |
/// | PYRAM5  | FPG5  | FPG5  |
/// | PYRAM13 | FPG10 | FPG10 |
/// | HEXA8   | FPG8  | FPG8  |
/// | HEXA20  | FPG27 | FPG27 |
/// | HEXA27  | FPG27 | FPG27 |
pub fn default_family(t: CellType, fam: Family) -> &'static str {
    use CellType::*;
    match fam {
        Family::Noeu => "NOEU",
        Family::Fpg1 => "FPG1",
        Family::Rigi | Family::Mass => {
            let rigi = fam == Family::Rigi;
            match t {
                Poi1 => "FPG1",
                Seg2 => "FPG2",
                Seg3 => "FPG4",
                Seg4 => "FPG4",
                Tria3 => {
                    if rigi {
                        "FPG1"
                    } else {
                        "FPG3"
                    }
                }
                Tria6 => {
                    if rigi {
                        "FPG3"
                    } else {
                        "FPG6"
                    }
                }
                Tria7 => "FPG6",
                Quad4 => "FPG4",
                Quad8 | Quad9 => "FPG9",
                Tetra4 => {
                    if rigi {
                        "FPG1"
                    } else {
                        "FPG4"
                    }
                }
                Tetra10 => {
                    if rigi {
                        "FPG5"
                    } else {
                        "FPG15"
                    }
                }
                Penta6 => "FPG6",
                Penta15 | Penta18 => "FPG21",
                Pyram5 => "FPG5",
                Pyram13 => "FPG10",
                Hexa8 => "FPG8",
                Hexa20 | Hexa27 => "FPG27",
            }
        }
    }
}

/// The default rule of `fam` on `t` (see [`default_family`]).
pub fn family_rule(t: CellType, fam: Family) -> QuadratureRule {
    let name = default_family(t, fam);
    aster_rule(t, name).unwrap_or_else(|| panic!("family {name} missing for {}", t.name()))
}

// ---------------------------------------------------------------------------
// Generic rules of a requested degree
// ---------------------------------------------------------------------------

/// Collapsed-coordinate ("conical product", Stroud) rule on the triangle,
/// exact for degree `d`: x = u, y = v (1 - u), with Gauss–Legendre in u and v.
fn collapsed_triangle(d: usize) -> QuadratureRule {
    let nu = (d + 2).div_ceil(2);
    let nv = (d + 1).div_ceil(2);
    let (xu, wu) = gauss_legendre_1d(nu);
    let (xv, wv) = gauss_legendre_1d(nv);
    let mut pts = Vec::new();
    let mut w = Vec::new();
    for (a, wa) in xu.iter().zip(&wu) {
        let u = 0.5 * (a + 1.0);
        for (b, wb) in xv.iter().zip(&wv) {
            let v = 0.5 * (b + 1.0);
            pts.push([u, v * (1.0 - u), 0.0]);
            w.push(0.25 * wa * wb * (1.0 - u));
        }
    }
    QuadratureRule::new(&format!("TRI-CONICAL-DEG{d}"), RefDomain::Triangle, pts, w, d)
}

/// Collapsed-coordinate rule on the tetrahedron, exact for degree `d`:
/// x = u, y = v (1 - u), z = w (1 - u)(1 - v).
fn collapsed_tetrahedron(d: usize) -> QuadratureRule {
    let (xu, wu) = gauss_legendre_1d((d + 3).div_ceil(2));
    let (xv, wv) = gauss_legendre_1d((d + 2).div_ceil(2));
    let (xw, ww) = gauss_legendre_1d((d + 1).div_ceil(2));
    let mut pts = Vec::new();
    let mut w = Vec::new();
    for (a, wa) in xu.iter().zip(&wu) {
        let u = 0.5 * (a + 1.0);
        for (b, wb) in xv.iter().zip(&wv) {
            let v = 0.5 * (b + 1.0);
            for (c, wc) in xw.iter().zip(&ww) {
                let s = 0.5 * (c + 1.0);
                pts.push([u, v * (1.0 - u), s * (1.0 - u) * (1.0 - v)]);
                w.push(0.125 * wa * wb * wc * (1.0 - u) * (1.0 - u) * (1.0 - v));
            }
        }
    }
    QuadratureRule::new(&format!("TET-CONICAL-DEG{d}"), RefDomain::Tetrahedron, pts, w, d)
}

/// Conical product rule on the pyramid, exact for degree `d`:
/// x = (u - v)(1 - z)/2, y = (u + v)(1 - z)/2 with u, v ∈ [-1, 1] (Gauss in
/// u, v) and Gauss in z for the factor (1 - z)² / 2 of the Jacobian.
fn conical_pyramid(d: usize) -> QuadratureRule {
    let (xs, ws) = gauss_legendre_1d((d + 1).div_ceil(2));
    let (xz, wz) = gauss_legendre_1d((d + 3).div_ceil(2));
    let mut pts = Vec::new();
    let mut w = Vec::new();
    for (c, wc) in xz.iter().zip(&wz) {
        let z = 0.5 * (c + 1.0);
        let s = 1.0 - z;
        for (a, wa) in xs.iter().zip(&ws) {
            for (b, wb) in xs.iter().zip(&ws) {
                pts.push([0.5 * (a - b) * s, 0.5 * (a + b) * s, z]);
                w.push(0.5 * wc * wa * wb * s * s * 0.5);
            }
        }
    }
    QuadratureRule::new(&format!("PYR-CONICAL-DEG{d}"), RefDomain::Pyramid, pts, w, d)
}

/// A rule on `domain` that integrates every polynomial of total degree
/// ≤ `degree` exactly, with few points: Gauss–Legendre (tensor) rules on
/// segments, quadrangles and hexahedra; Code_Aster's symmetric tables on
/// triangles (up to degree 8) and tetrahedra (up to degree 6), collapsed
/// Gauss rules beyond; triangle × Gauss on prisms; Code_Aster's pyramid
/// rules up to degree 4, conical products beyond. The returned rule's
/// `degree` may exceed the request.
pub fn rule_for_degree(domain: RefDomain, degree: usize) -> QuadratureRule {
    let n = (degree + 1).div_ceil(2).max(1);
    match domain {
        RefDomain::Point => QuadratureRule::new("POINT", RefDomain::Point, vec![[0.0; 3]], vec![1.0], usize::MAX),
        RefDomain::Segment => gauss_legendre(n),
        RefDomain::Quadrangle | RefDomain::Hexahedron => {
            let dim = domain.dim();
            let (x, w) = gauss_legendre_1d(n);
            let (pts, wts) = tensor(&x, &w, dim);
            QuadratureRule::new(&format!("GAUSS{n}^{dim}"), domain, pts, wts, 2 * n - 1)
        }
        RefDomain::Triangle => {
            let name = match degree {
                0 | 1 => "FPG1",
                2 => "FPG3",
                3 => "FPG6", // positive weights preferred over FPG4
                4 => "FPG6",
                5 => "FPG7",
                6 => "FPG12",
                7 | 8 => "FPG16",
                _ => return collapsed_triangle(degree),
            };
            aster_triangle(name).expect("tabulated triangle rule")
        }
        RefDomain::Tetrahedron => {
            let name = match degree {
                0 | 1 => "FPG1",
                2 => "FPG4",
                3..=5 => "FPG15",
                6 => "FPG24",
                _ => return collapsed_tetrahedron(degree),
            };
            aster_tetrahedron(name).expect("tabulated tetrahedron rule")
        }
        RefDomain::Prism => {
            let t = rule_for_degree(RefDomain::Triangle, degree);
            let (x, w) = gauss_legendre_1d(n);
            let d = t.degree.min(2 * n - 1);
            prism_product(&format!("PRISM-DEG{d}"), &x, &w, &t, d)
        }
        RefDomain::Pyramid => match degree {
            0 | 1 => aster_pyramid("FPG1B").expect("pyramid rule"),
            2 => aster_pyramid("FPG5").expect("pyramid rule"),
            // FPG6 is accurate only to ~1e-8 (tabulated data), FPG10 to ~1e-15.
            3 | 4 => aster_pyramid("FPG10").expect("pyramid rule"),
            _ => conical_pyramid(degree),
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fact(n: usize) -> f64 {
        (1..=n).map(|k| k as f64).product()
    }

    /// Exact integral of x^a y^b z^c over the reference domain.
    fn exact(domain: RefDomain, a: usize, b: usize, c: usize) -> f64 {
        let seg = |k: usize| if k.is_multiple_of(2) { 2.0 / (k as f64 + 1.0) } else { 0.0 };
        let tri = |a: usize, b: usize| fact(a) * fact(b) / fact(a + b + 2);
        match domain {
            RefDomain::Point => 1.0,
            RefDomain::Segment => seg(a),
            RefDomain::Quadrangle => seg(a) * seg(b),
            RefDomain::Hexahedron => seg(a) * seg(b) * seg(c),
            RefDomain::Triangle => tri(a, b),
            RefDomain::Tetrahedron => fact(a) * fact(b) * fact(c) / fact(a + b + c + 3),
            RefDomain::Prism => seg(a) * tri(b, c),
            RefDomain::Pyramid => {
                if a % 2 == 1 || b % 2 == 1 {
                    0.0
                } else {
                    4.0 * fact(a) * fact(b) * fact(c) / fact(a + b + c + 3)
                }
            }
        }
    }

    /// Largest error over monomials of total degree exactly `d`.
    fn max_error(rule: &QuadratureRule, d: usize) -> f64 {
        let dim = rule.domain.dim();
        let mut worst: f64 = 0.0;
        for a in 0..=d {
            for b in 0..=(d - a) {
                let c = d - a - b;
                if (dim < 2 && b > 0) || (dim < 3 && c > 0) {
                    continue;
                }
                let q = rule.integrate(|p| p[0].powi(a as i32) * p[1].powi(b as i32) * p[2].powi(c as i32));
                let e = exact(rule.domain, a, b, c);
                worst = worst.max((q - e).abs());
            }
        }
        worst
    }

    /// Check the stated degree: exact up to it, not exact one degree above.
    fn check(rule: &QuadratureRule, tol: f64) {
        let s: f64 = rule.weights.iter().sum();
        assert!((s - rule.domain.measure()).abs() < tol, "{} on {:?}: weights sum to {s}", rule.name, rule.domain);
        for d in 0..=rule.degree {
            let e = max_error(rule, d);
            assert!(e < tol, "{} on {:?}: degree {d} error {e:e}", rule.name, rule.domain);
        }
        let e = max_error(rule, rule.degree + 1);
        assert!(e > 1e3 * tol, "{} on {:?}: also exact at degree {} ({e:e})", rule.name, rule.domain, rule.degree + 1);
    }

    #[test]
    fn gauss_legendre_1_to_10() {
        for n in 1..=10 {
            let r = gauss_legendre(n);
            assert_eq!(r.len(), n);
            assert!(r.points.windows(2).all(|p| p[0][0] < p[1][0]));
            check(&r, 1e-13);
        }
        let (x, w) = gauss_legendre_1d(2);
        assert!((x[1] - 1.0 / 3f64.sqrt()).abs() < 1e-15 && (w[0] - 1.0).abs() < 1e-15);
    }

    #[test]
    fn code_aster_families_are_exact_to_their_degree() {
        for t in CellType::ALL {
            if t == CellType::Poi1 {
                continue;
            }
            for name in aster_families(t) {
                let r = aster_rule(t, name).unwrap_or_else(|| panic!("{} {name}", t.name()));
                assert_eq!(r.domain, RefDomain::of(t));
                let tol = match *name {
                    "FPG13" => 1e-11,
                    "FPG16" if r.domain == RefDomain::Triangle => 1e-13,
                    "FPG6" if r.domain == RefDomain::Pyramid => 1e-7,
                    _ => 1e-13,
                };
                check(&r, tol);
                for p in &r.points {
                    assert!(super::super::reference::is_inside(t, p, 1e-12), "{} {name}: {p:?}", t.name());
                }
            }
        }
    }

    #[test]
    fn generic_rules_reach_requested_degree() {
        let domains = [
            RefDomain::Segment,
            RefDomain::Triangle,
            RefDomain::Quadrangle,
            RefDomain::Tetrahedron,
            RefDomain::Prism,
            RefDomain::Pyramid,
            RefDomain::Hexahedron,
        ];
        for d in domains {
            for deg in 0..=10 {
                let r = rule_for_degree(d, deg);
                assert!(r.degree >= deg, "{:?} degree {deg}: got {}", d, r.degree);
                let s: f64 = r.weights.iter().sum();
                assert!((s - d.measure()).abs() < 1e-12);
                for k in 0..=deg {
                    let e = max_error(&r, k);
                    assert!(e < 1e-12, "{:?} requested {deg}, rule {} fails degree {k}: {e:e}", d, r.name);
                }
            }
        }
        // Triangle ≥ 6, tetrahedron ≥ 6 with tabulated rules.
        assert_eq!(rule_for_degree(RefDomain::Triangle, 6).name, "FPG12");
        assert_eq!(rule_for_degree(RefDomain::Tetrahedron, 6).name, "FPG24");
        // Stated degrees of the conical rules are exact.
        check(&collapsed_triangle(9), 1e-13);
        check(&collapsed_tetrahedron(8), 1e-13);
        check(&conical_pyramid(7), 1e-13);
    }

    #[test]
    fn default_rules_match_code_aster() {
        use CellType::*;
        let expect = [
            (Poi1, 1, 1),
            (Seg2, 2, 2),
            (Seg3, 4, 4),
            (Tria3, 1, 3),
            (Tria6, 3, 6),
            (Quad4, 4, 4),
            (Quad8, 9, 9),
            (Quad9, 9, 9),
            (Tetra4, 1, 4),
            (Tetra10, 5, 15),
            (Penta6, 6, 6),
            (Penta15, 21, 21),
            (Pyram5, 5, 5),
            (Pyram13, 10, 10),
            (Hexa8, 8, 8),
            (Hexa20, 27, 27),
            (Hexa27, 27, 27),
        ];
        for (t, nr, nm) in expect {
            assert_eq!(family_rule(t, Family::Rigi).len(), nr, "{} RIGI", t.name());
            assert_eq!(family_rule(t, Family::Mass).len(), nm, "{} MASS", t.name());
            assert_eq!(family_rule(t, Family::Noeu).len(), t.nnodes());
            assert_eq!(family_rule(t, Family::Fpg1).len(), 1);
        }
    }

    #[test]
    fn code_aster_point_order() {
        let a = 1.0 / 3f64.sqrt();
        let b = 0.6f64.sqrt();
        // QUAD8 RIGI = FPG9: corners, mid-sides, centre.
        let r = family_rule(CellType::Quad8, Family::Rigi);
        assert_eq!(r.points[0], [-b, -b, 0.0]);
        assert_eq!(r.points[5], [b, 0.0, 0.0]);
        assert_eq!(r.weights[8], 64.0 / 81.0);
        // HEXA8 FPG8: x slowest, z fastest.
        let r = family_rule(CellType::Hexa8, Family::Rigi);
        assert!((r.points[1][2] - a).abs() < 1e-15 && (r.points[1][0] + a).abs() < 1e-15);
        assert!((r.points[4][0] - a).abs() < 1e-15 && (r.points[4][2] + a).abs() < 1e-15);
        // HEXA20 FPG27: first point (-b,-b,-b), second (-b,-b,0), weights (5/9)^3 ...
        let r = family_rule(CellType::Hexa20, Family::Rigi);
        assert!((r.points[0][0] + b).abs() < 1e-15 && (r.points[1][2]).abs() < 1e-15);
        assert!((r.weights[13] - (8.0f64 / 9.0).powi(3)).abs() < 1e-15);
        // SEG FPG2: +a first.
        let r = aster_rule(CellType::Seg2, "FPG2").unwrap();
        assert!((r.points[0][0] - a).abs() < 1e-15);
        // TETRA FPG4: 2nd point has z = b.
        let r = aster_rule(CellType::Tetra10, "FPG4").unwrap();
        assert!(r.points[1][2] > 0.5 && r.points[2][1] > 0.5 && r.points[3][0] > 0.5);
        // TRIA6 RIGI = FPG3.
        let r = family_rule(CellType::Tria6, Family::Rigi);
        assert_eq!(r.points[1], [2.0 / 3.0, 1.0 / 6.0, 0.0]);
        // PENTA6 FPG6: x slowest, first triangle point (1/2, 1/2).
        let r = family_rule(CellType::Penta6, Family::Rigi);
        assert!((r.points[0][0] + a).abs() < 1e-15 && r.points[0][1] == 0.5 && r.points[0][2] == 0.5);
        assert!((r.points[3][0] - a).abs() < 1e-15);
        // PYRAM13 FPG1 is the node average (z = 3/13), as in Code_Aster.
        let r = family_rule(CellType::Pyram13, Family::Fpg1);
        assert!((r.points[0][2] - 3.0 / 13.0).abs() < 1e-15);
    }
}
