//! Analytic checks of the assembled elements on strips of cells: a plane wall with a uniform source
//! (a parabola, exact at the nodes of quadratic cells), a cylinder wall (`T = a + b ln r`, second order
//! on linear cells) and a wall cooled by exchange on one face (linear, exact on every cell).

use super::boundary::skin_load;
use super::element::{capacity, conduction, source, Conductivity, Modelisation};
use crate::fem::reference::node_coords;
use crate::mesh::CellType;
use nalgebra::{DMatrix, DVector};

/// A strip `[a, b] × [0, 0.1]` of `n` cells of type `t` (QUAD4/8/9), as node coordinates and cells;
/// nodes merged by position.
fn strip(t: CellType, a: f64, b: f64, n: usize) -> (Vec<[f64; 3]>, Vec<Vec<usize>>) {
    let mut nodes: Vec<[f64; 3]> = Vec::new();
    let mut cells = Vec::new();
    let h = (b - a) / n as f64;
    for c in 0..n {
        let mut ids = Vec::new();
        for p in node_coords(t) {
            let x = [a + h * (c as f64 + 0.5 * (p[0] + 1.0)), 0.05 * (p[1] + 1.0), 0.0];
            let id = nodes.iter().position(|q| (q[0] - x[0]).abs() < 1e-12 && (q[1] - x[1]).abs() < 1e-12);
            ids.push(id.unwrap_or_else(|| {
                nodes.push(x);
                nodes.len() - 1
            }));
        }
        cells.push(ids);
    }
    (nodes, cells)
}

/// Solve `K T = F` with the temperatures of the nodes at x = a and x = b prescribed (`ta`, `tb`;
/// None: free), K and F from the cells, plus an exchange `h (T_ext − T)` on the face x = b when given.
fn solve(
    m: Modelisation,
    t: CellType,
    (nodes, cells): &(Vec<[f64; 3]>, Vec<Vec<usize>>),
    s: f64,
    ends: (f64, Option<f64>),
    exchange: Option<(f64, f64)>,
) -> Vec<f64> {
    let nn = nodes.len();
    let mut k = DMatrix::zeros(nn, nn);
    let mut f = DVector::zeros(nn);
    for c in cells {
        let x: Vec<[f64; 3]> = c.iter().map(|&i| nodes[i]).collect();
        let ke = conduction(m, t, &x, &Conductivity::Iso(2.0)).unwrap();
        let (fe, _) = source(m, t, &x, None, &|_, _| Ok((s, 0.0))).unwrap();
        for (i, &a) in c.iter().enumerate() {
            f[a] += fe[i];
            for (j, &b) in c.iter().enumerate() {
                k[(a, b)] += ke[i * c.len() + j];
            }
        }
    }
    let xmax = nodes.iter().map(|p| p[0]).fold(f64::MIN, f64::max);
    let xmin = nodes.iter().map(|p| p[0]).fold(f64::MAX, f64::min);
    if let Some((h, text)) = exchange {
        // The face x = b: its nodes in order of y, as one SEG3 (or SEG2) cell.
        let mut face: Vec<usize> = (0..nn).filter(|&i| (nodes[i][0] - xmax).abs() < 1e-12).collect();
        face.sort_by(|&i, &j| nodes[i][1].total_cmp(&nodes[j][1]));
        let (st, order) =
            if face.len() == 3 { (CellType::Seg3, vec![face[0], face[2], face[1]]) } else { (CellType::Seg2, face) };
        let x: Vec<[f64; 3]> = order.iter().map(|&i| nodes[i]).collect();
        let (fe, de) = skin_load(m, st, &x, None, &|_, _| Ok((h * text, -h))).unwrap();
        for (i, &a) in order.iter().enumerate() {
            f[a] += fe[i];
            for (j, &b) in order.iter().enumerate() {
                k[(a, b)] -= de[i * order.len() + j];
            }
        }
    }
    for i in 0..nn {
        let v = if (nodes[i][0] - xmin).abs() < 1e-12 {
            Some(ends.0)
        } else if (nodes[i][0] - xmax).abs() < 1e-12 {
            ends.1
        } else {
            None
        };
        if let Some(v) = v {
            for j in 0..nn {
                k[(i, j)] = 0.0;
            }
            k[(i, i)] = 1.0;
            f[i] = v;
        }
    }
    k.lu().solve(&f).unwrap().iter().copied().collect()
}

#[test]
fn a_plane_wall_with_a_source_is_exact_at_the_nodes() {
    // −λ T'' = s on [0, 1], T(0) = T(1) = 0: T = s x (1 − x) / (2λ).
    let m = Modelisation::from_name("PLAN").unwrap();
    for t in [CellType::Quad8, CellType::Quad9, CellType::Quad4] {
        let mesh = strip(t, 0.0, 1.0, 4);
        let temps = solve(m, t, &mesh, 8.0, (0.0, Some(0.0)), None);
        for (p, v) in mesh.0.iter().zip(&temps) {
            let exact = 8.0 * p[0] * (1.0 - p[0]) / 4.0;
            // Linear cells are nodally exact in 1D conduction too (the Green function is piecewise linear).
            assert!((v - exact).abs() < 1e-10, "{t:?} at x = {}: {v} vs {exact}", p[0]);
        }
    }
}

#[test]
fn a_cylinder_wall_converges_to_the_logarithm_at_second_order() {
    // Steady AXIS conduction between r = 1 (T = 100) and r = 2 (T = 0): T = 100 (1 − ln r / ln 2).
    let m = Modelisation::from_name("AXIS").unwrap();
    let err = |t: CellType, n: usize| {
        let mesh = strip(t, 1.0, 2.0, n);
        let temps = solve(m, t, &mesh, 0.0, (100.0, Some(0.0)), None);
        mesh.0.iter().zip(&temps).map(|(p, v)| (v - 100.0 * (1.0 - p[0].ln() / 2f64.ln())).abs()).fold(0.0, f64::max)
    };
    let (e8, e16) = (err(CellType::Quad4, 8), err(CellType::Quad4, 16));
    let order = (e8 / e16).log2();
    assert!(e16 < 2e-2 && (order - 2.0).abs() < 0.2, "QUAD4: {e8:e} → {e16:e}, order {order}");
    // Quadratic cells: far more accurate (the nodal error falls faster than second order).
    let (q4, q8) = (err(CellType::Quad8, 4), err(CellType::Quad8, 8));
    assert!(q8 < 1e-3 && q8 < q4 / 8.0, "QUAD8: {q4:e} → {q8:e}");
}

#[test]
fn a_wall_cooled_by_exchange_is_exact() {
    // T(0) = 100, −λ T'(1) = h (T(1) − T_ext): T linear, T(1) = (λ T0 + h T_ext) / (λ + h).
    let m = Modelisation::from_name("PLAN").unwrap();
    let (lam, h, text) = (2.0, 5.0, 20.0);
    let t1 = (lam * 100.0 + h * text) / (lam + h);
    for t in [CellType::Quad4, CellType::Quad8] {
        let mesh = strip(t, 0.0, 1.0, 3);
        let temps = solve(m, t, &mesh, 0.0, (100.0, None), Some((h, text)));
        for (p, v) in mesh.0.iter().zip(&temps) {
            let exact = 100.0 + (t1 - 100.0) * p[0];
            assert!((v - exact).abs() < 1e-9, "{t:?} at x = {}: {v} vs {exact}", p[0]);
        }
    }
}

#[test]
fn a_lumped_capacity_has_the_consistent_total() {
    let m = Modelisation::from_name("PLAN_DIAG").unwrap();
    let (nodes, cells) = strip(CellType::Quad4, 0.0, 1.0, 5);
    let total: f64 = cells
        .iter()
        .map(|c| {
            let x: Vec<[f64; 3]> = c.iter().map(|&i| nodes[i]).collect();
            capacity(m, CellType::Quad4, &x, 3.0).unwrap().iter().sum::<f64>()
        })
        .sum();
    assert!((total - 3.0 * 0.1).abs() < 1e-12);
}
