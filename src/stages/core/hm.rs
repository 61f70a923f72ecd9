//! The checked saturated-HM problem of a model and a material field: the kinematics and integration of
//! the modelisation, the Biot material of every cell (ELAS, THM_INIT, THM_DIFFU, THM_LIQU with
//! COMP_THM='LIQU_SATU'), the integration points of every cell, and the numbering (`DX DY [DZ]` on every
//! node, `PRE1` on the vertices of the HM cells).

use super::problem::{coords_of, mat_param};
use crate::concepts::model::{Material, MaterialField, Modelling, Role};
use crate::concepts::{ConceptData, ConceptRef};
use crate::diag::{Error, Result};
use crate::fem::dofs::DofNumbering;
use crate::hm::element::Column;
pub use crate::hm::physics::{HmCell, HmProblem, HEAVISIDE};
use crate::hm::thermal::{Coef, ThermalMat};
use crate::hm::{Biot, CellPoints, Kinematics, Variant};
use crate::mesh::Mesh;
use crate::xfem::model::XfemModel;
use std::rc::Rc;

/// The kinematics and the integration of an HM modelisation; None for the others.
pub fn hm_kind(m: Modelling) -> Option<(Kinematics, Variant)> {
    use Modelling::*;
    Some(match m {
        DPlanHm => (Kinematics::DPlan, Variant::Full),
        DPlanHmd => (Kinematics::DPlan, Variant::Lumped),
        DPlanHms => (Kinematics::DPlan, Variant::Selective),
        DPlanHmSi => (Kinematics::DPlan, Variant::Reduced),
        AxisHm => (Kinematics::Axis, Variant::Full),
        AxisHmd => (Kinematics::Axis, Variant::Lumped),
        AxisHms => (Kinematics::Axis, Variant::Selective),
        ThreeDHm => (Kinematics::ThreeD, Variant::Full),
        ThreeDHmd => (Kinematics::ThreeD, Variant::Lumped),
        ThreeDHms => (Kinematics::ThreeD, Variant::Selective),
        ThreeDHmSi => (Kinematics::ThreeD, Variant::Reduced),
        DPlanThm => (Kinematics::DPlan, Variant::Full),
        DPlanThmd => (Kinematics::DPlan, Variant::Lumped),
        DPlanThms => (Kinematics::DPlan, Variant::Selective),
        AxisThm => (Kinematics::Axis, Variant::Full),
        AxisThmd => (Kinematics::Axis, Variant::Lumped),
        AxisThms => (Kinematics::Axis, Variant::Selective),
        ThreeDThm => (Kinematics::ThreeD, Variant::Full),
        ThreeDThmd => (Kinematics::ThreeD, Variant::Lumped),
        ThreeDThms => (Kinematics::ThreeD, Variant::Selective),
        _ => return None,
    })
}

/// What a parameter of the material is called in messages, and its value.
fn required(m: &Material, beh: &str, param: &str, cell: &str) -> Result<f64> {
    mat_param(m, beh, param, cell)?.ok_or_else(|| {
        Error::runtime(format!(
            "cell {cell}: the material gives no {beh}/{param}, which a saturated HM model (KIT_HM, LIQU_SATU) needs"
        ))
    })
}

/// The Biot material of a cell's DEFI_MATERIAU; missing or unsupported data stop with the parameter named.
pub fn biot_of(m: &Material, cell: &str) -> Result<(Biot, Option<ConceptRef>)> {
    match m.options.get("COMP_THM").map(String::as_str) {
        Some("LIQU_SATU") => {}
        Some(other) => {
            return Err(Error::unsupported(format!(
                "cell {cell}: COMP_THM='{other}' is not supported yet (LIQU_SATU is)"
            )))
        }
        None => {
            return Err(Error::runtime(format!(
            "cell {cell}: the material has no COMP_THM; a saturated HM model needs COMP_THM='LIQU_SATU' and THM_INIT, \
                 THM_DIFFU, THM_LIQU"
        )))
        }
    }
    for beh in ["ELAS", "THM_INIT", "THM_DIFFU", "THM_LIQU"] {
        if !m.behaviours.contains_key(beh) {
            return Err(Error::runtime(format!(
                "cell {cell}: the material has no {beh}, which a saturated HM model (KIT_HM, LIQU_SATU) needs"
            )));
        }
    }
    for (beh, params) in [
        (
            "THM_DIFFU",
            &[
                "BIOT_L", "BIOT_N", "BIOT_T", "PERMIN_L", "PERMIN_N", "PERMIN_T", "PERMIN_X", "PERMIN_Y", "PERMIN_Z",
                "EMMAG", "PERM_END",
            ][..],
        ),
        ("ELAS", &["E_L", "E_N"][..]),
    ] {
        for p in params {
            if m.behaviours.get(beh).is_some_and(|b| b.contains_key(*p)) {
                return Err(Error::unsupported(format!(
                    "cell {cell}: {beh}/{p} is not supported yet (isotropic BIOT_COEF and PERM_IN are)"
                )));
            }
        }
    }
    let pesa = |k: &str| mat_param(m, "THM_DIFFU", k, cell).map(|v| v.unwrap_or(0.0));
    let biot = Biot {
        e: required(m, "ELAS", "E", cell)?,
        nu: required(m, "ELAS", "NU", cell)?,
        biot: required(m, "THM_DIFFU", "BIOT_COEF", cell)?,
        phi0: required(m, "THM_INIT", "PORO", cell)?,
        rho_l: required(m, "THM_LIQU", "RHO", cell)?,
        inv_kw: required(m, "THM_LIQU", "UN_SUR_K", cell)?,
        // A viscosity of the temperature (THM) at THM_INIT TEMP here; the THM law evaluates it at each point.
        visc: match required(m, "THM_LIQU", "VISC", cell) {
            Ok(v) => v,
            Err(e) => {
                let t0 = mat_param(m, "THM_INIT", "TEMP", cell)?.unwrap_or(0.0);
                coef(m, "THM_LIQU", "VISC", cell, None).ok().and_then(|c| c.at(t0).ok()).ok_or(e)?
            }
        },
        perm: perm_in(m, cell)?,
        gravity: [pesa("PESA_X")?, pesa("PESA_Y")?, pesa("PESA_Z")?],
        rho_h: required(m, "THM_DIFFU", "RHO", cell)?,
    };
    biot.check().map_err(|e| Error::runtime(format!("cell {cell}: {e}")))?;
    let pesa_mult = match m.behaviours.get("THM_DIFFU").and_then(|b| b.get("PESA_MULT")) {
        Some(crate::concepts::model::MatValue::Func(f)) => Some(f.clone()),
        Some(_) => return Err(Error::runtime(format!("cell {cell}: THM_DIFFU/PESA_MULT must be a function of INST"))),
        None => None,
    };
    Ok((biot, pesa_mult))
}

/// THM_DIFFU PERM_IN: a constant, or a function of PORO that does not vary.
fn perm_in(m: &Material, cell: &str) -> Result<f64> {
    use crate::concepts::model::MatValue;
    match m.behaviours.get("THM_DIFFU").and_then(|b| b.get("PERM_IN")) {
        None => Err(Error::runtime(format!(
            "cell {cell}: the material gives no THM_DIFFU/PERM_IN, which a saturated HM model needs"
        ))),
        Some(MatValue::Func(f)) => {
            let label = f.label();
            match &*f.data() {
                ConceptData::Function(g) if g.nom_para == "TOUTPARA" => g.eval(0.0),
                ConceptData::Function(g) if g.nom_para == "PORO" && g.y.windows(2).all(|w| w[0] == w[1]) => Ok(g.y[0]),
                _ => Err(Error::unsupported(format!(
                    "cell {cell}: THM_DIFFU/PERM_IN ({label}) varies; a permeability depending on the porosity \
                     is not supported yet (a constant is)"
                ))),
            }
        }
        Some(_) => Ok(mat_param(m, "THM_DIFFU", "PERM_IN", cell)?.unwrap_or(0.0)),
    }
}

/// A thermal coefficient of a THM material: a constant, or a function of TEMP (the absolute temperature);
/// `default` where the parameter may be absent.
fn coef(m: &Material, beh: &str, param: &str, cell: &str, default: Option<f64>) -> Result<Coef> {
    use crate::concepts::model::MatValue;
    let Some(v) = m.behaviours.get(beh).and_then(|b| b.get(param)) else {
        return default.map(Coef::Const).ok_or_else(|| {
            Error::runtime(format!(
                "cell {cell}: the material gives no {beh}/{param}, which a saturated THM model (KIT_THM, LIQU_SATU) \
                 needs"
            ))
        });
    };
    let MatValue::Func(f) = v else { return Ok(Coef::Const(mat_param(m, beh, param, cell)?.unwrap_or(0.0))) };
    let para: Vec<String> = match &*f.data() {
        ConceptData::Function(g) => vec![g.nom_para.clone()],
        ConceptData::Formula(g) => g.nom_para.clone(),
        ConceptData::Nappe(g) => vec![g.nom_para.clone(), g.nom_para_fonc.clone()],
        _ => Vec::new(),
    };
    if para.iter().all(|p| p == "TOUTPARA") || para.is_empty() {
        return Ok(Coef::Const(mat_param(m, beh, param, cell)?.unwrap_or(0.0)));
    }
    if let Some(p) = para.iter().find(|p| *p != "TEMP") {
        return Err(Error::unsupported(format!(
            "cell {cell}: {beh}/{param} ({}) is a function of {p}; THM parameters of the temperature (TEMP) or \
             constant are supported",
            f.label()
        )));
    }
    let (f, name) = (f.clone(), format!("{beh}/{param}"));
    Ok(Coef::OfTemp(Rc::new(move |t: f64| {
        super::eval::eval_named(&f, &|_: &str| Ok(t)).map_err(|e| format!("{name} at TEMP = {t}: {}", e.msg))
    })))
}

/// The thermal parameters of a THM material (ELAS ALPHA, THM_INIT TEMP, THM_LIQU ALPHA CP VISC
/// D_VISC_TEMP, THM_DIFFU CP LAMB_T D_LB_T LAMB_CT); what is not supported yet stops by name.
pub fn thermal_of(m: &Material, cell: &str) -> Result<ThermalMat> {
    for (beh, params) in [
        (
            "THM_DIFFU",
            &[
                "LAMB_TL", "LAMB_TN", "LAMB_TT", "LAMB_C_L", "LAMB_C_N", "LAMB_C_T", "LAMB_S", "LAMB_PHI", "D_LB_S",
                "D_LB_PHI", "D_LB_TL", "D_LB_TN", "D_LB_TT", "SOURCE",
            ][..],
        ),
        ("ELAS", &["ALPHA_L", "ALPHA_N"][..]),
    ] {
        for p in params {
            if m.behaviours.get(beh).is_some_and(|b| b.contains_key(*p)) {
                return Err(Error::unsupported(format!(
                    "cell {cell}: {beh}/{p} is not supported yet in THM (isotropic LAMB_T, LAMB_CT and ALPHA are)"
                )));
            }
        }
    }
    let has = |beh: &str, p: &str| m.behaviours.get(beh).is_some_and(|b| b.contains_key(p));
    if !has("THM_DIFFU", "LAMB_T") && !has("THM_DIFFU", "LAMB_CT") {
        return Err(Error::runtime(format!(
            "cell {cell}: the material gives no THM_DIFFU/LAMB_T (nor LAMB_CT): a THM model needs a thermal conductivity"
        )));
    }
    let th = ThermalMat {
        t0: mat_param(m, "THM_INIT", "TEMP", cell)?.unwrap_or(0.0),
        alpha_s: coef(m, "ELAS", "ALPHA", cell, Some(0.0))?,
        alpha_l: coef(m, "THM_LIQU", "ALPHA", cell, None)?,
        cp_l: coef(m, "THM_LIQU", "CP", cell, None)?,
        cp_s: coef(m, "THM_DIFFU", "CP", cell, None)?,
        visc: coef(m, "THM_LIQU", "VISC", cell, None)?,
        dvisc: coef(m, "THM_LIQU", "D_VISC_TEMP", cell, Some(0.0))?,
        lamb_t: coef(m, "THM_DIFFU", "LAMB_T", cell, Some(0.0))?,
        dlamb_t: coef(m, "THM_DIFFU", "D_LB_T", cell, Some(0.0))?,
        lamb_ct: coef(m, "THM_DIFFU", "LAMB_CT", cell, Some(0.0))?,
    };
    if th.t0 <= 0.0 {
        return Err(Error::runtime(format!(
            "cell {cell}: THM_INIT/TEMP = {} K: the reference temperature of a THM model must be positive (kelvins)",
            th.t0
        )));
    }
    Ok(th)
}

/// The HM problem of a model whose cells all carry one HM modelisation.
pub fn hm_problem(model: &ConceptRef, chmat: &ConceptRef) -> Result<HmProblem> {
    let m = model.model()?;
    let mesh = m.current_mesh();
    let mut modelling = None;
    let (mut bulk, mut skin) = (Vec::new(), Vec::new());
    for (c, e) in m.elements.iter().enumerate() {
        let Some(e) = e else { continue };
        if modelling.is_some_and(|x| x != e.modelisation) {
            return Err(Error::unsupported(format!(
                "models mixing several modelisations are not supported yet ({} and {})",
                modelling.unwrap(),
                e.modelisation
            )));
        }
        modelling = Some(e.modelisation);
        match e.role {
            Role::Bulk => bulk.push(c),
            Role::Skin => skin.push(c),
        }
    }
    let modelling = modelling.ok_or_else(|| Error::runtime(format!("model {} has no element", model.label())))?;
    let (kin, variant) = hm_kind(modelling)
        .ok_or_else(|| Error::runtime(format!("MODELISATION='{modelling}' is not a saturated HM modelisation")))?;
    let data = chmat.data();
    let ConceptData::MaterialField(MaterialField { cells: mats, .. }) = &*data else {
        return Err(Error::runtime(format!("{} holds no material field", chmat.label())));
    };
    let dim = kin.dim();
    let pre1 = dim;
    let thm = modelling.is_thm();
    let xm = m.xfem.clone();
    if thm && xm.is_some() {
        return Err(Error::unsupported(format!("X-FEM {modelling} elements are not supported yet")));
    }
    if xm.is_some() && variant != Variant::Full {
        return Err(Error::unsupported(format!(
            "X-FEM {modelling} elements are not supported yet (D_PLAN_HM and 3D_HM are)"
        )));
    }
    let nsets = xm.as_ref().map_or(0, |x| x.node_sets.iter().map(Vec::len).max().unwrap_or(0));
    if nsets > HEAVISIDE.len() {
        return Err(Error::unsupported(format!("nodes with {nsets} Heaviside sets are not supported yet (4 are)")));
    }
    // DX DY [DZ] on every node of the model's cells, PRE1 on the vertices; on an X-FEM model, per
    // enrichment set of a node, its Heaviside displacement and (on a vertex) pressure.
    let per_set = dim + 1;
    let mut mask = vec![0u32; mesh.nnodes()];
    let mut vertex = vec![false; mesh.nnodes()];
    for &c in bulk.iter().chain(&skin) {
        let t = mesh.cell_types[c];
        for (k, &n) in mesh.cells[c].iter().enumerate() {
            mask[n] |= (1 << dim) - 1;
            if k < t.nvertices() {
                mask[n] |= 1 << pre1;
                if thm {
                    mask[n] |= 1 << (pre1 + 1);
                }
                vertex[n] = true;
            }
        }
    }
    if let Some(x) = &xm {
        for n in 0..mesh.nnodes() {
            for j in 0..x.node_sets[n].len() {
                let base = per_set * (j + 1);
                mask[n] |= ((1 << dim) - 1) << base;
                if vertex[n] {
                    mask[n] |= 1 << (base + dim);
                }
            }
        }
    }
    let mut names = crate::fem::dofs::COMPONENTS[..dim].to_vec();
    names.push("PRE1");
    if thm {
        names.push("TEMP");
    }
    for set in HEAVISIDE.iter().take(nsets) {
        names.extend(&set[..dim]);
        names.push(set[3]);
    }
    let numbering = DofNumbering::with_components(names, mask);
    let mut cells: Vec<Option<HmCell>> = (0..mesh.cells.len()).map(|_| None).collect();
    type Cached = (Biot, Option<ConceptRef>, Option<ThermalMat>);
    let mut cache: Vec<(*const crate::concepts::Concept, Cached)> = Vec::new();
    // PESA_MULT, a function of INST.
    let multiplier = |f: ConceptRef| -> crate::hm::physics::Multiplier {
        Rc::new(move |t: f64| super::eval::eval_at(&f, &[0.0; 3], t))
    };
    for &c in &bulk {
        let name = &mesh.cell_names[c];
        let Some(mc) = &mats[c] else {
            return Err(Error::runtime(format!("cell {name} of the model has no material (AFFE_MATERIAU)")));
        };
        let key = Rc::as_ptr(mc);
        let (mat, pesa_mult, thermal) = match cache.iter().find(|(k, _)| *k == key) {
            Some((_, v)) => v.clone(),
            None => {
                let md = mc.data();
                let ConceptData::Material(mat) = &*md else { unreachable!("AFFE_MATERIAU holds materials") };
                let (b, pm) = biot_of(mat, name)?;
                let th = if thm { Some(thermal_of(mat, name)?) } else { None };
                let v = (b, pm, th);
                cache.push((key, v.clone()));
                v
            }
        };
        let points = match &xm {
            Some(x) if x.cells.contains_key(&c) => enriched_points(&mesh, x, kin, c, &vertex),
            _ => CellPoints::new(kin, variant, mesh.cell_types[c], &coords_of(&mesh, c)).map(|p| {
                if thm {
                    p.with_temperature()
                } else {
                    p
                }
            }),
        }
        .map_err(|e| Error::runtime(format!("cell {name}: {e}")))?;
        let dofs = numbering.cell_dofs(&mesh.cells[c]).expect("the cell's nodes are numbered");
        if dofs.len() != points.ndof {
            return Err(Error::runtime(format!(
                "cell {name}: {} unknowns on its nodes, {} in its element (a node enriched outside the X-FEM cells?)",
                dofs.len(),
                points.ndof
            )));
        }
        cells[c] = Some(HmCell { points, mat, pesa_mult: pesa_mult.map(multiplier), dofs, thermal });
    }
    Ok(HmProblem {
        mesh,
        modelling: modelling.to_string(),
        kin,
        variant,
        bulk,
        skin,
        cells,
        numbering,
        pre1,
        temp: thm.then_some(pre1 + 1),
        xfem: xm,
        theta: 1.0,
        pressure_row_scale: 0.0,
    })
}

/// The element of an X-FEM cell: its sub-cells' points (`XINT`), the functions of its nodes and their
/// Heaviside copies in the numbering's order (node by node: DX DY [DZ], PRE1 on a vertex, then per set
/// the same), the factors ψ of each point's sub-domain.
fn enriched_points(
    mesh: &Mesh,
    xm: &XfemModel,
    kin: Kinematics,
    c: usize,
    vertex: &[bool],
) -> std::result::Result<CellPoints, String> {
    let t = mesh.cell_types[c];
    let nodes = &mesh.cells[c];
    let coords = coords_of(mesh, c);
    let dim = kin.dim();
    let (mut ucols, mut pcols) = (Vec::new(), Vec::new());
    let mut next = 0;
    for (a, &n) in nodes.iter().enumerate() {
        let v = vertex[n];
        if v != (a < t.nvertices()) {
            return Err(format!("node {} is a vertex of one cell and a middle node of another", mesh.node_names[n]));
        }
        for set in std::iter::once(None).chain((0..xm.node_sets[n].len()).map(Some)) {
            ucols.push(Column { node: a, set, first: next });
            next += dim;
            if v {
                pcols.push(Column { node: a, set, first: next });
                next += 1;
            }
        }
    }
    let points: Vec<([f64; 3], f64, i32)> =
        crate::xfem::discrete::bulk_points(t, &coords, xm, c)?.into_iter().map(|p| (p.xi, p.w, p.region)).collect();
    let factor = |a: usize, set: Option<usize>, region: i32| set.map_or(1.0, |j| xm.psi(nodes[a], j, region));
    CellPoints::enriched(kin, t, &coords, &points, &ucols, &pcols, next, &factor)
}

/// The integration points of the ELGA fields of an element (modelisation `m` on a cell of type `t`), in
/// the order of the fields' values, with Code_Aster's name of their family: an HM element's (see
/// [`crate::hm::element::point_family`]), else the RIGI family of the mechanical element.
pub fn elga_family(
    m: Modelling,
    t: crate::mesh::CellType,
) -> std::result::Result<(String, crate::fem::quadrature::QuadratureRule), String> {
    match hm_kind(m) {
        Some((_, variant)) => crate::hm::element::point_family(variant, t),
        None => {
            let rule = match m.mechanics() {
                Some(md) => crate::fem::elasticity::rigi_rule_of(md, t),
                None => crate::fem::elasticity::rigi_rule(t),
            };
            Ok((rule.name.clone(), rule))
        }
    }
}

/// The number of integration points of a cell's element (the points of its ELGA fields): the HM
/// variant's family, or the RIGI family of a mechanical element.
pub fn elga_points(m: Modelling, t: crate::mesh::CellType) -> std::result::Result<usize, String> {
    match hm_kind(m) {
        Some((_, variant)) => crate::hm::element::point_count(variant, t),
        None => elga_family(m, t).map(|(_, r)| r.len()),
    }
}
