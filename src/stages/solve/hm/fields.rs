//! The initial state of ETAT_INIT of an HM STAT_NON_LINE.

use crate::concepts::result::Field;
use crate::diag::Result;
use crate::hm::law::PointState;
use crate::hm::physics::sief_components;
use crate::stages::core::hm::HmProblem;
use crate::stages::core::settings::Settings;

/// The initial unknowns and point states: ETAT_INIT's DEPL (the components the model carries; the
/// others are passed over, as Code_Aster does), SIGM (σ', σ_p, M, w at the points; a component the
/// field lacks is zero) and VARI (ρ − ρ₀, φ − φ₀); zero and the material's initial state otherwise.
pub fn initial_state(cfg: &Settings, p: &HmProblem) -> Result<(Vec<f64>, Vec<Vec<PointState>>)> {
    let num = &p.numbering;
    let mut u = vec![0.0; num.ndofs()];
    let init = cfg.initial.as_ref();
    if let Some(e) = init {
        if let Some(c) = &e.depl {
            let fd = c.field().map_err(|er| cfg.err("ETAT_INIT/DEPL", er.msg))?;
            let Field::Node { components, values } =
                fd.reals(&c.label()).map_err(|er| cfg.err("ETAT_INIT/DEPL", er.msg))?
            else {
                return Err(cfg.err("ETAT_INIT/DEPL", format!("{} is not a nodal field (CHAM_NO)", c.label())));
            };
            let ncf = components.len();
            for (d, ud) in u.iter_mut().enumerate() {
                let (n, k) = num.node_comp(d);
                if let Some(j) = components.iter().position(|x| x == num.components[k]) {
                    let v = values.get(n * ncf + j).copied().unwrap_or(f64::NAN);
                    if v.is_finite() {
                        *ud = v;
                    }
                }
            }
        }
    }
    let mut states: Vec<Vec<PointState>> = p
        .elements()
        .map(|(_, cell)| {
            let ue: Vec<f64> = cell.dofs.iter().map(|&d| u[d]).collect();
            cell.points.initial_states(&cell.mat, &ue)
        })
        .collect();
    let Some(e) = init else { return Ok((u, states)) };
    let dim = p.kin.dim();
    if let Some(c) = &e.sigm {
        let fd = c.field().map_err(|er| cfg.err("ETAT_INIT/SIGM", er.msg))?;
        let field = fd.reals(&c.label()).map_err(|er| cfg.err("ETAT_INIT/SIGM", er.msg))?;
        let thm = p.temp.is_some();
        let sief = sief_components(dim, thm);
        for ((cell_id, _), st) in p.elements().zip(states.iter_mut()) {
            let Some(vals) = cell_values(field, cell_id, st.len()).map_err(|m| cfg.err("ETAT_INIT/SIGM", m))? else {
                continue;
            };
            let get = point_reader(fd.field.components(), &vals);
            for (k, ps) in st.iter_mut().enumerate() {
                for i in 0..6 {
                    ps.sig[i] = get(k, &sief[i]);
                    ps.sigp[i] = get(k, &sief[6 + i]);
                }
                ps.m = get(k, "M11");
                for i in 0..dim {
                    ps.w[i] = get(k, &sief[13 + i]);
                }
                if thm {
                    ps.h = get(k, "ENT11");
                    ps.qp = get(k, "QPRIM");
                    for i in 0..dim {
                        ps.qt[i] = get(k, &sief[15 + dim + i]);
                    }
                }
            }
        }
    }
    if let Some(c) = &e.vari {
        let fd = c.field().map_err(|er| cfg.err("ETAT_INIT/VARI", er.msg))?;
        let field = fd.reals(&c.label()).map_err(|er| cfg.err("ETAT_INIT/VARI", er.msg))?;
        for ((cell_id, cell), st) in p.elements().zip(states.iter_mut()) {
            let Some(vals) = cell_values(field, cell_id, st.len()).map_err(|m| cfg.err("ETAT_INIT/VARI", m))? else {
                continue;
            };
            let get = point_reader(fd.field.components(), &vals);
            for (k, ps) in st.iter_mut().enumerate() {
                ps.rho = cell.mat.rho_l + get(k, "V2");
                ps.phi = cell.mat.phi0 + get(k, "V3");
            }
        }
    }
    Ok((u, states))
}

/// The values of a field of points on a cell with `npts` points: an ELGA field with exactly that many
/// points, or a value per cell (ELEM, repeated at every point).
fn cell_values(f: &Field, c: usize, npts: usize) -> std::result::Result<Option<Vec<f64>>, String> {
    let ncmp = f.components().len();
    match f {
        Field::Elga { cells, .. } => match cells.get(c).and_then(|v| v.as_ref()) {
            None => Ok(None),
            Some(v) if v.len() == npts * ncmp => Ok(Some(v.clone())),
            Some(v) => Err(format!(
                "the field has {} points on a cell where the model integrates on {npts}",
                v.len() / ncmp.max(1)
            )),
        },
        Field::Elem { cells, .. } => Ok(cells.get(c).and_then(|v| v.as_ref()).map(|v| v.repeat(npts))),
        _ => Err("a field of points (ELGA) is needed".to_string()),
    }
}

/// The value of a named component at a point of a cell's ELGA values (0 where absent or not finite).
fn point_reader<'a>(comps: &'a [String], vals: &'a [f64]) -> impl Fn(usize, &str) -> f64 + 'a {
    move |pt, name| {
        comps
            .iter()
            .position(|x| x == name)
            .map(|j| vals[pt * comps.len() + j])
            .filter(|v| v.is_finite())
            .unwrap_or(0.0)
    }
}
