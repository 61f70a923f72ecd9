//! MODI_REPERE on node fields of a result: vectors (VECT_2D, VECT_3D) and
//! symmetric tensors (TENS_2D, TENS_3D) expressed in a user frame
//! (UTILISATEUR: ANGL_NAUT or VECT_X/VECT_Y) or in the cylindrical frame of
//! each node (CYLINDRIQUE: ORIGINE, AXE_Z), as Code_Aster's `chrpno` does.
//!
//! Conventions (Code_Aster's):
//! * the frame is a matrix P whose rows are the new axes; a vector becomes
//!   `P v`, a tensor `P S Pᵀ`;
//! * UTILISATEUR: P from the nautical angles (α about Z, β about Y1 counted
//!   the other way, γ about X; `matrot`), in degrees; in 2D only α;
//! * CYLINDRIQUE: the rows are `(e_r, e_z, e_θ)` with `e_r` from the axis
//!   to the node, `e_z` = AXE_Z (Z in 2D) and `e_θ = e_z × e_r`. So the
//!   components XX, YY, ZZ of the result are the radial, axial and
//!   circumferential ones: for TENS_3D (SIXX, SIYY, SIZZ, SIXY, SIXZ, SIYZ)
//!   = (σ_rr, σ_zz, σ_θθ, σ_rz, σ_rθ, σ_zθ); for TENS_2D (SIXX, SIYY, SIZZ,
//!   SIXY) = (σ_rr, σ_zz, σ_θθ, σ_rθ). A node on the axis takes the
//!   direction of the centroid of the last cell holding it.
//!
//! The frame is 2D when every node has the same Z (Code_Aster's `Z_CST`).
//! The result holds the selected steps; the fields named in MODI_CHAM are
//! reduced to the transformed components, and a node missing one of them
//! loses them all (as in Code_Aster).

use crate::catalog::args::Args;
use crate::concepts::result::{Field, ResultData, Step};
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::mesh::Mesh;
use crate::stages::select::select_nodes;
use crate::stages::Ctx;
use nalgebra::{Matrix3, Vector3};

/// A frame: its rows are the axes.
type Mat3 = Matrix3<f64>;
type V3 = Vector3<f64>;

/// Code_Aster's `matrot`: the rows of the result are the axes of the frame
/// reached by the nautical angles (radians).
pub fn nautical(alpha: f64, beta: f64, gamma: f64) -> Mat3 {
    let (sa, ca) = alpha.sin_cos();
    let (sb, cb) = beta.sin_cos();
    let (sg, cg) = gamma.sin_cos();
    Matrix3::new(
        cb * ca,
        cb * sa,
        -sb,
        sg * sb * ca - cg * sa,
        cg * ca + sg * sb * sa,
        sg * cb,
        sg * sa + cg * sb * ca,
        cg * sb * sa - ca * sg,
        cg * cb,
    )
}

/// The unit vector along `v`, or None for a zero (or non-finite) one.
fn unit(v: V3) -> Option<V3> {
    v.try_normalize(0.0).filter(|u| u.iter().all(|x| x.is_finite()))
}

/// The nautical angles of the frame whose X axis is `vx` and whose Y axis is
/// in the plane of `vx`, `vy` (Code_Aster's `angvxy`), in radians.
fn angles_of(vx: [f64; 3], vy: [f64; 3]) -> Option<[f64; 3]> {
    let x = unit(V3::from(vx))?;
    let alpha = if x[0] == 0.0 && x[1] == 0.0 { 0.0 } else { x[1].atan2(x[0]) };
    let beta = -x[2].clamp(-1.0, 1.0).asin();
    // Y axis of the frame reached by alpha and beta, then gamma turns it to vy.
    let p = nautical(alpha, beta, 0.0);
    let vy = V3::from(vy);
    let y = unit(vy - vy.dot(&x) * x)?;
    let gamma = y.dot(&p.row(2).transpose()).atan2(y.dot(&p.row(1).transpose()));
    Some([alpha, beta, gamma])
}

/// `P S Pᵀ` for the symmetric tensor `s`.
pub fn rotate_tensor(p: &Mat3, s: &Mat3) -> Mat3 {
    p * s * p.transpose()
}

/// The cylindrical frame (rows e_r, e_z, e_θ) at point `x`, or None on the axis.
pub fn cylindrical_frame(x: [f64; 3], origin: [f64; 3], axis: [f64; 3]) -> Option<Mat3> {
    let axis = V3::from(axis);
    let d = V3::from(x) - V3::from(origin);
    let radial = d - d.dot(&axis) * axis;
    if radial.norm() < 1e-6 {
        return None;
    }
    let r = radial.normalize();
    let t = unit(axis.cross(&r))?;
    Some(Matrix3::from_rows(&[r.transpose(), axis.transpose(), t.transpose()]))
}

/// Kind of a MODI_CHAM occurrence.
#[derive(Clone, Copy, PartialEq, Debug)]
enum Kind {
    Vect2,
    Vect3,
    Tens2,
    Tens3,
}

/// The components transformed by default for a field and a kind.
fn default_components(field: &str, kind: Kind) -> Vec<String> {
    let prefix = if field.starts_with("EPSI") || field.starts_with("EPS") { "EP" } else { "SI" };
    let v: Vec<String> = match kind {
        Kind::Vect2 => ["DX", "DY"].iter().map(|s| s.to_string()).collect(),
        Kind::Vect3 => ["DX", "DY", "DZ"].iter().map(|s| s.to_string()).collect(),
        Kind::Tens2 => ["XX", "YY", "ZZ", "XY"].iter().map(|s| format!("{prefix}{s}")).collect(),
        Kind::Tens3 => ["XX", "YY", "ZZ", "XY", "XZ", "YZ"].iter().map(|s| format!("{prefix}{s}")).collect(),
    };
    v
}

/// How each node's frame is given.
enum Frame {
    Fixed(Mat3),
    Cylinder { origin: [f64; 3], axis: [f64; 3] },
}

/// Transform the values `v` (in the order of the kind's components) with P.
fn apply(kind: Kind, p: &Mat3, v: &[f64]) -> Vec<f64> {
    match kind {
        Kind::Vect2 => vec![p[(0, 0)] * v[0] + p[(0, 1)] * v[1], p[(1, 0)] * v[0] + p[(1, 1)] * v[1]],
        Kind::Vect3 => (p * V3::new(v[0], v[1], v[2])).iter().copied().collect(),
        Kind::Tens2 | Kind::Tens3 => {
            let (xy, xz, yz) = if kind == Kind::Tens2 { (v[3], 0.0, 0.0) } else { (v[3], v[4], v[5]) };
            let s = Matrix3::new(v[0], xy, xz, xy, v[1], yz, xz, yz, v[2]);
            let l = rotate_tensor(p, &s);
            if kind == Kind::Tens3 {
                vec![l[(0, 0)], l[(1, 1)], l[(2, 2)], l[(0, 1)], l[(0, 2)], l[(1, 2)]]
            } else {
                vec![l[(0, 0)], l[(1, 1)], l[(2, 2)], l[(0, 1)]]
            }
        }
    }
}

/// CYLINDRIQUE, 2D tensors: SIXY takes the r-θ term (Code_Aster keeps XX,
/// YY, ZZ and the (1,3) term of the frame (e_r, e_z, e_θ)).
fn apply_cyl(kind: Kind, p: &Mat3, v: &[f64]) -> Vec<f64> {
    if kind == Kind::Tens2 {
        let s = Matrix3::new(v[0], v[3], 0.0, v[3], v[1], 0.0, 0.0, 0.0, v[2]);
        let l = rotate_tensor(p, &s);
        vec![l[(0, 0)], l[(1, 1)], l[(2, 2)], l[(0, 2)]]
    } else {
        apply(kind, p, v)
    }
}

/// A node on the axis: the direction of the centroid of the last cell that
/// holds it (Code_Aster's rule), or None.
fn off_axis_point(mesh: &Mesh, node: usize) -> Option<[f64; 3]> {
    let c = (0..mesh.cells.len()).rev().find(|&c| mesh.cells[c].contains(&node))?;
    let n = mesh.cells[c].len() as f64;
    let mut g = [0.0; 3];
    for &m in &mesh.cells[c] {
        for (gk, xk) in g.iter_mut().zip(mesh.coords[m]) {
            *gk += xk / n;
        }
    }
    Some(g)
}

pub fn modi_repere(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    if a.given("CHAM_GD") {
        return Err(a.err("CHAM_GD", "not supported yet (RESULTAT is)"));
    }
    a.refuse(&["LIST_ORDRE", "NUME_MODE", "NOEUD_CMP", "NOM_CAS", "FREQ", "LIST_FREQ", "LIST_INST"])?;
    let repere = a.req_text("REPERE")?.to_string();
    if !matches!(repere.as_str(), "UTILISATEUR" | "CYLINDRIQUE") {
        return Err(a.err("REPERE", format!("REPERE='{repere}' is not supported yet (UTILISATEUR, CYLINDRIQUE are)")));
    }
    let rc = a.req_concept("RESULTAT")?;
    let (model, material, cara_elem, loads, steps) = {
        let r = rc.result().map_err(|e| a.err("RESULTAT", e.msg))?;
        (r.model.clone(), r.material.clone(), r.cara_elem.clone(), r.loads.clone(), r.steps.clone())
    };
    let (mesh, mesh_name) = {
        let m = model.model().map_err(|e| a.err("RESULTAT", e.msg))?;
        (m.current_mesh(), m.mesh_concept.label())
    };
    // Steps.
    let mut chosen: Vec<Step> = Vec::new();
    if a.has("NUME_ORDRE") {
        for n in a.ints("NUME_ORDRE") {
            let s = steps
                .iter()
                .find(|s| s.nume_ordre == n)
                .ok_or_else(|| a.err("NUME_ORDRE", format!("result {} has no order number {n}", rc.label())))?;
            chosen.push(s.clone());
        }
    } else if a.has("INST") {
        let prec = a.real("PRECISION").unwrap_or(1e-6);
        let absolute = a.text("CRITERE") == Some("ABSOLU");
        for t in a.reals("INST") {
            let s = steps
                .iter()
                .find(|s| {
                    let tol = if absolute { prec } else { prec * t.abs() };
                    (s.inst - t).abs() <= tol
                })
                .ok_or_else(|| a.err("INST", format!("result {} has no step at time {t}", rc.label())))?;
            chosen.push(s.clone());
        }
    } else {
        chosen = steps;
    }
    let z_cst = mesh.coords.iter().all(|x| x[2] == mesh.coords.first().map(|y| y[2]).unwrap_or(0.0));
    let mut text = String::new();
    for occ in a.facts("MODI_CHAM") {
        let field = occ.req_text("NOM_CHAM")?.to_string();
        let kind = match occ.req_text("TYPE_CHAM")? {
            "VECT_2D" => Kind::Vect2,
            "VECT_3D" => Kind::Vect3,
            "TENS_2D" => Kind::Tens2,
            "TENS_3D" => Kind::Tens3,
            other => return Err(occ.err("TYPE_CHAM", format!("TYPE_CHAM='{other}' is not supported yet"))),
        };
        let type_dim = if matches!(kind, Kind::Vect2 | Kind::Tens2) { 2 } else { 3 };
        let mut ndim = if z_cst { 2 } else { 3 };
        if ndim > type_dim {
            return Err(occ.err(
                "TYPE_CHAM",
                format!("the nodes of mesh {mesh_name} are not all in one plane Z = constant: use a 3D type"),
            ));
        } else if ndim < type_dim {
            text.push_str(&format!(
                " <A> MODI_REPERE: a 3D type on the plane mesh {mesh_name}: the frame is taken in 3D\n"
            ));
            ndim = 3;
        }
        if repere == "CYLINDRIQUE" && kind == Kind::Vect2 {
            return Err(occ.err("TYPE_CHAM", "TYPE_CHAM='VECT_2D' in REPERE='CYLINDRIQUE' is not supported yet"));
        }
        let comps = if occ.has("NOM_CMP") { occ.texts("NOM_CMP") } else { default_components(&field, kind) };
        for step in chosen.iter_mut() {
            let Some(f) = step.fields.get(&field) else {
                return Err(occ.err(
                    "NOM_CHAM",
                    format!("result {} has no field {field} at order {}", rc.label(), step.nume_ordre),
                ));
            };
            let Field::Node { components, values } = f else {
                return Err(occ.err("NOM_CHAM", format!("{field} is not a node field: not supported yet")));
            };
            let ncmp = components.len();
            let mut idx = Vec::new();
            for c in &comps {
                idx.push(components.iter().position(|x| x == c).ok_or_else(|| {
                    occ.err(
                        if occ.has("NOM_CMP") { "NOM_CMP" } else { "NOM_CHAM" },
                        format!("field {field} has no component {c} (it has {})", components.join(" ")),
                    )
                })?);
            }
            // The reduced field keeps the field's own order of components.
            let mut keep: Vec<usize> = idx.clone();
            keep.sort_unstable();
            let nn = mesh.coords.len();
            let mut out = vec![f64::NAN; nn * keep.len()];
            for n in 0..nn {
                let v: Vec<f64> = idx.iter().map(|&k| values[n * ncmp + k]).collect();
                if v.iter().any(|x| !x.is_finite()) {
                    continue;
                }
                for (j, &k) in keep.iter().enumerate() {
                    out[n * keep.len() + j] = values[n * ncmp + k];
                }
            }
            let pos = |k: usize| keep.iter().position(|&x| x == k).unwrap();
            for af in a.facts("AFFE") {
                let nodes: Vec<usize> = if af.text("TOUT") == Some("OUI") {
                    (0..nn).collect()
                } else {
                    select_nodes(&mesh, af, &mesh_name)?
                };
                let frame = if repere == "UTILISATEUR" {
                    let ang = if af.has("VECT_X") {
                        if ndim != 3 {
                            return Err(af.err("VECT_X", "VECT_X and VECT_Y need a 3D frame"));
                        }
                        let (x, y) = (af.reals("VECT_X"), af.reals("VECT_Y"));
                        angles_of([x[0], x[1], x[2]], [y[0], y[1], y[2]]).ok_or_else(|| {
                            af.err("VECT_X", "VECT_X and VECT_Y must be independent, non-zero vectors")
                        })?
                    } else {
                        let g = af.reals("ANGL_NAUT");
                        let d = std::f64::consts::PI / 180.0;
                        if ndim == 3 {
                            if g.len() != 3 {
                                return Err(af.err("ANGL_NAUT", "three nautical angles are needed in 3D"));
                            }
                            [g[0] * d, g[1] * d, g[2] * d]
                        } else {
                            if g.len() != 1 {
                                text.push_str(" <A> MODI_REPERE: in 2D only the first nautical angle is used\n");
                            }
                            [g.first().copied().unwrap_or(0.0) * d, 0.0, 0.0]
                        }
                    };
                    Frame::Fixed(nautical(ang[0], ang[1], ang[2]))
                } else {
                    let o = af.reals("ORIGINE");
                    if ndim == 3 {
                        if o.len() != 3 {
                            return Err(af.err("ORIGINE", "a 3D cylindrical frame needs ORIGINE with 3 coordinates"));
                        }
                        let z = af.reals("AXE_Z");
                        if z.len() != 3 {
                            return Err(af.err("AXE_Z", "a 3D cylindrical frame needs AXE_Z"));
                        }
                        let Some(axis) = unit(V3::new(z[0], z[1], z[2])) else {
                            return Err(af.err("AXE_Z", "AXE_Z is zero"));
                        };
                        Frame::Cylinder { origin: [o[0], o[1], o[2]], axis: axis.into() }
                    } else {
                        if o.len() != 2 {
                            text.push_str(" <A> MODI_REPERE: in 2D ORIGINE takes two coordinates\n");
                        }
                        if af.has("AXE_Z") {
                            text.push_str(" <A> MODI_REPERE: AXE_Z is ignored in 2D (the axis is Z)\n");
                        }
                        let origin = [o.first().copied().unwrap_or(0.0), o.get(1).copied().unwrap_or(0.0), 0.0];
                        Frame::Cylinder { origin, axis: [0.0, 0.0, 1.0] }
                    }
                };
                for n in nodes {
                    let p = match &frame {
                        Frame::Fixed(p) => *p,
                        Frame::Cylinder { origin, axis } => {
                            let mut x = mesh.coords[n];
                            if ndim == 2 {
                                x[2] = 0.0;
                            }
                            match cylindrical_frame(x, *origin, *axis) {
                                Some(p) => p,
                                None => {
                                    let Some(mut g) = off_axis_point(&mesh, n) else {
                                        for j in 0..keep.len() {
                                            out[n * keep.len() + j] = f64::NAN;
                                        }
                                        continue;
                                    };
                                    if ndim == 2 {
                                        g[2] = 0.0;
                                    }
                                    cylindrical_frame(g, *origin, *axis).ok_or_else(|| {
                                        af.err(
                                            "ORIGINE",
                                            format!(
                                                "node {} and the cell around it are on the axis: no radial direction",
                                                mesh.node_names[n]
                                            ),
                                        )
                                    })?
                                }
                            }
                        }
                    };
                    let v: Vec<f64> = idx.iter().map(|&k| out[n * keep.len() + pos(k)]).collect();
                    if v.iter().any(|x| !x.is_finite()) {
                        continue;
                    }
                    let w = if matches!(frame, Frame::Cylinder { .. }) {
                        apply_cyl(kind, &p, &v)
                    } else {
                        apply(kind, &p, &v)
                    };
                    for (&k, val) in idx.iter().zip(w) {
                        out[n * keep.len() + pos(k)] = val;
                    }
                }
            }
            let names = keep.iter().map(|&k| components[k].clone()).collect();
            step.fields.insert(field.clone(), Field::Node { components: names, values: out });
        }
    }
    if !text.is_empty() {
        ctx.io.mess(&text);
    }
    Ok(Some(ConceptData::Result(ResultData {
        model,
        material,
        cara_elem,
        loads,
        steps: chosen,
        comportement: Vec::new(),
    })))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-12 * (1.0 + b.abs())
    }

    #[test]
    fn uniaxial_stress_in_cylindrical_frame() {
        // σ = σ0 e_y ⊗ e_y at the point (cos t, sin t): σ_rr = σ0 sin²t,
        // σ_θθ = σ0 cos²t, σ_rθ = σ0 sin t cos t (e_θ = (-sin t, cos t)).
        let s0 = 2.5;
        for t in [0.0f64, 0.3, 1.0, 2.0, -2.5] {
            let p = cylindrical_frame([t.cos(), t.sin(), 0.0], [0.0; 3], [0.0, 0.0, 1.0]).unwrap();
            let w = apply_cyl(Kind::Tens2, &p, &[0.0, s0, 0.7, 0.0]);
            assert!(close(w[0], s0 * t.sin().powi(2)));
            assert!(close(w[1], 0.7), "YY holds the axial (old ZZ) term");
            assert!(close(w[2], s0 * t.cos().powi(2)));
            assert!(close(w[3], s0 * t.sin() * t.cos()));
        }
        assert!(cylindrical_frame([0.0, 0.0, 5.0], [0.0; 3], [0.0, 0.0, 1.0]).is_none());
    }

    #[test]
    fn nautical_angles() {
        // α = 90°: X' = Y, Y' = -X.
        let p = nautical(std::f64::consts::FRAC_PI_2, 0.0, 0.0);
        let v = apply(Kind::Vect3, &p, &[1.0, 2.0, 3.0]);
        assert!(close(v[0], 2.0) && close(v[1], -1.0) && close(v[2], 3.0));
        // Plane stress tensor turned by 30°: Mohr's formulas.
        let a = 30f64.to_radians();
        let p = nautical(a, 0.0, 0.0);
        let (sx, sy, txy) = (10.0, -4.0, 3.0);
        let w = apply(Kind::Tens2, &p, &[sx, sy, 1.5, txy]);
        let c = (2.0 * a).cos();
        let s = (2.0 * a).sin();
        assert!(close(w[0], (sx + sy) / 2.0 + (sx - sy) / 2.0 * c + txy * s));
        assert!(close(w[1], (sx + sy) / 2.0 - (sx - sy) / 2.0 * c - txy * s));
        assert!(close(w[2], 1.5));
        assert!(close(w[3], -(sx - sy) / 2.0 * s + txy * c));
        // β = 90° turns Z onto X' counted the other way: X' = -Z... (matrot: row 1 = (0, 0, -1)).
        let p = nautical(0.0, std::f64::consts::FRAC_PI_2, 0.0);
        assert!(close(p[(0, 2)], -1.0));
    }

    #[test]
    fn vectors_to_angles_and_back() {
        let vx = [1.0, 1.0, 1.0];
        let vy = [-1.0, 1.0, 0.0];
        let g = angles_of(vx, vy).unwrap();
        let p = nautical(g[0], g[1], g[2]);
        let s = 3f64.sqrt();
        assert!(p.row(0).iter().all(|&v| close(v, 1.0 / s)));
        let y = [-1.0 / 2f64.sqrt(), 1.0 / 2f64.sqrt(), 0.0];
        for k in 0..3 {
            assert!((p[(1, k)] - y[k]).abs() < 1e-12);
        }
    }

    #[test]
    fn three_d_tensor_rotation_keeps_invariants() {
        let p = cylindrical_frame([1.0, 2.0, 3.0], [0.5, -1.0, 0.0], [0.0, 0.6, 0.8]).unwrap();
        let v = [3.0, -1.0, 2.0, 0.5, -0.7, 1.1];
        let w = apply(Kind::Tens3, &p, &v);
        assert!(close(w[0] + w[1] + w[2], v[0] + v[1] + v[2]));
        let frob =
            |x: &[f64]| x[0] * x[0] + x[1] * x[1] + x[2] * x[2] + 2.0 * (x[3] * x[3] + x[4] * x[4] + x[5] * x[5]);
        assert!(close(frob(&w), frob(&v)));
        // e_z row is the axis, e_θ = e_z × e_r.
        assert!(close(p[(1, 1)], 0.6) && close(p[(1, 2)], 0.8));
        let t = p.row(1).cross(&p.row(0));
        for k in 0..3 {
            assert!(close(p[(2, k)], t[k]));
        }
    }
}
