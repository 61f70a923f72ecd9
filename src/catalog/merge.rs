//! The schema `aster check` validates a hand-written command against: Code_Aster's facts completed by
//! ours.
//!
//! A hand-written schema describes what our stage does, which is often less than Code_Aster offers
//! (DEFI_MATERIAU's behaviours, STAT_NON_LINE's options). `aster check` must accept every valid
//! Code_Aster call, so it validates against Code_Aster's schema (generated from its catalogue), widened
//! where ours accepts more (older spellings, values of ours): the types and allowed values of a keyword
//! both schemas declare are united, keywords only ours declares are added, and Code_Aster's statuses,
//! defaults, block conditions and rules are kept. `aster run` then validates the call a second time
//! against the hand-written schema, which stays the source of truth for what runs: what lies outside it
//! stops the run by name as not supported yet (`validate::validate_supported`). A call the merged schema
//! refuses and the hand-written one accepts is valid too: ours keeps spellings of older Code_Aster
//! versions under conditions 2025's no longer has (DEFI_CONTACT's XFEM zones), which the merge cannot
//! express (the runner's session tries both).

use super::schema::*;
use crate::concepts::ConceptKind;

/// The checked schema of a command that has both a hand-written schema `h` and Code_Aster's `g`.
pub fn merge(h: &Command, g: &Command) -> Command {
    let reentrant = match (h.reentrant, g.reentrant) {
        (Reentrant::No, Reentrant::No) => Reentrant::No,
        (Reentrant::Mandatory, Reentrant::Mandatory) => Reentrant::Mandatory,
        _ => Reentrant::Optional,
    };
    Command {
        name: h.name,
        doc: h.doc,
        produces: g.produces.clone(),
        reentrant,
        entries: merge_level(&h.entries, &g.entries),
        rules: g.rules.clone(),
        open: h.open || g.open,
    }
}

/// The entries of one level, blocks flattened, each with the conditions of the blocks around it.
fn flatten<'e>(entries: &'e [Entry], conds: &mut Vec<&'e Cond>, out: &mut Vec<(Vec<&'e Cond>, &'e Entry)>) {
    for e in entries {
        match e {
            Entry::Bloc(b) => {
                conds.push(&b.cond);
                flatten(&b.entries, conds, out);
                conds.pop();
            }
            _ => out.push((conds.clone(), e)),
        }
    }
}

fn name_of(e: &Entry) -> Option<&'static str> {
    match e {
        Entry::Simp(s) => Some(s.name),
        Entry::Fact(f) => Some(f.name),
        Entry::Bloc(_) => None,
    }
}

fn merge_level(h: &[Entry], g: &[Entry]) -> Vec<Entry> {
    let mut hs = Vec::new();
    flatten(h, &mut Vec::new(), &mut hs);
    let mut gs = Vec::new();
    flatten(g, &mut Vec::new(), &mut gs);
    let mut out = merge_entries(g, &hs, &mut Vec::new());
    // Keywords only ours declares, under our block conditions; optional, since a mandatory keyword of
    // ours (a stage's requirement) is no rule of Code_Aster's.
    let mut added = Vec::new();
    let hs_names: Vec<&str> = hs.iter().filter_map(|(_, e)| name_of(e)).collect();
    for (conds, e) in hs {
        let name = name_of(e).unwrap();
        if gs.iter().any(|(_, x)| name_of(x) == Some(name)) || added.contains(&name) {
            continue;
        }
        added.push(name);
        // Declared under several conditions of ours: offered under none.
        let several = hs_names.iter().filter(|n| **n == name).count() > 1;
        let conds = if several { Vec::new() } else { conds };
        let mut entry = e.clone();
        match &mut entry {
            Entry::Simp(s) if s.statut == Statut::O => s.statut = Statut::F,
            Entry::Fact(f) if f.statut == FactStatut::O => f.statut = FactStatut::F,
            _ => {}
        }
        for c in conds.iter().rev() {
            entry = Entry::Bloc(bloc((*c).clone(), vec![entry]));
        }
        out.push(entry);
    }
    out
}

/// Code_Aster's entries `g`, widened by ours `hs`; `conds` are the conditions of the blocks around `g`.
fn merge_entries(g: &[Entry], hs: &[(Vec<&Cond>, &Entry)], conds: &mut Vec<String>) -> Vec<Entry> {
    g.iter()
        .map(|e| match e {
            Entry::Simp(s) => {
                let ours: Vec<&Simp> = hs
                    .iter()
                    .filter_map(|(_, x)| match x {
                        Entry::Simp(o) if o.name == s.name => Some(o),
                        _ => None,
                    })
                    .collect();
                Entry::Simp(widen(s, &ours))
            }
            Entry::Fact(f) => {
                // Ours may declare the factor keyword several times under different conditions (one
                // ZONE per FORMULATION): the one under the same conditions, else all of them.
                let ours: Vec<(&Vec<&Cond>, &Fact)> = hs
                    .iter()
                    .filter_map(|(c, x)| match x {
                        Entry::Fact(o) if o.name == f.name => Some((c, o)),
                        _ => None,
                    })
                    .collect();
                let same: Vec<&Fact> = ours
                    .iter()
                    .filter(|(c, _)| c.iter().map(|c| c.to_string()).eq(conds.iter().cloned()))
                    .map(|(_, o)| *o)
                    .collect();
                let chosen: Vec<&Fact> = if same.is_empty() { ours.iter().map(|(_, o)| *o).collect() } else { same };
                if chosen.is_empty() {
                    return e.clone();
                }
                let mut m = f.clone();
                let their: Vec<Entry> = chosen.iter().flat_map(|o| o.entries.iter().cloned()).collect();
                m.entries = merge_level(&their, &f.entries);
                for o in &chosen {
                    m.max = match (m.max, o.max) {
                        (Some(a), Some(b)) => Some(a.max(b)),
                        _ => None,
                    };
                }
                Entry::Fact(m)
            }
            Entry::Bloc(b) => {
                conds.push(b.cond.to_string());
                let entries = merge_entries(&b.entries, hs, conds);
                conds.pop();
                Entry::Bloc(Bloc { cond: b.cond.clone(), entries, rules: b.rules.clone() })
            }
        })
        .collect()
}

/// Code_Aster's simple keyword, accepting also the types and values our declarations accept.
fn widen(g: &Simp, ours: &[&Simp]) -> Simp {
    let mut s = g.clone();
    if ours.is_empty() {
        return s;
    }
    let mut kinds: Vec<ConceptKind> = Vec::new();
    let mut had_co = false;
    for t in g.types.iter().chain(ours.iter().flat_map(|o| o.types.iter())) {
        match t {
            Ty::Co(k) => {
                had_co = true;
                for x in k.iter() {
                    if !kinds.contains(x) {
                        kinds.push(*x);
                    }
                }
            }
            t if !s.types.contains(t) => s.types.push(t.clone()),
            _ => {}
        }
    }
    if had_co {
        s.types.retain(|t| !matches!(t, Ty::Co(_)));
        s.types.insert(0, Ty::Co(Box::leak(kinds.into_boxed_slice())));
    }
    s.allowed = match &g.allowed {
        None => None,
        Some(a) => {
            let mut all = a.clone();
            let mut open = false;
            for o in ours {
                match &o.allowed {
                    None => open = true,
                    Some(b) => {
                        for x in b {
                            if !all.contains(x) {
                                all.push(x.clone());
                            }
                        }
                    }
                }
            }
            (!open).then_some(all)
        }
    };
    for o in ours {
        s.max = match (s.max, o.max) {
            (Some(a), Some(b)) => Some(a.max(b)),
            _ => None,
        };
        s.min = s.min.min(o.min);
        s.val_min = match (s.val_min, o.val_min) {
            (Some(a), Some(b)) => Some(a.min(b)),
            _ => None,
        };
        s.val_max = match (s.val_max, o.val_max) {
            (Some(a), Some(b)) => Some(a.max(b)),
            _ => None,
        };
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kws;

    #[test]
    fn ours_widens_code_asters() {
        let g = Command::new("X", "").kw(kws![
            simp("A").txt().o().one_of(&["P", "Q"]),
            fact("F", kws![simp("B").r()]).many(),
            bloc(eq("A", "P"), kws![simp("C").i()]),
        ]);
        let h = Command::new("X", "ours").kw(kws![
            simp("A").txt().one_of(&["P", "OLD"]),
            fact("F", kws![simp("B").r(), simp("B_OLD").r()]),
            simp("D").txt(),
        ]);
        let m = merge(&h, &g);
        let text = super::super::generated::write(&m);
        assert!(text.contains("s A o T into='P','Q','OLD'"), "{text}");
        assert!(text.contains("s B_OLD f R"), "{text}");
        assert!(text.contains("b (eq A 'P') {\n    s C f I"), "{text}");
        assert!(text.contains("s D f T"), "{text}");
        assert_eq!(m.doc, "ours");
    }
}
