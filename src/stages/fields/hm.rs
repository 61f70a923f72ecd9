//! CALC_CHAMP on saturated HM results: the fields Code_Aster derives from SIEF_ELGA (σ', σ_p, M, w),
//! VARI_ELGA and the displacements, at the integration points of the HM elements and extrapolated to
//! the nodes as `inmat4`/`inmat6` do (a least-squares fit of the vertex element's functions through the
//! point values, middle nodes the mean of their edge's ends; at the vertex points of `*_HMD` elements
//! the point value itself). On `*_HMS` elements SIGM_ELNO and EPSI_ELNO fit through every point of the
//! RIGI family (Gauss and vertex points, as `te0004` does), while SIEF_ELNO and VARI_ELNO take their
//! mechanical components from the Gauss points and their hydraulic ones from the vertex points (`posthm`).

use crate::catalog::args::Args;
use crate::concepts::result::{Field, Step};
use crate::concepts::ConceptRef;
use crate::diag::Result;
use crate::fem::elasticity::gauss_to_node_matrix;
use crate::fem::quadrature::{QuadratureRule, RefDomain};
use crate::hm::element::{CellPoints, Variant};
use crate::hm::law::PointState;
use crate::hm::physics::sief_components;
use crate::stages::core::hm::{hm_problem, HmProblem};

/// The options CALC_CHAMP computes on HM results.
pub const OPTIONS: &[&str] = &[
    "SIGM_ELGA",
    "SIGM_ELNO",
    "SIGM_NOEU",
    "SIEF_ELNO",
    "SIEF_NOEU",
    "SIEQ_ELGA",
    "SIEQ_ELNO",
    "SIEQ_NOEU",
    "EPSI_ELGA",
    "EPSI_ELNO",
    "EPSI_NOEU",
    "EPEQ_ELGA",
    "EPEQ_ELNO",
    "EPEQ_NOEU",
    "VARI_ELNO",
    "VARI_NOEU",
    "FORC_NODA",
];

const EPEQ_COMPONENTS: [&str; 5] = ["INVA_2", "PRIN_1", "PRIN_2", "PRIN_3", "INVA_2SG"];

/// The extrapolation matrix (`m[node][point]`) of the points `pts` of a cell.
fn gano(cp: &CellPoints, pts: &[usize]) -> Vec<Vec<f64>> {
    let rule = QuadratureRule {
        name: cp.family.clone(),
        domain: RefDomain::of(cp.cell),
        points: pts.iter().map(|&k| cp.points[k].xi).collect(),
        weights: vec![1.0; pts.len()],
        degree: 0,
    };
    gauss_to_node_matrix(cp.cell, &rule)
}

/// How the point values of a cell go to its nodes.
#[derive(Clone, Copy)]
enum Extrapolation {
    /// Code_Aster's `te0004` on the RIGI family: one fit through every point of the family (on `*_HMS`
    /// elements the Gauss points and the vertex points, which hold what the element stored there).
    Rigi,
    /// `posthm` (SIEF_ELNO, VARI_ELNO): on `*_HMS` elements the components below the split from the
    /// Gauss points (the MASS family), the others from the vertex points (NOEU_S); every point elsewhere.
    Split(usize),
}

/// Extrapolate point values (`ncmp` per point) to the nodes of a cell.
fn to_nodes(cp: &CellPoints, v: &[f64], ncmp: usize, how: Extrapolation) -> Vec<f64> {
    let npts = cp.points.len();
    let nno = cp.cell.nnodes();
    let mut out = vec![0.0; nno * ncmp];
    let groups: Vec<(Vec<usize>, std::ops::Range<usize>)> = match (cp.variant, how) {
        (Variant::Selective, Extrapolation::Split(s)) => {
            let ng = npts - cp.cell.nvertices();
            vec![((0..ng).collect(), 0..s.min(ncmp)), ((ng..npts).collect(), s.min(ncmp)..ncmp)]
        }
        _ => vec![((0..npts).collect(), 0..ncmp)],
    };
    for (pts, comps) in groups {
        if comps.is_empty() {
            continue;
        }
        let m = gano(cp, &pts);
        for (node, row) in m.iter().enumerate() {
            for (w, &k) in row.iter().zip(&pts) {
                for c in comps.clone() {
                    out[node * ncmp + c] += w * v[k * ncmp + c];
                }
            }
        }
    }
    out
}

/// Principal values (ascending) of a symmetric tensor given as [xx, yy, zz, xy, xz, yz].
fn principal(s: &[f64; 6]) -> [f64; 3] {
    let m = nalgebra::Matrix3::new(s[0], s[3], s[4], s[3], s[1], s[5], s[4], s[5], s[2]);
    let mut e: [f64; 3] = m.symmetric_eigenvalues().into();
    e.sort_by(|x, y| x.total_cmp(y));
    e
}

/// EPEQ of a tensorial strain: the second invariant √(2/3 e:e) of its deviator, the principal strains,
/// the invariant signed by the trace.
fn epeq(e: &[f64; 6]) -> [f64; 5] {
    let tr = e[0] + e[1] + e[2];
    let m = tr / 3.0;
    let dev2 =
        (e[0] - m).powi(2) + (e[1] - m).powi(2) + (e[2] - m).powi(2) + 2.0 * (e[3] * e[3] + e[4] * e[4] + e[5] * e[5]);
    let inva = (2.0 / 3.0 * dev2).sqrt();
    let pr = principal(e);
    [inva, pr[0], pr[1], pr[2], if tr < 0.0 { -inva } else { inva }]
}

/// Compute `wanted` on every step of an HM result (restricted to the cells `only` accepts).
pub fn calc_champ_hm(
    a: &Args,
    wanted: &[String],
    steps: &mut [Step],
    model: &ConceptRef,
    chmat: &ConceptRef,
    only: &dyn Fn(&usize) -> bool,
    orders: &[i64],
) -> Result<Vec<i64>> {
    if let Some(o) = wanted.iter().find(|o| !OPTIONS.contains(&o.as_str())) {
        return Err(a.err("RESULTAT", format!("option {o} is not supported yet on a saturated HM result")));
    }
    let p = hm_problem(model, chmat).map_err(|e| e.at(a.span))?;
    let ns = p.kin.mechanics().nsig();
    let sigma_names: Vec<String> = p.kin.mechanics().sigma_names().iter().map(|s| s.to_string()).collect();
    let eps_names: Vec<String> = p.kin.mechanics().epsilon_names().iter().map(|s| s.to_string()).collect();
    let mut passed_over = Vec::new();
    // The previous order's SIEF_ELGA and the time step, for FORC_NODA (Code_Aster's `fnoevo`).
    let mut previous = std::collections::BTreeMap::new();
    if wanted.iter().any(|o| o == "FORC_NODA") {
        for w in steps.windows(2) {
            if let Some(f) = w[0].fields.get("SIEF_ELGA") {
                previous.insert(w[1].nume_ordre, (f.clone(), w[1].inst - w[0].inst));
            }
        }
    }
    for step in steps.iter_mut() {
        if !orders.is_empty() && !orders.contains(&step.nume_ordre) {
            continue;
        }
        // Every order asked for: one without the point fields (an initial state stored without them) is
        // passed over, as Code_Aster does with an alarm; an order named by NUME_ORDRE must have them.
        if orders.is_empty() && !(step.fields.contains_key("SIEF_ELGA") && step.fields.contains_key("VARI_ELGA")) {
            passed_over.push(step.nume_ordre);
            continue;
        }
        let fields = step_fields(&p, step, only, ns)
            .map_err(|m| a.err("RESULTAT", format!("order {}: {m}", step.nume_ordre)))?;
        for o in wanted {
            let f = match o.as_str() {
                "FORC_NODA" => forc_noda(&p, step, previous.get(&step.nume_ordre), only)
                    .map_err(|m| a.err("FORCE", format!("order {}: {m}", step.nume_ordre)))?,
                "SIGM_ELGA" => Field::Elga { components: sigma_names.clone(), cells: fields.sigm_elga.clone() },
                "SIGM_ELNO" => Field::Elno { components: sigma_names.clone(), cells: fields.sigm_elno.clone() },
                "SIGM_NOEU" => Field::Node {
                    components: sigma_names.clone(),
                    values: crate::fem::postpro::to_nodes(&p.mesh, &fields.sigm_elno, ns),
                },
                "SIEF_ELNO" => Field::Elno { components: fields.sief_names.clone(), cells: fields.sief_elno.clone() },
                "SIEF_NOEU" => Field::Node {
                    components: fields.sief_names.clone(),
                    values: crate::fem::postpro::to_nodes(&p.mesh, &fields.sief_elno, fields.sief_names.len()),
                },
                "EPSI_ELGA" => Field::Elga { components: eps_names.clone(), cells: fields.epsi_elga.clone() },
                "EPSI_ELNO" => Field::Elno { components: eps_names.clone(), cells: fields.epsi_elno.clone() },
                "EPSI_NOEU" => Field::Node {
                    components: eps_names.clone(),
                    values: crate::fem::postpro::to_nodes(&p.mesh, &fields.epsi_elno, ns),
                },
                "VARI_ELNO" => Field::Elno { components: fields.vari_names.clone(), cells: fields.vari_elno.clone() },
                "VARI_NOEU" => Field::Node {
                    components: fields.vari_names.clone(),
                    values: crate::fem::postpro::to_nodes(&p.mesh, &fields.vari_elno, fields.vari_names.len()),
                },
                "SIEQ_ELGA" | "SIEQ_ELNO" | "SIEQ_NOEU" => {
                    let src = if o == "SIEQ_ELGA" { &fields.sigm_elga } else { &fields.sigm_elno };
                    let cells: Vec<Option<Vec<f64>>> = src
                        .iter()
                        .map(|c| {
                            c.as_ref()
                                .map(|v| v.chunks(ns).flat_map(crate::fem::postpro::equivalent_stresses).collect())
                        })
                        .collect();
                    let names: Vec<String> =
                        crate::fem::postpro::SIEQ_COMPONENTS.iter().map(|s| s.to_string()).collect();
                    let n = names.len();
                    match o.as_str() {
                        "SIEQ_ELGA" => Field::Elga { components: names, cells },
                        "SIEQ_ELNO" => Field::Elno { components: names, cells },
                        _ => {
                            Field::Node { components: names, values: crate::fem::postpro::to_nodes(&p.mesh, &cells, n) }
                        }
                    }
                }
                _ => {
                    // EPEQ_*.
                    let src = if o == "EPEQ_ELGA" { &fields.epsi_elga } else { &fields.epsi_elno };
                    let cells: Vec<Option<Vec<f64>>> = src
                        .iter()
                        .map(|c| {
                            c.as_ref().map(|v| {
                                v.chunks(ns)
                                    .flat_map(|e| {
                                        let mut t = [0.0; 6];
                                        t[..ns].copy_from_slice(e);
                                        epeq(&t)
                                    })
                                    .collect()
                            })
                        })
                        .collect();
                    let names: Vec<String> = EPEQ_COMPONENTS.iter().map(|s| s.to_string()).collect();
                    match o.as_str() {
                        "EPEQ_ELGA" => Field::Elga { components: names, cells },
                        "EPEQ_ELNO" => Field::Elno { components: names, cells },
                        _ => Field::Node {
                            components: names,
                            values: crate::fem::postpro::to_nodes(&p.mesh, &cells, EPEQ_COMPONENTS.len()),
                        },
                    }
                }
            };
            step.fields.insert(o.clone(), f);
        }
    }
    Ok(passed_over)
}

/// FORC_NODA of a step (`fnothm`): the nodal forces of the stored stresses and fluid mass on the
/// displacements, with the fluid's gravity at INST 0 (Code_Aster's); zero on PRE1 and TEMP.
fn forc_noda(
    p: &HmProblem,
    step: &Step,
    previous: Option<&(Field, f64)>,
    only: &dyn Fn(&usize) -> bool,
) -> std::result::Result<Field, String> {
    let Some(Field::Elga { components: names, cells: sief }) = step.fields.get("SIEF_ELGA") else {
        return Err("the result holds no SIEF_ELGA".into());
    };
    let prev_cells = match previous {
        Some((Field::Elga { components, cells }, dt)) if components == names => Some((cells, *dt)),
        _ => None,
    };
    let num = &p.numbering;
    let ncomp = num.ncomp;
    let mut values = vec![f64::NAN; p.mesh.nnodes() * ncomp];
    for d in 0..num.ndofs() {
        let (n, k) = num.node_comp(d);
        values[n * ncomp + k] = 0.0;
    }
    let nsief = names.len();
    let dim = p.kin.dim();
    let thm = p.temp.is_some();
    // The point states of stored SIEF_ELGA values (the components of `sief_components`).
    let states = |s: &[f64], mat: &crate::hm::Biot| -> Vec<PointState> {
        s.chunks(nsief)
            .map(|x| {
                let mut ps = PointState::initial(mat);
                ps.sig = std::array::from_fn(|i| x[i]);
                ps.sigp = std::array::from_fn(|i| x[6 + i]);
                ps.m = x[12];
                ps.w[..dim].copy_from_slice(&x[13..13 + dim]);
                if thm && x.len() >= 15 + 2 * dim {
                    ps.h = x[13 + dim];
                    ps.qp = x[14 + dim];
                    ps.qt[..dim].copy_from_slice(&x[15 + dim..15 + 2 * dim]);
                }
                ps
            })
            .collect()
    };
    for (c, cell) in p.elements().filter(|(c, _)| only(c)) {
        let Some(s) = &sief[c] else { continue };
        let npts = cell.points.points.len();
        if s.len() != npts * nsief || nsief != sief_components(dim, thm).len() {
            return Err(format!("cell {}: the stored fields do not match the model's points", p.mesh.cell_names[c]));
        }
        let now = states(s, &cell.mat);
        let before = prev_cells.and_then(|(cells, dt)| {
            cells[c].as_ref().filter(|v| v.len() == s.len()).map(|v| (states(v, &cell.mat), dt))
        });
        let g = p.gravity(cell, 0.0).map_err(|e| e.msg)?;
        let fe = cell.points.stored_forces(&now, before.as_ref().map(|(v, dt)| (v.as_slice(), *dt)), &g);
        for (&d, v) in cell.dofs.iter().zip(&fe) {
            let (n, k) = num.node_comp(d);
            values[n * ncomp + k] += v;
        }
    }
    Ok(Field::Node { components: num.components.iter().map(|s| s.to_string()).collect(), values })
}

/// The point and node fields of one step.
struct StepFields {
    sief_names: Vec<String>,
    vari_names: Vec<String>,
    sigm_elga: Vec<Option<Vec<f64>>>,
    sigm_elno: Vec<Option<Vec<f64>>>,
    sief_elno: Vec<Option<Vec<f64>>>,
    epsi_elga: Vec<Option<Vec<f64>>>,
    epsi_elno: Vec<Option<Vec<f64>>>,
    vari_elno: Vec<Option<Vec<f64>>>,
}

fn step_fields(
    p: &HmProblem,
    step: &Step,
    only: &dyn Fn(&usize) -> bool,
    ns: usize,
) -> std::result::Result<StepFields, String> {
    let nc = p.mesh.cells.len();
    let (
        Some(Field::Elga { components: sief_names, cells: sief }),
        Some(Field::Elga { components: vari_names, cells: vari }),
    ) = (step.fields.get("SIEF_ELGA"), step.fields.get("VARI_ELGA"))
    else {
        return Err("the result holds no SIEF_ELGA and VARI_ELGA of an HM model".into());
    };
    let Some(Field::Node { components, values: depl }) = step.fields.get("DEPL") else {
        return Err("the result holds no DEPL".into());
    };
    let nsief = sief_names.len();
    let nvari = vari_names.len();
    let mut out = StepFields {
        sief_names: sief_names.clone(),
        vari_names: vari_names.clone(),
        sigm_elga: vec![None; nc],
        sigm_elno: vec![None; nc],
        sief_elno: vec![None; nc],
        epsi_elga: vec![None; nc],
        epsi_elno: vec![None; nc],
        vari_elno: vec![None; nc],
    };
    let ncd = components.len();
    for (c, cell) in p.elements().filter(|(c, _)| only(c)) {
        let cp = &cell.points;
        let npts = cp.points.len();
        let (Some(s), Some(v)) = (&sief[c], &vari[c]) else { continue };
        if s.len() != npts * nsief || v.len() != npts * nvari {
            return Err(format!("cell {}: the stored fields do not match the model's points", p.mesh.cell_names[c]));
        }
        let sg: Vec<f64> = s.chunks(nsief).flat_map(|x| x[..ns].to_vec()).collect();
        // SIGM_ELNO is te0004's fit through every point of the RIGI family: on `*_HMS` elements the vertex
        // points take part with the effective stress they hold (a copy of a Gauss point's). SIEF_ELNO and
        // VARI_ELNO are posthm's: σ' and σ_p (the first 12 components) and the skeleton's variable (V1)
        // from the Gauss points, M, w and the fluid's variables from the vertex points.
        out.sigm_elno[c] = Some(to_nodes(cp, &sg, ns, Extrapolation::Rigi));
        out.sief_elno[c] = Some(to_nodes(cp, s, nsief, Extrapolation::Split(12)));
        out.vari_elno[c] = Some(to_nodes(cp, v, nvari, Extrapolation::Split(1)));
        out.sigm_elga[c] = Some(sg);
        // Strains of the displacements at the points (tensorial shear).
        let ue: Vec<f64> = cell
            .dofs
            .iter()
            .map(|&d| {
                let (n, k) = p.numbering.node_comp(d);
                depl[n * ncd + components.iter().position(|x| x == p.numbering.components[k]).unwrap_or(k)]
            })
            .collect();
        // thmCompEpsiElga fills the Gauss points only: the vertex points of an `*_HMS` element keep the
        // zero the elementary computation starts from, and EPSI_ELNO (te0004) fits through them too.
        let ngauss = if cp.variant == Variant::Selective { npts - cp.cell.nvertices() } else { npts };
        let mut e = Vec::with_capacity(npts * ns);
        for (i, pt) in cp.points.iter().enumerate() {
            let eps = if i < ngauss { cp.strain(pt, &ue) } else { Default::default() };
            for (k, v) in eps.iter().enumerate().take(ns) {
                e.push(if k >= 3 { 0.5 * v } else { *v });
            }
        }
        out.epsi_elno[c] = Some(to_nodes(cp, &e, ns, Extrapolation::Rigi));
        out.epsi_elga[c] = Some(e);
    }
    if out.sigm_elga.iter().all(Option::is_none) {
        return Err("no cell of the selection carries an HM element".into());
    }
    Ok(out)
}
