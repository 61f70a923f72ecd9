//! The fields of an HM state (DEPL, SIEF_ELGA, VARI_ELGA) and the initial state of ETAT_INIT.

use crate::catalog::args::Args;
use crate::concepts::result::Field;
use crate::diag::Result;
use crate::hm::element::Variant;
use crate::hm::law::PointState;
use crate::stages::core::hm::HmProblem;
use std::collections::BTreeMap;

/// The components of SIEF_ELGA on an HM element (Code_Aster's ECONTPG: σ', σ_p, M, w).
pub fn sief_components(dim: usize) -> Vec<String> {
    let mut v: Vec<String> =
        ["SIXX", "SIYY", "SIZZ", "SIXY", "SIXZ", "SIYZ", "SIPXX", "SIPYY", "SIPZZ", "SIPXY", "SIPXZ", "SIPYZ", "M11"]
            .iter()
            .map(|s| s.to_string())
            .collect();
    v.extend(["FH11X", "FH11Y", "FH11Z"][..dim].iter().map(|s| s.to_string()));
    v
}

/// The internal variables of KIT_HM (ELAS, LIQU_SATU, HYDR_UTIL): V1 the skeleton's (none for ELAS),
/// V2 = ρ − ρ₀ (RHOLIQ), V3 = φ − φ₀ (POROSITE).
pub const VARI_COMPONENTS: [&str; 3] = ["V1", "V2", "V3"];

/// DEPL, SIEF_ELGA and VARI_ELGA of a state.
pub fn step_fields(p: &HmProblem, u: &[f64], states: &[Vec<PointState>]) -> BTreeMap<String, Field> {
    let num = &p.numbering;
    let nc = num.ncomp;
    let mut values = vec![f64::NAN; p.mesh.nnodes() * nc];
    for (d, v) in u.iter().enumerate() {
        let (n, k) = num.node_comp(d);
        values[n * nc + k] = *v;
    }
    let components = num.components.iter().map(|s| s.to_string()).collect();
    let dim = p.kin.dim();
    let sief_c = sief_components(dim);
    let mut sief: Vec<Option<Vec<f64>>> = vec![None; p.mesh.cells.len()];
    let mut vari: Vec<Option<Vec<f64>>> = vec![None; p.mesh.cells.len()];
    for ((c, cell), st) in p.elements().zip(states) {
        let ngauss =
            if p.variant == Variant::Selective { st.len() - p.mesh.cell_types[c].nvertices() } else { st.len() };
        let mut s = Vec::with_capacity(st.len() * sief_c.len());
        let mut v = Vec::with_capacity(st.len() * 3);
        for (k, ps) in st.iter().enumerate() {
            // The vertex points of an S element hold the effective stress of Gauss point k (Code_Aster copies it).
            let sig = if k >= ngauss { st[k - ngauss].sig } else { ps.sig };
            s.extend_from_slice(&sig);
            s.extend_from_slice(&ps.sigp);
            s.push(ps.m);
            s.extend_from_slice(&ps.w[..dim]);
            v.extend([0.0, ps.rho - cell.mat.rho_l, ps.phi - cell.mat.phi0]);
        }
        sief[c] = Some(s);
        vari[c] = Some(v);
    }
    let mut f = BTreeMap::new();
    f.insert("DEPL".to_string(), Field::Node { components, values });
    f.insert("SIEF_ELGA".to_string(), Field::Elga { components: sief_c, cells: sief });
    f.insert(
        "VARI_ELGA".to_string(),
        Field::Elga { components: VARI_COMPONENTS.iter().map(|s| s.to_string()).collect(), cells: vari },
    );
    f
}

/// The initial unknowns and point states: ETAT_INIT's DEPL (the components the model carries; the
/// others are passed over, as Code_Aster does), SIGM (σ', σ_p, M, w at the points; a component the
/// field lacks is zero) and VARI (ρ − ρ₀, φ − φ₀); zero and the material's initial state otherwise.
pub fn initial_state(a: &Args, p: &HmProblem) -> Result<(Vec<f64>, Vec<Vec<PointState>>)> {
    let num = &p.numbering;
    let mut u = vec![0.0; num.ndofs()];
    let init = a.fact("ETAT_INIT");
    if let Some(e) = init {
        e.refuse(&["EVOL_NOLI", "NUME_ORDRE", "INST", "STRX", "COHE", "NUME_DIDI", "INST_ETAT_INIT"])?;
        for k in ["CRITERE", "PRECISION"] {
            if e.declares(k) {
                e.has(k);
            }
        }
        if let Some(c) = e.concept("DEPL") {
            let fd = c.field().map_err(|er| e.err("DEPL", er.msg))?;
            let Field::Node { components, values } = &fd.field else {
                return Err(e.err("DEPL", format!("{} is not a nodal field (CHAM_NO)", c.label())));
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
    if let Some(c) = e.concept("SIGM") {
        let fd = c.field().map_err(|er| e.err("SIGM", er.msg))?;
        let sief = sief_components(dim);
        for ((cell_id, _), st) in p.elements().zip(states.iter_mut()) {
            let Some(vals) = cell_values(&fd.field, cell_id, st.len()).map_err(|m| e.err("SIGM", m))? else {
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
            }
        }
    }
    if let Some(c) = e.concept("VARI") {
        let fd = c.field().map_err(|er| e.err("VARI", er.msg))?;
        for ((cell_id, cell), st) in p.elements().zip(states.iter_mut()) {
            let Some(vals) = cell_values(&fd.field, cell_id, st.len()).map_err(|m| e.err("VARI", m))? else {
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
