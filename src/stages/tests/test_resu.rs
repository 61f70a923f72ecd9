//! TEST_RESU (RESU) and POST_RELEVE_T (EXTRACTION): reading values out of
//! results.

use super::verdict::{check, Scalar};
use crate::catalog::args::Args;
use crate::concepts::result::{Field, ResultData, Step};
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::mesh::Mesh;
use crate::stages::Ctx;
use std::rc::Rc;

pub fn mesh_of_result(r: &ResultData) -> Result<Rc<Mesh>> {
    Ok(r.model.model()?.current_mesh())
}

/// The step an occurrence designates (NUME_ORDRE or INST; the only step otherwise).
fn step_of<'r>(r: &'r ResultData, occ: &Args, name: &str) -> Result<&'r Step> {
    if let Some(n) = occ.ints("NUME_ORDRE").first() {
        return r.by_order(*n).ok_or_else(|| occ.err("NUME_ORDRE", format!("result {name} has no order number {n}")));
    }
    if let Some(t) = occ.reals("INST").first() {
        // PRECISION and CRITERE of TEST_RESU are the check's tolerance, not the time search's.
        let hits: Vec<&Step> =
            r.steps.iter().filter(|s| (s.inst - t).abs() <= 1e-6 * t.abs().max(1e-300) || s.inst == *t).collect();
        return match hits.as_slice() {
            [one] => Ok(one),
            [] => Err(occ.err("INST", format!("result {name} has no step at time {t}"))),
            _ => Err(occ.err("INST", format!("several steps of result {name} are at time {t}"))),
        };
    }
    match r.steps.as_slice() {
        [one] => Ok(one),
        [] => Err(occ.err("RESULTAT", format!("result {name} holds no step"))),
        _ => Err(occ.err("RESULTAT", format!("result {name} holds {} steps: give NUME_ORDRE or INST", r.steps.len()))),
    }
}

/// The single entity an occurrence names: by name (`name_kw`) or by a group
/// of exactly one member (`group_kw`); `what` is "node" or "cell".
fn one_entity(
    names: &[String],
    groups: &std::collections::BTreeMap<String, Vec<usize>>,
    occ: &Args,
    name_kw: &str,
    group_kw: &str,
    what: &str,
    mesh_name: &str,
) -> Result<Option<usize>> {
    if let Some(n) = occ.text(name_kw) {
        return names
            .iter()
            .position(|x| x == n)
            .map(Some)
            .ok_or_else(|| occ.err(name_kw, format!("{what} '{n}' is not in mesh {mesh_name}")));
    }
    if let Some(g) = occ.text(group_kw) {
        let m = groups
            .get(g)
            .ok_or_else(|| occ.err(group_kw, format!("group of {what}s '{g}' is not in mesh {mesh_name}")))?;
        if m.len() != 1 {
            return Err(occ.err(group_kw, format!("group '{g}' holds {} {what}s; the test needs exactly one", m.len())));
        }
        return Ok(Some(m[0]));
    }
    Ok(None)
}

fn one_node(mesh: &Mesh, occ: &Args, mesh_name: &str) -> Result<Option<usize>> {
    one_entity(&mesh.node_names, &mesh.node_groups, occ, "NOEUD", "GROUP_NO", "node", mesh_name)
}

fn one_cell(mesh: &Mesh, occ: &Args, mesh_name: &str) -> Result<Option<usize>> {
    one_entity(&mesh.cell_names, &mesh.cell_groups, occ, "MAILLE", "GROUP_MA", "cell", mesh_name)
}

/// The value of one component of a field at the place an occurrence names.
fn locate(field: &Field, k: usize, mesh: &Mesh, occ: &Args, mesh_name: &str) -> Result<f64> {
    let n = field.components().len();
    let v = match field {
        Field::Node { values, .. } => {
            let node =
                one_node(mesh, occ, mesh_name)?.ok_or_else(|| occ.err("NOEUD", "NOEUD or GROUP_NO is required"))?;
            values[node * n + k]
        }
        Field::Elno { cells, .. } => {
            let c =
                one_cell(mesh, occ, mesh_name)?.ok_or_else(|| occ.err("MAILLE", "MAILLE or GROUP_MA is required"))?;
            // POINT: the cell's node of that local number, else the node of NOEUD / GROUP_NO.
            let i = match occ.declares("POINT").then(|| occ.int("POINT")).flatten() {
                Some(p) if p >= 1 && p as usize <= mesh.cells[c].len() => p as usize - 1,
                Some(p) => {
                    let nno = mesh.cells[c].len();
                    return Err(
                        occ.err("POINT", format!("cell {} has {nno} nodes, point {p} requested", mesh.cell_names[c]))
                    );
                }
                None => {
                    let node = one_node(mesh, occ, mesh_name)?
                        .ok_or_else(|| occ.err("NOEUD", "NOEUD, GROUP_NO or POINT is required"))?;
                    mesh.cells[c].iter().position(|&x| x == node).ok_or_else(|| {
                        occ.err(
                            "NOEUD",
                            format!("node {} is not a node of cell {}", mesh.node_names[node], mesh.cell_names[c]),
                        )
                    })?
                }
            };
            let vals = cells[c]
                .as_ref()
                .ok_or_else(|| occ.err("MAILLE", format!("the field has no value on cell {}", mesh.cell_names[c])))?;
            vals[i * n + k]
        }
        Field::Elga { cells, .. } => {
            let c =
                one_cell(mesh, occ, mesh_name)?.ok_or_else(|| occ.err("MAILLE", "MAILLE or GROUP_MA is required"))?;
            let p =
                occ.int("POINT").ok_or_else(|| occ.err("POINT", "POINT is required for a field at Gauss points"))?;
            if occ.given("SOUS_POINT") {
                return Err(occ.err("SOUS_POINT", "not supported yet"));
            }
            let vals = cells[c]
                .as_ref()
                .ok_or_else(|| occ.err("MAILLE", format!("the field has no value on cell {}", mesh.cell_names[c])))?;
            let npg = vals.len() / n;
            if p < 1 || p as usize > npg {
                return Err(occ
                    .err("POINT", format!("cell {} has {npg} Gauss points, point {p} requested", mesh.cell_names[c])));
            }
            vals[(p as usize - 1) * n + k]
        }
        Field::Elem { cells, .. } => {
            let c =
                one_cell(mesh, occ, mesh_name)?.ok_or_else(|| occ.err("MAILLE", "MAILLE or GROUP_MA is required"))?;
            let vals = cells[c]
                .as_ref()
                .ok_or_else(|| occ.err("MAILLE", format!("the field has no value on cell {}", mesh.cell_names[c])))?;
            vals[k]
        }
    };
    if v.is_nan() {
        return Err(occ.err("NOM_CMP", "the field has no value of this component there"));
    }
    Ok(v)
}

pub fn test_resu(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    a.refuse(&["CARTE", "MAILLAGE", "OBJET", "GENE"])?;
    for kw in ["CHAM_NO", "CHAM_ELEM"] {
        for occ in a.facts(kw) {
            test_field(ctx, occ, kw)?;
        }
    }
    for occ in a.facts("RESU") {
        let rc = occ.req_concept("RESULTAT")?;
        let name = rc.label();
        let r = rc.result()?;
        let mesh = mesh_of_result(&r)?;
        let mesh_name = r.model.model()?.mesh_concept.label();
        let step = step_of(&r, occ, &name)?;
        occ.refuse(&["NOM_VARI", "PARA", "FREQ", "NUME_MODE", "NOEUD_CMP", "NOM_CAS", "ANGLE", "SOUS_POINT"])?;
        for kw in ["NOEUD", "GROUP_NO"] {
            if occ.vals(kw).len() > 1 {
                return Err(occ.err(kw, "one node only: the test reads one value"));
            }
        }
        if occ.has("TYPE_TEST") {
            for kw in ["NOEUD", "GROUP_NO", "MAILLE", "GROUP_MA"] {
                if occ.given(kw) {
                    return Err(occ.err(
                        kw,
                        "TYPE_TEST over a part of the field is not supported yet (it runs over the whole field)",
                    ));
                }
            }
        }
        let cham = occ.req_text("NOM_CHAM")?;
        let field = step.fields.get(cham).ok_or_else(|| {
            occ.err("NOM_CHAM", format!("result {name} has no field {cham} at order {}", step.nume_ordre))
        })?;
        // TYPE_TEST without NOM_CMP runs over every component of the field, as Code_Aster's.
        let cmp_given = occ.text("NOM_CMP");
        let (value, where_, cmp) = match (occ.text("TYPE_TEST"), cmp_given) {
            (Some(tt), None) => {
                let vals: Vec<f64> = (0..field.components().len()).flat_map(|k| field.all_values(k)).collect();
                if vals.is_empty() {
                    return Err(occ.err("TYPE_TEST", format!("field {cham} has no value")));
                }
                (super::verdict::type_test(tt, &vals), format!("TYPE_TEST {tt}"), tt)
            }
            _ => {
                let cmp = occ.req_text("NOM_CMP")?;
                let k = field.component(cmp).ok_or_else(|| {
                    occ.err(
                        "NOM_CMP",
                        format!("field {cham} has no component {cmp} (components: {})", field.components().join(", ")),
                    )
                })?;
                match occ.text("TYPE_TEST") {
                    Some(tt) => {
                        let vals = field.all_values(k);
                        if vals.is_empty() {
                            return Err(occ.err("TYPE_TEST", format!("field {cham} has no value of {cmp}")));
                        }
                        (super::verdict::type_test(tt, &vals), format!("TYPE_TEST {tt}"), cmp)
                    }
                    None => {
                        let v = locate(field, k, &mesh, occ, &mesh_name)?;
                        (v, place(occ, false), cmp)
                    }
                }
            }
        };
        let title = match cmp_given {
            Some(c) => format!("RESULTAT {name} NUME_ORDRE {} NOM_CHAM {cham} NOM_CMP {c} {where_}", step.nume_ordre),
            None => format!("RESULTAT {name} NUME_ORDRE {} NOM_CHAM {cham} {where_}", step.nume_ordre),
        };
        check(ctx, occ, Scalar::R(value), cmp, &title)?;
    }
    Ok(None)
}

/// Where an occurrence tests, for the title of its check: the entity keywords given and POINT
/// (`declared_only`: those its factor keyword declares).
fn place(occ: &Args, declared_only: bool) -> String {
    let mut w = Vec::new();
    for kw in ["NOEUD", "GROUP_NO", "MAILLE", "GROUP_MA"] {
        let t = if declared_only { occ.text_if_declared(kw) } else { occ.text(kw) };
        if let Some(t) = t {
            w.push(format!("{kw} {t}"));
        }
    }
    if let Some(p) = occ.declares("POINT").then(|| occ.int("POINT")).flatten() {
        w.push(format!("POINT {p}"));
    }
    w.join(" ")
}

/// One occurrence of CHAM_NO or CHAM_ELEM: a value of a standalone field.
fn test_field(ctx: &mut Ctx, occ: &Args, kw: &str) -> Result<()> {
    let fc = occ.req_concept("CHAM_GD")?;
    let name = fc.label();
    let f = fc.field()?;
    let mesh = f.mesh_concept.mesh()?;
    let mesh_name = f.mesh_concept.label();
    if f.functions.is_some() {
        return Err(occ.err("CHAM_GD", format!("{name} is a field of functions; only fields of reals can be tested")));
    }
    let field = &f.field;
    let (value, legend, where_) = match (occ.text("TYPE_TEST"), occ.text("NOM_CMP")) {
        (Some(tt), cmp) => {
            let ks: Vec<usize> = match cmp {
                Some(c) => vec![field.component(c).ok_or_else(|| {
                    occ.err("NOM_CMP", format!("field {name} has no component {c} ({})", field.components().join(", ")))
                })?],
                None => (0..field.components().len()).collect(),
            };
            let vals: Vec<f64> = ks.iter().flat_map(|&k| field.all_values(k)).collect();
            let v = super::verdict::type_test(tt, &vals);
            (v, cmp.unwrap_or(tt).to_string(), format!("TYPE_TEST {tt}"))
        }
        (None, Some(cmp)) => {
            let k = field.component(cmp).ok_or_else(|| {
                occ.err("NOM_CMP", format!("field {name} has no component {cmp} ({})", field.components().join(", ")))
            })?;
            let v = locate(field, k, &mesh, occ, &mesh_name)?;
            // CHAM_NO declares neither cells nor points: only the keywords of this factor keyword are read.
            (v, cmp.to_string(), format!("NOM_CMP {cmp} {}", place(occ, true)))
        }
        (None, None) => return Err(occ.err("NOM_CMP", "NOM_CMP or TYPE_TEST is required")),
    };
    let title = format!("{kw} {name} {where_}");
    check(ctx, occ, Scalar::R(value), &legend, title.trim_end())
}
