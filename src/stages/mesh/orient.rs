//! MODI_MAILLAGE: ORIE_PEAU (and its former spellings ORIE_PEAU_2D /
//! ORIE_PEAU_3D), TRANSLATION and ECHELLE; ORIE_PEAU reorients skin cells so that their normal points out of
//! the cell they bound, as Code_Aster's `orilma` / `oriema` do.
//!
//! For each skin cell (SEG2/SEG3 bounding plane cells, TRIA3/6 and
//! QUAD4/8/9 bounding volume cells) the bounded cell is a cell of one
//! dimension more holding all of its nodes — among GROUP_MA_INTERNE
//! (GROUP_MA_SURF, GROUP_MA_VOLU) when given. A skin cell between cells on
//! both sides is an error (name the side with GROUP_MA_INTERNE); one that
//! bounds no cell is left as it is and reported. The test is Code_Aster's:
//! the normal from the first nodes against the vector between the vertex
//! centroids; a cell found inward has its nodes permuted by
//! [`geometry::flip_permutation`]. TRANSLATION and ECHELLE move the nodes
//! (the translation first, then the scaling about the origin). Like
//! Code_Aster, the mesh of MAILLAGE is modified in place, reuse or not.

use crate::catalog::args::Args;
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::fem::geometry;
use crate::mesh::Mesh;
use crate::stages::Ctx;
use std::collections::HashSet;
use std::rc::Rc;

/// MODI_MAILLAGE keywords not implemented yet.
const NOT_YET: &[&str] = &[
    "ORIE_FISSURE",
    "DEFORME",
    "ORIE_NORM_COQUE",
    "ORIE_LIGNE",
    "MODI_MAILLE",
    "MODI_BASE",
    "ROTATION",
    "SYMETRIE",
    "ABSC_CURV",
];

/// Cells of the groups of keyword `kw` of an occurrence, each once, in order.
fn group_cells(mesh: &Mesh, occ: &Args, kw: &str, mesh_name: &str) -> Result<Vec<usize>> {
    let mut seen = HashSet::new();
    let mut out = Vec::new();
    for g in occ.texts(kw) {
        let members = mesh
            .cell_groups
            .get(&g)
            .ok_or_else(|| occ.err(kw, format!("group of cells '{g}' is not in mesh {mesh_name}")))?;
        out.extend(members.iter().copied().filter(|c| seen.insert(*c)));
    }
    Ok(out)
}

/// What one occurrence did.
#[derive(Debug, Default, PartialEq)]
pub struct OrientReport {
    pub examined: usize,
    pub flipped: usize,
    /// Skin cells that bound no cell (left as they are).
    pub lonely: Vec<usize>,
}

/// Why a skin cell cannot be oriented.
#[derive(Debug, PartialEq)]
pub enum OrientError {
    /// Not a SEG2/3, TRIA3/6, QUAD4/8/9 cell, or a degenerate one.
    NotSkin(usize),
    /// Segments and faces in the same list.
    Mixed,
    /// Between two cells on both sides: (skin, one side, other side).
    Between(usize, usize, usize),
}

/// Orient `skin` cells of `mesh` outward (see the module documentation),
/// looking for the bounded cells among `inside` when given.
pub fn orient_skin(
    mesh: &mut Mesh,
    skin: &[usize],
    inside: Option<&HashSet<usize>>,
) -> std::result::Result<OrientReport, OrientError> {
    let mut rep = OrientReport::default();
    let (mut segs, mut faces) = (false, false);
    for &c in skin {
        let t = mesh.cell_types[c];
        if !geometry::is_skin_type(t) {
            return Err(OrientError::NotSkin(c));
        }
        segs |= t.dim() == 1;
        faces |= t.dim() == 2;
    }
    if segs && faces {
        return Err(OrientError::Mixed);
    }
    let node_cells = geometry::node_to_cells(mesh);
    for &c in skin {
        rep.examined += 1;
        let t = mesh.cell_types[c];
        let xs = geometry::cell_coords(mesh, c);
        let candidates = geometry::bounded_cells(mesh, &node_cells, c, inside);
        let mut chosen: Option<(usize, f64)> = None;
        for v in candidates {
            let m = geometry::outward_measure(t, &xs, mesh.cell_types[v], &geometry::cell_coords(mesh, v))
                .ok_or(OrientError::NotSkin(c))?;
            match chosen {
                None => chosen = Some((v, m)),
                // Same side as the first: keep the first (utmasu).
                Some((_, m0)) if (m0 > 0.0) == (m > 0.0) => {}
                Some((v0, _)) => return Err(OrientError::Between(c, v0, v)),
            }
        }
        let Some((_, m)) = chosen else {
            rep.lonely.push(c);
            continue;
        };
        if m < 0.0 {
            let perm = geometry::flip_permutation(t).ok_or(OrientError::NotSkin(c))?;
            let old = mesh.cells[c].clone();
            mesh.cells[c] = perm.iter().map(|&i| old[i]).collect();
            rep.flipped += 1;
        }
    }
    Ok(rep)
}

pub fn modi_maillage(ctx: &mut Ctx, a: &Args) -> Result<Option<ConceptData>> {
    for kw in NOT_YET {
        if a.given(kw) {
            return Err(a.err(kw, "not supported yet"));
        }
    }
    let c = a.req_concept("MAILLAGE")?;
    let label = c.label();
    let mut mesh = (*c.mesh().map_err(|e| a.err("MAILLAGE", e.msg))?).clone();
    let mut text = String::new();
    // (factor keyword, skin groups, groups of the bounded cells, expected skin dimension)
    let forms: [(&str, &str, &str, Option<usize>); 3] = [
        ("ORIE_PEAU", "GROUP_MA_PEAU", "GROUP_MA_INTERNE", None),
        ("ORIE_PEAU_2D", "GROUP_MA", "GROUP_MA_SURF", Some(1)),
        ("ORIE_PEAU_3D", "GROUP_MA", "GROUP_MA_VOLU", Some(2)),
    ];
    let mut any = false;
    for (fact, skin_kw, in_kw, want) in forms {
        for occ in a.facts(fact) {
            any = true;
            let skin = group_cells(&mesh, occ, skin_kw, &label)?;
            if let Some(d) = want {
                if let Some(&bad) = skin.iter().find(|&&s| mesh.cell_types[s].dim() != d) {
                    let what = if d == 1 { "segments (SEG2, SEG3)" } else { "faces (TRIA3/6, QUAD4/8/9)" };
                    return Err(occ.err(
                        skin_kw,
                        format!(
                            "cell {} is a {}: {fact} orients {what}",
                            mesh.cell_names[bad],
                            mesh.cell_types[bad].name()
                        ),
                    ));
                }
            }
            let inside: Option<HashSet<usize>> =
                if occ.has(in_kw) { Some(group_cells(&mesh, occ, in_kw, &label)?.into_iter().collect()) } else { None };
            let rep = orient_skin(&mut mesh, &skin, inside.as_ref()).map_err(|e| match e {
                OrientError::NotSkin(s) => occ.err(
                    skin_kw,
                    format!(
                        "cell {} ({}) is not a skin cell that can be oriented (SEG2/3 of a plane domain, \
                         TRIA3/6 or QUAD4/8/9 of a volume), or it is degenerate",
                        mesh.cell_names[s],
                        mesh.cell_types[s].name()
                    ),
                ),
                OrientError::Mixed => occ.err(skin_kw, "the groups mix segments and faces: orient them separately"),
                OrientError::Between(s, v1, v2) => occ.err(
                    skin_kw,
                    format!(
                        "cell {} lies between cells {} and {}, one on each side: name the side to orient \
                         against with {in_kw}",
                        mesh.cell_names[s], mesh.cell_names[v1], mesh.cell_names[v2]
                    ),
                ),
            })?;
            text.push_str(&format!(
                "  {fact} ({}): {} skin cells examined, {} reoriented\n",
                occ.texts(skin_kw).join(", "),
                rep.examined,
                rep.flipped
            ));
            if !rep.lonely.is_empty() {
                let names: Vec<&str> = rep.lonely.iter().take(10).map(|&s| mesh.cell_names[s].as_str()).collect();
                text.push_str(&format!(
                    " <A> MODI_MAILLAGE: {} skin cells bound no cell{} and were left as they are: {}{}\n",
                    rep.lonely.len(),
                    if inside.is_some() { format!(" of {in_kw}") } else { String::new() },
                    names.join(" "),
                    if rep.lonely.len() > 10 { " ..." } else { "" }
                ));
            }
        }
    }
    // The moves of the nodes, in Code_Aster's order: the translation, then the scaling about the origin.
    let tran = a.reals("TRANSLATION");
    if !tran.is_empty() {
        any = true;
        if tran.len() != mesh.dim && !(tran.len() == 3 && mesh.dim == 2) {
            return Err(a.err("TRANSLATION", format!("{} components for a mesh of dimension {}", tran.len(), mesh.dim)));
        }
        for x in mesh.coords.iter_mut() {
            for (k, t) in tran.iter().enumerate() {
                x[k] += t;
            }
        }
        text.push_str(&format!("  TRANSLATION {tran:?}: {} nodes moved\n", mesh.coords.len()));
    }
    if let Some(e) = a.real("ECHELLE") {
        any = true;
        if !(e.is_finite() && e != 0.0) {
            return Err(a.err("ECHELLE", format!("the scale factor must be a non-zero number (got {e})")));
        }
        for x in mesh.coords.iter_mut() {
            x.iter_mut().for_each(|v| *v *= e);
        }
        text.push_str(&format!("  ECHELLE {e}: {} nodes scaled\n", mesh.coords.len()));
    }
    if !any {
        return Err(a.err("MAILLAGE", "no modification asked (ORIE_PEAU, TRANSLATION and ECHELLE are supported)"));
    }
    ctx.io.mess(&text);
    let rc = Rc::new(mesh);
    // Code_Aster modifies MAILLAGE in place, reuse or not.
    c.replace(ConceptData::Mesh(rc.clone()));
    Ok(Some(ConceptData::Mesh(rc)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate::box_mesh;
    use crate::mesh::CellType;

    #[test]
    fn reorients_a_reversed_edge_and_face() {
        let mut m = box_mesh(CellType::Quad8, &[2, 2], &[1.0, 1.0]).unwrap();
        let haut = m.cell_groups["HAUT"].clone();
        let before = m.cells[haut[0]].clone();
        m.cells[haut[0]] = vec![before[1], before[0], before[2]];
        let all: Vec<usize> = (0..m.cells.len()).filter(|&c| m.cell_types[c].dim() == 1).collect();
        let rep = orient_skin(&mut m, &all, None).unwrap();
        assert_eq!(rep.flipped, 1);
        assert_eq!(m.cells[haut[0]], before);
        // Idempotent.
        assert_eq!(orient_skin(&mut m, &all, None).unwrap().flipped, 0);

        let mut m = box_mesh(CellType::Hexa20, &[1, 1, 1], &[1.0, 2.0, 3.0]).unwrap();
        let z = m.cell_groups["ZMAX"][0];
        let good = m.cells[z].clone();
        let p = geometry::flip_permutation(CellType::Quad8).unwrap();
        m.cells[z] = p.iter().map(|&i| good[i]).collect();
        let rep = orient_skin(&mut m, &[z], None).unwrap();
        assert_eq!(rep.flipped, 1);
        assert_eq!(m.cells[z], good, "flipping twice gives the cell back");
    }

    #[test]
    fn internal_face_needs_a_side() {
        // Two squares side by side; an edge on their common side.
        let mut m = box_mesh(CellType::Quad4, &[2, 1], &[2.0, 1.0]).unwrap();
        let quads: Vec<usize> = m.cell_groups["SURFACE"].clone();
        let mid: Vec<usize> = (0..m.coords.len()).filter(|&n| (m.coords[n][0] - 1.0).abs() < 1e-12).collect();
        m.cells.push(vec![mid[0], mid[1]]);
        m.cell_types.push(CellType::Seg2);
        m.cell_names.push("MID".into());
        let s = m.cells.len() - 1;
        assert!(matches!(orient_skin(&mut m, &[s], None), Err(OrientError::Between(..))));
        // Against the left square: the normal must point to +x.
        let left = *quads.iter().find(|&&q| m.cells[q].iter().any(|&n| m.coords[n][0] < 0.5)).unwrap();
        let inside: HashSet<usize> = [left].into_iter().collect();
        orient_skin(&mut m, &[s], Some(&inside)).unwrap();
        let n = geometry::normal_at(CellType::Seg2, &geometry::cell_coords(&m, s), &[0.0; 3]).unwrap();
        assert!((n[0] - 1.0).abs() < 1e-12);
        let right: HashSet<usize> = quads.iter().copied().filter(|q| *q != left).collect();
        orient_skin(&mut m, &[s], Some(&right)).unwrap();
        let n = geometry::normal_at(CellType::Seg2, &geometry::cell_coords(&m, s), &[0.0; 3]).unwrap();
        assert!((n[0] + 1.0).abs() < 1e-12);
    }

    #[test]
    fn refuses_volume_cells_and_mixtures() {
        let mut m = box_mesh(CellType::Hexa8, &[1, 1, 1], &[1.0, 1.0, 1.0]).unwrap();
        let v = m.cell_groups["VOLUME"][0];
        assert_eq!(orient_skin(&mut m, &[v], None), Err(OrientError::NotSkin(v)));
    }
}
