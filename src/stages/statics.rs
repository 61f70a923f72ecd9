//! MECA_STATIQUE (linear elastic statics) and CALC_CHAMP (stresses and
//! strains at nodes): model + material field + loads → assembled, reduced,
//! solved with the `fem` and `solve` libraries; the run log states the size
//! of the system, what was eliminated and the time of each phase.

use super::model::model_of;
use super::results::result_of;
use super::Ctx;
use crate::catalog::args::Args;
use crate::concepts::model::{Load, LoadItem, LoadValue, Material, MaterialField, Role};
use crate::concepts::result::{Field, ResultData, Step};
use crate::concepts::{ConceptData, ConceptRef};
use crate::diag::{Error, Result};
use crate::fem::assembly::{Assembler, ElementDofs, SparsityPattern};
use crate::fem::dofs::{component_index, Constraints, DofMap, DofNumbering};
use crate::fem::elasticity::{self, IsoElastic, Modelisation};
use crate::mesh::Mesh;
use crate::solve::{self, SolverOptions};
use std::collections::BTreeMap;
use std::rc::Rc;
use std::time::Instant;

/// Evaluate a load value at a point and time.
pub fn load_value(v: &LoadValue, x: &[f64; 3], inst: f64) -> Result<f64> {
    match v {
        LoadValue::Real(r) => Ok(*r),
        LoadValue::Func(c) => eval_at(c, x, inst),
    }
}

/// A function, nappe or formula of (X, Y, Z, INST) at a point and time.
pub fn eval_at(c: &ConceptRef, x: &[f64; 3], inst: f64) -> Result<f64> {
    let arg = |p: &str| -> Result<f64> {
        match p {
            "X" => Ok(x[0]),
            "Y" => Ok(x[1]),
            "Z" => Ok(x[2]),
            "INST" => Ok(inst),
            other => {
                Err(Error::runtime(format!("{}: parameter {other} is not known here (X, Y, Z or INST)", c.label())))
            }
        }
    };
    match &*c.data() {
        ConceptData::Function(f) if f.nom_para == "TOUTPARA" => f.eval(0.0),
        ConceptData::Function(f) => f.eval(arg(&f.nom_para)?),
        ConceptData::Nappe(n) => n.eval(arg(&n.nom_para)?, arg(&n.nom_para_fonc)?),
        ConceptData::Formula(f) => {
            let vals: Vec<f64> = f.nom_para.iter().map(|p| arg(p)).collect::<Result<_>>()?;
            f.eval(&vals)
        }
        _ => Err(Error::runtime(format!("{} ({}) is not a function", c.label(), c.kind()))),
    }
}

/// A material parameter as a real: a real, or a function that does not
/// depend on a variable unknown here (DEFI_CONSTANTE, NOM_PARA 'TOUTPARA';
/// a formula of no parameter). None when the parameter is not given.
pub(super) fn mat_param(m: &Material, behaviour: &str, param: &str, cell: &str) -> Result<Option<f64>> {
    let Some(v) = m.behaviours.get(behaviour).and_then(|b| b.get(param)) else {
        return Ok(None);
    };
    let depends = |on: &str, what: &str| {
        Error::unsupported(format!(
            "cell {cell}: {behaviour}/{param} is {what} of {on}; material parameters depending on {on} \
             are not supported yet (only constants: reals or DEFI_CONSTANTE)"
        ))
    };
    use crate::concepts::model::MatValue;
    match v {
        MatValue::Real(r) => Ok(Some(*r)),
        MatValue::Text(t) => {
            Err(Error::runtime(format!("cell {cell}: {behaviour}/{param} is the text '{t}', not a number")))
        }
        MatValue::Func(c) => {
            let label = c.label();
            let what = format!("the function {label}");
            let value = match &*c.data() {
                ConceptData::Function(f) if f.nom_para == "TOUTPARA" => f.eval(0.0),
                ConceptData::Function(f) => return Err(depends(&f.nom_para, &what)),
                ConceptData::Nappe(n) => return Err(depends(&n.nom_para, &what)),
                ConceptData::Formula(f) if f.nom_para.is_empty() => f.eval(&[]),
                ConceptData::Formula(f) => return Err(depends(&f.nom_para.join(", "), &what)),
                _ => {
                    return Err(Error::runtime(format!(
                        "cell {cell}: {behaviour}/{param}: {label} ({}) is not a function",
                        c.kind()
                    )))
                }
            };
            value
                .map(Some)
                .map_err(|e| Error::runtime(format!("cell {cell}: {behaviour}/{param} ({label}): {}", e.msg)))
        }
    }
}

/// The elastic behaviours we compute with, and the parameters each requires.
const ELASTIC_BEHAVIOURS: &[(&str, &[&str])] = &[
    ("ELAS", &["E", "NU"]),
    ("ELAS_FO", &["E", "NU"]),
    ("ELAS_ISTR", &["E_L", "E_N", "NU_LT", "NU_LN", "G_LN"]),
    ("ELAS_ISTR_FO", &["E_L", "E_N", "NU_LT", "NU_LN", "G_LN"]),
];

/// The elastic law of a material and its density RHO (0 when not given).
pub(super) fn elastic_of(m: &Material, cell: &str) -> Result<(IsoElastic, f64)> {
    let Some((beh, params)) = ELASTIC_BEHAVIOURS.iter().find(|(b, _)| m.behaviours.contains_key(*b)) else {
        let others: Vec<&str> = m.behaviours.keys().map(String::as_str).collect();
        return Err(Error::unsupported(format!(
            "cell {cell}: the material has no ELAS (E, NU), ELAS_FO or ELAS_ISTR(_FO); it defines {}, \
             which this command does not support yet",
            if others.is_empty() { "nothing".to_string() } else { others.join(", ") }
        )));
    };
    let mut v = Vec::with_capacity(params.len());
    for p in params.iter() {
        let x = mat_param(m, beh, p, cell)?.ok_or_else(|| {
            Error::unsupported(format!(
                "cell {cell}: {beh} without {p} is not supported yet ({} are needed)",
                params.join(", ")
            ))
        })?;
        v.push(x);
    }
    let law = match v[..] {
        [e, nu] => IsoElastic::new(e, nu),
        [e_l, e_n, nu_lt, nu_ln, g_ln] => IsoElastic::transverse_isotropic(e_l, e_n, nu_lt, nu_ln, g_ln)
            .map_err(|e| Error::runtime(format!("cell {cell}: {beh}: {e}")))?,
        _ => unreachable!("ELASTIC_BEHAVIOURS lists 2 or 5 parameters"),
    };
    let rho = mat_param(m, beh, "RHO", cell)?.unwrap_or(0.0);
    Ok((law, rho))
}

/// What a linear elastic computation is built from, checked.
pub(super) struct Problem {
    pub mesh: Rc<Mesh>,
    pub modelisation: Modelisation,
    pub bulk: Vec<usize>,
    pub materials: Vec<Option<(IsoElastic, f64)>>,
    pub numbering: DofNumbering,
}

pub(super) fn problem(model: &ConceptRef, chmat: &ConceptRef) -> Result<Problem> {
    let m = model_of(model)?;
    let mesh = m.current_mesh();
    let mut modelisation = None;
    let mut bulk = Vec::new();
    for (c, e) in m.elements.iter().enumerate() {
        let Some(e) = e else { continue };
        let Some(md) = Modelisation::from_name(&e.modelisation) else {
            return Err(Error::runtime(format!(
                "MODELISATION='{}' is not supported yet by this command (3D, D_PLAN, C_PLAN, AXIS are)",
                e.modelisation
            )));
        };
        if modelisation.is_some_and(|x| x != md) {
            return Err(Error::runtime("models mixing several modelisations are not supported yet"));
        }
        modelisation = Some(md);
        if e.role == Role::Bulk {
            bulk.push(c);
        }
    }
    let modelisation = modelisation.ok_or_else(|| Error::runtime(format!("model {} has no element", model.label())))?;
    let data = chmat.data();
    let ConceptData::MaterialField(MaterialField { cells, .. }) = &*data else {
        return Err(Error::runtime(format!("{} holds no material field", chmat.label())));
    };
    let mut materials = vec![None; mesh.cells.len()];
    let mut cache: Vec<(*const crate::concepts::Concept, (IsoElastic, f64))> = Vec::new();
    for &c in &bulk {
        let Some(mc) = &cells[c] else {
            return Err(Error::runtime(format!(
                "cell {} of the model has no material (AFFE_MATERIAU)",
                mesh.cell_names[c]
            )));
        };
        let md = mc.data();
        let ConceptData::Material(mat) = &*md else { unreachable!("AFFE_MATERIAU holds materials") };
        // One evaluation per material concept.
        let key = Rc::as_ptr(mc);
        let entry = match cache.iter().find(|(k, _)| *k == key) {
            Some((_, v)) => *v,
            None => {
                let v = elastic_of(mat, &mesh.cell_names[c])?;
                if let Err(e) = v.0.check(modelisation) {
                    return Err(Error::unsupported(format!("cell {}: {e}", mesh.cell_names[c])));
                }
                cache.push((key, v));
                v
            }
        };
        materials[c] = Some(entry);
    }
    let numbering = DofNumbering::for_cells(&mesh, modelisation.dim(), &bulk);
    Ok(Problem { mesh, modelisation, bulk, materials, numbering })
}

fn coords_of(mesh: &Mesh, cell: usize) -> Vec<[f64; 3]> {
    mesh.cells[cell].iter().map(|&n| mesh.coords[n]).collect()
}

/// The loads of EXCIT with their multiplier at `inst`.
pub(super) fn loads(a: &Args, inst: f64) -> Result<Vec<(ConceptRef, f64)>> {
    let mut out = Vec::new();
    for occ in a.facts("EXCIT") {
        if occ.given("TYPE_CHARGE") && occ.text("TYPE_CHARGE") != Some("FIXE_CSTE") {
            return Err(occ.err("TYPE_CHARGE", "not supported yet"));
        }
        let c = occ.req_concept("CHARGE")?;
        let mult = match occ.concept("FONC_MULT") {
            Some(f) => eval_at(&f, &[0.0; 3], inst).map_err(|e| e.at(occ.span_of("FONC_MULT")))?,
            None => 1.0,
        };
        out.push((c, mult));
    }
    Ok(out)
}

/// The reduced linear system of a step: constraints eliminated, loads at `inst`.
pub(super) struct System {
    pub map: DofMap,
    pub k: faer::sparse::SparseColMat<usize, f64>,
    pub rhs: Vec<f64>,
    pub t_numbering: std::time::Duration,
    pub t_assembly: std::time::Duration,
}

pub(super) fn assemble(a: &Args, p: &Problem, model: &ConceptRef, inst: f64) -> Result<System> {
    let mesh = &p.mesh;
    let md = p.modelisation;
    let dim = md.dim();
    let t0 = Instant::now();
    // Kinematic conditions and forces.
    let mut cons = Constraints::new();
    let mut forces: Vec<(Vec<usize>, Vec<f64>)> = Vec::new();
    let model_ref = model_of(model)?;
    // The dofs of a boundary cell carrying a surface load; the cell must be a skin element of the model.
    let skin_dofs = |c: usize| -> Result<Vec<usize>> {
        let on_skin = model_ref.elements[c].as_ref().map(|e| e.role) == Some(Role::Skin);
        match p.numbering.cell_dofs(&mesh.cells[c]) {
            Some(d) if on_skin => Ok(d),
            _ => Err(a.err("EXCIT", format!("cell {} is not a boundary cell of the model", mesh.cell_names[c]))),
        }
    };
    for (lc, mult) in loads(a, inst)? {
        let data = lc.data();
        let ConceptData::Load(Load { items, model: lmodel, .. }) = &*data else {
            return Err(a.err("EXCIT", format!("{} is not a mechanical load", lc.label())));
        };
        if !Rc::ptr_eq(lmodel, model) {
            return Err(a.err("EXCIT", format!("load {} is defined on another model ({})", lc.label(), lmodel.label())));
        }
        for item in items {
            match item {
                LoadItem::Dof { node, component, value } => {
                    let comp = component_index(component).filter(|&k| k < dim).ok_or_else(|| {
                        a.err(
                            "EXCIT",
                            format!("load {}: component {component} is not a dof of a {} model", lc.label(), md.name()),
                        )
                    })?;
                    let dof = p.numbering.dof(*node, comp).ok_or_else(|| {
                        a.err(
                            "EXCIT",
                            format!(
                                "load {}: node {} carries no element of the model",
                                lc.label(),
                                mesh.node_names[*node]
                            ),
                        )
                    })?;
                    cons.impose(dof, mult * load_value(value, &mesh.coords[*node], inst)?);
                }
                LoadItem::Relation { terms, value } => {
                    let mut t = Vec::new();
                    for (node, comp, coef) in terms {
                        let k = component_index(comp)
                            .filter(|&k| k < dim)
                            .ok_or_else(|| a.err("EXCIT", format!("component {comp} is not a dof of the model")))?;
                        let dof = p.numbering.dof(*node, k).ok_or_else(|| {
                            a.err("EXCIT", format!("node {} carries no element of the model", mesh.node_names[*node]))
                        })?;
                        t.push((dof, *coef));
                    }
                    cons.relation(t, mult * load_value(value, &[0.0; 3], inst)?);
                }
                LoadItem::NodalForce { node, component, value } => {
                    let k = match component.as_str() {
                        "FX" => 0,
                        "FY" => 1,
                        "FZ" => 2,
                        c => {
                            return Err(
                                a.err("EXCIT", format!("load {}: FORCE_NODALE {c} is not supported yet", lc.label()))
                            )
                        }
                    };
                    if k >= dim {
                        return Err(
                            a.err("EXCIT", format!("load {}: {component} in a {} model", lc.label(), md.name()))
                        );
                    }
                    let dof = p.numbering.dof(*node, k).ok_or_else(|| {
                        a.err("EXCIT", format!("node {} carries no element of the model", mesh.node_names[*node]))
                    })?;
                    forces.push((vec![dof], vec![mult * load_value(value, &mesh.coords[*node], inst)?]));
                }
                LoadItem::SurfaceForce { cells, components } => {
                    if dim < 3 && components.iter().any(|(n, _)| n == "FZ") {
                        return Err(a.err("EXCIT", format!("load {}: FZ in a {} model", lc.label(), md.name())));
                    }
                    for &c in cells {
                        let dofs = skin_dofs(c)?;
                        let xs = coords_of(mesh, c);
                        let err = std::cell::RefCell::new(None);
                        let f = |x: &[f64; 3], _n: &[f64; 3]| -> [f64; 3] {
                            let mut v = [0.0; 3];
                            for (name, val) in components {
                                let k = match name.as_str() {
                                    "FX" => 0,
                                    "FY" => 1,
                                    _ => 2,
                                };
                                match load_value(val, x, inst) {
                                    Ok(r) => v[k] = mult * r,
                                    Err(e) => *err.borrow_mut() = Some(e),
                                }
                            }
                            v
                        };
                        let fe = elasticity::boundary_force(md, mesh.cell_types[c], &xs, &f)
                            .map_err(|e| Error::runtime(e.to_string()))?;
                        if let Some(e) = err.into_inner() {
                            return Err(e.at(a.span));
                        }
                        forces.push((dofs, fe));
                    }
                }
                LoadItem::Pressure { cells, value } => {
                    for &c in cells {
                        let dofs = skin_dofs(c)?;
                        let xs = coords_of(mesh, c);
                        let pres: Vec<f64> =
                            xs.iter().map(|x| load_value(value, x, inst).map(|v| v * mult)).collect::<Result<_>>()?;
                        let fe = elasticity::pressure_force(md, mesh.cell_types[c], &xs, &pres, None)
                            .map_err(|e| Error::runtime(e.to_string()))?;
                        forces.push((dofs, fe));
                    }
                }
                LoadItem::Gravity { g, direction, cells } => {
                    let on: Vec<usize> = match cells {
                        Some(c) => c.iter().copied().filter(|c| p.materials[*c].is_some()).collect(),
                        None => p.bulk.clone(),
                    };
                    for c in on {
                        let rho = p.materials[c].as_ref().unwrap().1;
                        if rho == 0.0 {
                            return Err(a.err(
                                "EXCIT",
                                format!(
                                    "load {}: PESANTEUR on cell {}, whose material gives no RHO",
                                    lc.label(),
                                    mesh.cell_names[c]
                                ),
                            ));
                        }
                        let xs = coords_of(mesh, c);
                        let acc = [
                            rho * g * direction[0] * mult,
                            rho * g * direction[1] * mult,
                            rho * g * direction[2] * mult,
                        ];
                        let fe = elasticity::body_force(md, mesh.cell_types[c], &xs, &|_x| acc)
                            .map_err(|e| Error::runtime(e.to_string()))?;
                        let dofs = p.numbering.cell_dofs(&mesh.cells[c]).unwrap();
                        forces.push((dofs, fe));
                    }
                }
            }
        }
    }
    drop(model_ref);
    let map = DofMap::build(p.numbering.ndofs(), &cons)
        .map_err(|e| a.err("EXCIT", format!("incompatible kinematic conditions: {e}")))?;
    let t_numbering = t0.elapsed();

    // Assembly.
    let t0 = Instant::now();
    let mut elems = ElementDofs::new();
    for &c in &p.bulk {
        elems.push(&p.numbering.cell_dofs(&mesh.cells[c]).unwrap());
    }
    let pattern = SparsityPattern::build(&map, &elems);
    let mut asm = Assembler::new(&map, pattern);
    for (i, &c) in p.bulk.iter().enumerate() {
        let mat = &p.materials[c].as_ref().unwrap().0;
        let ke = elasticity::stiffness(md, mat, mesh.cell_types[c], &coords_of(mesh, c))
            .map_err(|e| Error::runtime(format!("cell {}: {e}", mesh.cell_names[c])).at(a.span))?;
        asm.add_matrix(elems.get(i), &ke);
    }
    for (dofs, fe) in &forces {
        asm.add_vector(dofs, fe);
    }
    let (k, rhs) = asm.finish();
    let t_assembly = t0.elapsed();
    Ok(System { map, k, rhs, t_numbering, t_assembly })
}

pub(super) fn solver_options(a: &Args) -> SolverOptions {
    let mut opts = SolverOptions::default();
    if let Some(s) = a.fact("SOLVEUR") {
        if let Some(n) = s.int("NPREC") {
            opts.nprec = n as i32;
        }
        if let Some(r) = s.real("RESI_RELA") {
            opts.resi_rela = r;
        }
    }
    opts
}

/// Solve, turning a singular matrix into a message naming the unknowns.
pub(super) fn solve_reduced(
    a: &Args,
    p: &Problem,
    map: &DofMap,
    k: &faer::sparse::SparseColMat<usize, f64>,
    rhs: &[f64],
    opts: &SolverOptions,
) -> Result<solve::Solution> {
    solve::solve(k.as_ref(), rhs, opts).map_err(|e| match e {
        solve::SolveError::Singular { dofs, .. } => {
            let names: Vec<String> =
                dofs.iter().take(6).map(|&d| p.numbering.label(map.free_to_full[d], Some(&p.mesh))).collect();
            a.err(
                "EXCIT",
                format!("the system is singular (rigid-body motion not prevented?): unknowns {}", names.join(", ")),
            )
        }
        other => Error::runtime(other.to_string()).at(a.span),
    })
}

/// DEPL (and SIEF_ELGA) of a full displacement vector.
pub(super) fn step_fields(p: &Problem, u: &[f64], with_sief: bool) -> Result<BTreeMap<String, Field>> {
    let mesh = &p.mesh;
    let md = p.modelisation;
    let dim = md.dim();
    let mut depl = vec![f64::NAN; mesh.coords.len() * dim];
    for (d, v) in u.iter().enumerate() {
        let (node, k) = p.numbering.node_comp(d);
        depl[node * dim + k] = *v;
    }
    let comps: Vec<String> = ["DX", "DY", "DZ"][..dim].iter().map(|s| s.to_string()).collect();
    let mut fields = BTreeMap::new();
    fields.insert("DEPL".to_string(), Field::Node { components: comps, values: depl });
    if with_sief {
        let mut cells = vec![None; mesh.cells.len()];
        for &c in &p.bulk {
            let ue: Vec<f64> = p.numbering.cell_dofs(&mesh.cells[c]).unwrap().iter().map(|&d| u[d]).collect();
            let g = elasticity::gauss_fields(
                md,
                &p.materials[c].as_ref().unwrap().0,
                mesh.cell_types[c],
                &coords_of(mesh, c),
                &ue,
            )
            .map_err(|e| Error::runtime(e.to_string()))?;
            cells[c] = Some(g.sig.iter().flat_map(|s| s[..md.nsig()].to_vec()).collect());
        }
        let names = md.sigma_names().iter().map(|s| s.to_string()).collect();
        fields.insert("SIEF_ELGA".to_string(), Field::Elga { components: names, cells });
    }
    Ok(fields)
}

pub fn meca_statique(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    if let Some(mo) = a.concept("MODELE") {
        if model_of(&mo)?.xfem.is_some() {
            return super::xfem_solve::meca_statique_xfem(ctx, a, &mo);
        }
    }
    // RESULTAT (adding a step to a result) and INST_FIN are not implemented.
    a.refuse(&["CARA_ELEM", "LIST_INST", "SENSIBILITE", "RESULTAT", "INST_FIN"])?;
    if let Some(o) = a.text("OPTION") {
        if o != "SIEF_ELGA" && o != "SANS" {
            return Err(a.err("OPTION", format!("OPTION='{o}' is not supported yet")));
        }
    }
    let t_all = Instant::now();
    let model = a.req_concept("MODELE")?;
    let chmat = a.concept("CHAM_MATER").ok_or_else(|| a.err("CHAM_MATER", "a material field is required"))?;
    let inst = a.reals("INST").first().copied().unwrap_or(0.0);
    let p = problem(&model, &chmat).map_err(|e| e.at(a.span))?;
    let md = p.modelisation;
    let System { map, k, rhs, t_numbering, t_assembly } = assemble(a, &p, &model, inst)?;

    // Solve.
    let sol = solve_reduced(a, &p, &map, &k, &rhs, &solver_options(a))?;
    let u = map.expand(&sol.x);

    // Fields.
    let t0 = Instant::now();
    let fields = step_fields(&p, &u, a.text("OPTION") != Some("SANS"))?;
    let t_post = t0.elapsed();
    ctx.io.mess(&format!(
        "  linear statics ({}): {} unknowns, {} eliminated by kinematic conditions, {} solved ({:?}); residual {:.1e}\n  \
         time: numbering {:.3} s, assembly {:.3} s, factorization {:.3} s, solve {:.3} s, fields {:.3} s, total {:.3} s\n",
        md.name(),
        map.nfull,
        map.n_eliminated(),
        map.nfree,
        sol.method,
        sol.residual,
        t_numbering.as_secs_f64(),
        t_assembly.as_secs_f64(),
        (sol.timings.symbolic + sol.timings.factorization).as_secs_f64(),
        sol.timings.solve.as_secs_f64(),
        t_post.as_secs_f64(),
        t_all.elapsed().as_secs_f64()
    ));
    let loads = a.facts("EXCIT").iter().filter_map(|o| o.concept("CHARGE")).collect();
    Ok(Some(ConceptData::Result(ResultData {
        model,
        material: Some(chmat),
        loads,
        steps: vec![Step { nume_ordre: 1, inst, fields }],
    })))
}

// ------------------------------------------------------------------ CALC_CHAMP

/// Average ELNO values to nodes over the cells sharing each node.
fn to_nodes(mesh: &Mesh, cells: &[Option<Vec<f64>>], ncmp: usize) -> Vec<f64> {
    let mut sum = vec![0.0; mesh.coords.len() * ncmp];
    let mut count = vec![0usize; mesh.coords.len()];
    for (c, v) in cells.iter().enumerate() {
        let Some(v) = v else { continue };
        for (i, &n) in mesh.cells[c].iter().enumerate() {
            count[n] += 1;
            for k in 0..ncmp {
                sum[n * ncmp + k] += v[i * ncmp + k];
            }
        }
    }
    for n in 0..count.len() {
        for k in 0..ncmp {
            sum[n * ncmp + k] = if count[n] > 0 { sum[n * ncmp + k] / count[n] as f64 } else { f64::NAN };
        }
    }
    sum
}

/// The components of SIEQ_* we compute (Code_Aster's SIEQ also has the
/// principal directions VECT_*, not computed yet).
const SIEQ_COMPONENTS: [&str; 8] = ["VMIS", "TRESCA", "PRIN_1", "PRIN_2", "PRIN_3", "VMIS_SG", "TRSIG", "TRIAX"];

/// Principal stresses (ascending) of a symmetric tensor given as
/// [xx, yy, zz, xy, (xz, yz)], by cyclic Jacobi rotations (accurate to
/// rounding even for nearly equal eigenvalues).
fn principal(s: &[f64]) -> [f64; 3] {
    let (xz, yz) = if s.len() >= 6 { (s[4], s[5]) } else { (0.0, 0.0) };
    let mut a = [[s[0], s[3], xz], [s[3], s[1], yz], [xz, yz, s[2]]];
    for _ in 0..50 {
        let off = a[0][1].abs() + a[0][2].abs() + a[1][2].abs();
        let scale = a[0][0].abs() + a[1][1].abs() + a[2][2].abs() + off;
        if off <= f64::EPSILON * 1e-3 * scale.max(f64::MIN_POSITIVE) {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let c = 1.0 / (t * t + 1.0).sqrt();
            let sn = t * c;
            // A <- Jᵀ A J with the rotation in the (p, q) plane.
            for row in a.iter_mut() {
                let (akp, akq) = (row[p], row[q]);
                row[p] = c * akp - sn * akq;
                row[q] = sn * akp + c * akq;
            }
            let (rp, rq) = (a[p], a[q]);
            for k in 0..3 {
                a[p][k] = c * rp[k] - sn * rq[k];
                a[q][k] = sn * rp[k] + c * rq[k];
            }
        }
    }
    let mut e = [a[0][0], a[1][1], a[2][2]];
    e.sort_by(|x, y| x.total_cmp(y));
    e
}

/// SIEQ components of one stress tensor.
fn equivalent_stresses(s: &[f64]) -> Vec<f64> {
    let tr = s[0] + s[1] + s[2];
    let m = tr / 3.0;
    let shear: f64 = s.iter().skip(3).map(|v| v * v).sum();
    let j2 = 0.5 * ((s[0] - m).powi(2) + (s[1] - m).powi(2) + (s[2] - m).powi(2)) + shear;
    let vmis = (3.0 * j2).sqrt();
    let pr = principal(s);
    let triax = if vmis > 0.0 { m / vmis } else { 0.0 };
    vec![vmis, pr[2] - pr[0], pr[0], pr[1], pr[2], if tr < 0.0 { -vmis } else { vmis }, tr, triax]
}

pub fn calc_champ(_ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    const DONE: &[&str] = &[
        "SIGM_ELNO",
        "SIGM_NOEU",
        "EPSI_ELNO",
        "EPSI_NOEU",
        "SIEF_ELGA",
        "SIGM_ELGA",
        "EPSI_ELGA",
        "SIRO_ELEM",
        "SIEQ_ELNO",
        "SIEQ_NOEU",
    ];
    let rc = a.req_concept("RESULTAT")?;
    let mut wanted = Vec::new();
    for kw in ["CONTRAINTE", "DEFORMATION", "CRITERES"] {
        for o in a.texts(kw) {
            if !DONE.contains(&o.as_str()) {
                return Err(a.err(kw, format!("option {o} is not supported yet")));
            }
            wanted.push(o);
        }
    }
    for kw in ["ENERGIE", "FORCE", "VARI_INTERNE", "ERREUR", "EQUI", "CHAM_UTIL", "HYDRAULIQUE", "PROPRIETES"] {
        if a.given(kw) {
            return Err(a.err(kw, "not supported yet"));
        }
    }
    let (model, chmat, mut steps) = {
        let r = result_of(&rc)?;
        let chmat = r.material.clone().ok_or_else(|| a.err("RESULTAT", "the result has no material field"))?;
        (r.model.clone(), chmat, r.steps.clone())
    };
    let p = problem(&model, &chmat).map_err(|e| e.at(a.span))?;
    let mesh = &p.mesh;
    let md = p.modelisation;
    let restrict = if a.has("GROUP_MA") || a.has("MAILLE") {
        Some(super::model::select_cells(mesh, a, &model_of(&model)?.mesh_concept.label())?)
    } else {
        None
    };
    let only = |c: &usize| restrict.as_ref().map(|r| r.contains(c)).unwrap_or(true);
    // The result's own model and material are used; other step selections are not implemented.
    a.refuse(&[
        "MODELE",
        "CHAM_MATER",
        "INST",
        "LIST_INST",
        "LIST_ORDRE",
        "FREQ",
        "LIST_FREQ",
        "NUME_MODE",
        "NOM_CAS",
        "NOEUD_CMP",
        "CARA_ELEM",
        "EXCIT",
    ])?;
    let orders = a.ints("NUME_ORDRE");
    for step in steps.iter_mut() {
        if !orders.is_empty() && !orders.contains(&step.nume_ordre) {
            continue;
        }
        let Some(Field::Node { values: depl, .. }) = step.fields.get("DEPL") else {
            return Err(a.err("RESULTAT", format!("no DEPL at order {}", step.nume_ordre)));
        };
        let ns = md.nsig();
        let (mut sig_elno, mut eps_elno) = (vec![None; mesh.cells.len()], vec![None; mesh.cells.len()]);
        let (mut sig_elga, mut eps_elga) = (vec![None; mesh.cells.len()], vec![None; mesh.cells.len()]);
        for &c in p.bulk.iter().filter(|c| only(c)) {
            let ue: Vec<f64> =
                mesh.cells[c].iter().flat_map(|&n| (0..md.dim()).map(move |k| depl[n * md.dim() + k])).collect();
            let mat = &p.materials[c].as_ref().unwrap().0;
            let xs = coords_of(mesh, c);
            let (eps, sig) = elasticity::node_fields(md, mat, mesh.cell_types[c], &xs, &ue)
                .map_err(|e| Error::runtime(e.to_string()))?;
            sig_elno[c] = Some(sig.iter().flat_map(|s| s[..ns].to_vec()).collect::<Vec<_>>());
            eps_elno[c] = Some(eps.iter().flat_map(|s| s[..ns].to_vec()).collect::<Vec<_>>());
            let g = elasticity::gauss_fields(md, mat, mesh.cell_types[c], &xs, &ue)
                .map_err(|e| Error::runtime(e.to_string()))?;
            sig_elga[c] = Some(g.sig.iter().flat_map(|s| s[..ns].to_vec()).collect::<Vec<_>>());
            eps_elga[c] = Some(g.eps.iter().flat_map(|s| s[..ns].to_vec()).collect::<Vec<_>>());
        }
        let siro = match wanted.iter().any(|o| o == "SIRO_ELEM") {
            true => Some(super::fields::siro_elem(&p, &model, depl, &only).map_err(|e| e.at(a.span))?),
            false => None,
        };
        let sn: Vec<String> = md.sigma_names().iter().map(|s| s.to_string()).collect();
        let en: Vec<String> = md.epsilon_names().iter().map(|s| s.to_string()).collect();
        for o in &wanted {
            let f = match o.as_str() {
                "SIGM_ELNO" => Field::Elno { components: sn.clone(), cells: sig_elno.clone() },
                "EPSI_ELNO" => Field::Elno { components: en.clone(), cells: eps_elno.clone() },
                "SIGM_NOEU" => Field::Node { components: sn.clone(), values: to_nodes(mesh, &sig_elno, ns) },
                "EPSI_NOEU" => Field::Node { components: en.clone(), values: to_nodes(mesh, &eps_elno, ns) },
                // In linear elasticity the generalized and Cauchy stresses coincide.
                "SIEF_ELGA" | "SIGM_ELGA" => Field::Elga { components: sn.clone(), cells: sig_elga.clone() },
                "SIRO_ELEM" => siro.clone().expect("computed above"),
                "SIEQ_ELNO" | "SIEQ_NOEU" => {
                    let cells: Vec<Option<Vec<f64>>> = sig_elno
                        .iter()
                        .map(|c| c.as_ref().map(|v| v.chunks(ns).flat_map(equivalent_stresses).collect()))
                        .collect();
                    let names = SIEQ_COMPONENTS.iter().map(|s| s.to_string()).collect();
                    if o == "SIEQ_ELNO" {
                        Field::Elno { components: names, cells }
                    } else {
                        Field::Node { components: names, values: to_nodes(mesh, &cells, SIEQ_COMPONENTS.len()) }
                    }
                }
                _ => Field::Elga { components: en.clone(), cells: eps_elga.clone() },
            };
            step.fields.insert(o.clone(), f);
        }
    }
    let r = result_of(&rc)?;
    let data = ResultData { model: r.model.clone(), material: r.material.clone(), loads: r.loads.clone(), steps };
    Ok(Some(ConceptData::Result(data)))
}

#[cfg(test)]
mod sieq_tests {
    use super::*;

    #[test]
    fn equivalent_stresses_of_known_tensors() {
        // Uniaxial: VMIS = TRESCA = |s|, principal (0, 0, s).
        let e = equivalent_stresses(&[0.0, 0.0, 7.0, 0.0, 0.0, 0.0]);
        assert!((e[0] - 7.0).abs() < 1e-12 && (e[1] - 7.0).abs() < 1e-12);
        assert!(e[2].abs() < 1e-12 && e[3].abs() < 1e-12 && (e[4] - 7.0).abs() < 1e-12);
        // Pure shear xy = t: principal (-t, 0, t), VMIS = sqrt(3) t, TRESCA = 2t.
        let e = equivalent_stresses(&[0.0, 0.0, 0.0, 2.0]);
        assert!((e[0] - 2.0 * 3f64.sqrt()).abs() < 1e-12 && (e[1] - 4.0).abs() < 1e-12);
        assert!((e[2] + 2.0).abs() < 1e-12 && e[3].abs() < 1e-12 && (e[4] - 2.0).abs() < 1e-12);
        // Hydrostatic: VMIS 0, TRSIG = 3p.
        let e = equivalent_stresses(&[-5.0, -5.0, -5.0, 0.0, 0.0, 0.0]);
        assert!(e[0].abs() < 1e-12 && (e[6] + 15.0).abs() < 1e-12);
        // A general tensor: principal values are the eigenvalues (their sum and product).
        let s = [3.0, -1.0, 2.0, 0.5, -0.7, 1.1];
        let p = principal(&s);
        assert!((p[0] + p[1] + p[2] - 4.0).abs() < 1e-12);
        let det = s[0] * (s[1] * s[2] - s[5] * s[5]) - s[3] * (s[3] * s[2] - s[5] * s[4])
            + s[4] * (s[3] * s[5] - s[1] * s[4]);
        assert!((p[0] * p[1] * p[2] - det).abs() < 1e-10);
    }
}
