//! The architecture test, in the manner of rust-analyzer's tidy tests: it reads the `use crate::…`
//! edges of `src/` and fails when a module uses what docs/ARCHITECTURE.md says it must not know.
//!
//! The rules live in the document, not here: the table under "### Layers" lists, for each top-level
//! module, the modules it may use; the lists under "### Stages" name the shared floor of `stages` and
//! its command families. A family uses only the floor (never another family), the floor never uses a
//! family, and every command's schema file and stage are of the same family.

use crate::common::*;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Every `.rs` file below `dir`, with its module path (`["stages", "print", "med"]`).
fn sources(dir: &Path) -> Vec<(Vec<String>, String)> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "rs") {
                let rel = p.strip_prefix(dir).unwrap();
                let mut m: Vec<String> =
                    rel.iter().map(|c| c.to_string_lossy().trim_end_matches(".rs").to_string()).collect();
                if m.last().is_some_and(|l| l == "mod" || l == "lib" || l == "main") {
                    m.pop();
                }
                out.push((m, std::fs::read_to_string(&p).unwrap()));
            }
        }
    }
    out.sort();
    out
}

/// The non-test code of a file: everything before its first `#[cfg(test)]`.
fn code(text: &str) -> &str {
    text.find("#[cfg(test)]").map_or(text, |i| &text[..i])
}

/// The module paths a file's code names: `crate::a::b…`, and `super::`/`self::` resolved against the
/// file's own module path. Globs of test modules (`super::*`) are not edges.
fn edges(module: &[String], text: &str) -> BTreeSet<Vec<String>> {
    let mut out = BTreeSet::new();
    let src = code(text);
    let bytes = src.as_bytes();
    let ident = |c: u8| c.is_ascii_alphanumeric() || c == b'_';
    let mut i = 0;
    while i < bytes.len() {
        if !src.is_char_boundary(i) {
            i += 1;
            continue;
        }
        let at_word = i == 0 || !ident(bytes[i - 1]);
        let rest = &src[i..];
        let (base, skip): (Vec<String>, usize) = if at_word && rest.starts_with("crate::") {
            (Vec::new(), 7)
        } else if at_word && rest.starts_with("super::") {
            let mut b = module.to_vec();
            b.pop();
            (b, 7)
        } else {
            i += 1;
            continue;
        };
        let mut path = base;
        let mut j = i + skip;
        while skip == 7 && src[i..].starts_with("super::") && src[j..].starts_with("super::") {
            path.pop();
            j += 7;
        }
        loop {
            let start = j;
            while j < bytes.len() && ident(bytes[j]) {
                j += 1;
            }
            if start == j {
                break;
            }
            path.push(src[start..j].to_string());
            if src[j..].starts_with("::") {
                j += 2;
            } else {
                break;
            }
        }
        // `super::{a, b}` and `crate::x::{…}`: the brace list names items of the path.
        if src[j..].starts_with('{') {
            let end = src[j..].find('}').map_or(src.len(), |e| j + e);
            for item in src[j + 1..end].split(',') {
                let name: String = item.trim().chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
                if !name.is_empty() && name != "self" {
                    let mut p = path.clone();
                    p.push(name);
                    out.insert(p);
                }
            }
        }
        if !path.is_empty() {
            out.insert(path);
        }
        i = j.max(i + 1);
    }
    out
}

/// The rules of docs/ARCHITECTURE.md.
struct Rules {
    /// Top-level module → the top-level modules it may use.
    layers: BTreeMap<String, BTreeSet<String>>,
    /// `stages`' shared floor and its command families.
    floor: BTreeSet<String>,
    families: BTreeSet<String>,
}

fn rules(doc: &str) -> Rules {
    let section = |title: &str| -> &str {
        let i = doc.find(title).unwrap_or_else(|| panic!("docs/ARCHITECTURE.md has no '{title}' section"));
        let rest = &doc[i + title.len()..];
        &rest[..rest.find("\n#").unwrap_or(rest.len())]
    };
    let mut layers = BTreeMap::new();
    for line in section("### Layers").lines().filter(|l| l.starts_with("| `")) {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        let names = |c: &str| -> BTreeSet<String> {
            c.split(',').map(|s| s.trim().trim_matches('`').to_string()).filter(|s| !s.is_empty() && s != "—").collect()
        };
        layers.insert(cells[1].trim_matches('`').to_string(), names(cells[2]));
    }
    let list = |title: &str| -> BTreeSet<String> {
        let s = section("### Stages");
        let line = s.lines().find(|l| l.starts_with(title)).unwrap_or_else(|| panic!("no '{title}' line under Stages"));
        line[title.len()..].split(',').map(|n| n.trim().trim_matches(|c| c == '`' || c == '.').to_string()).collect()
    };
    Rules { layers, floor: list("Shared floor:"), families: list("Families:") }
}

/// Every violation of the rules by the files given.
fn violations(rules: &Rules, files: &[(Vec<String>, String)]) -> Vec<String> {
    let mut out = Vec::new();
    for (m, text) in files {
        let Some(top) = m.first() else { continue };
        let Some(allowed) = rules.layers.get(top) else {
            out.push(format!("src/{}: module `{top}` is not in the Layers table", m.join("/")));
            continue;
        };
        for e in edges(m, text) {
            let Some(target) = e.first() else { continue };
            if target != top && !allowed.contains(target) && rules.layers.contains_key(target) {
                out.push(format!("{} uses {} (`{top}` must not know `{target}`)", m.join("::"), e.join("::")));
            }
            // Inside stages: families use only the floor; the floor uses no family.
            if top == "stages" && target == "stages" && m.len() >= 2 && e.len() >= 2 {
                let (from, to) = (&m[1], &e[1]);
                if from == to {
                    continue;
                }
                let from_family = rules.families.contains(from);
                let to_family = rules.families.contains(to);
                if to_family && (from_family || rules.floor.contains(from)) {
                    out.push(format!(
                        "{} uses {}: stage modules never use a command family",
                        m.join("::"),
                        e.join("::")
                    ));
                }
            }
        }
    }
    out
}

/// Command → family of its schema (`catalog/commands/<family>…`) and of its stage (`stages::stage`).
fn command_families(files: &[(Vec<String>, String)]) -> (BTreeMap<String, String>, BTreeMap<String, String>) {
    let mut schema = BTreeMap::new();
    for (m, text) in files {
        if m.len() >= 3 && m[0] == "catalog" && m[1] == "commands" {
            for part in text.split("Command::new(").skip(1) {
                let part = part.trim_start().trim_start_matches('"');
                let name = &part[..part.find('"').unwrap()];
                schema.insert(name.to_string(), m[2].clone());
            }
        }
    }
    let registry = &files.iter().find(|(m, _)| m == &["stages"]).expect("src/stages/mod.rs").1;
    let body = &registry[registry.find("pub fn stage(").expect("stages::stage")..];
    let mut stage = BTreeMap::new();
    for line in body.lines() {
        let Some((names, target)) = line.split_once("=>") else { continue };
        let family = target.trim().split("::").next().unwrap().to_string();
        for n in names.split('|') {
            let n = n.trim().trim_matches('"');
            if !n.is_empty() && n != "_" {
                stage.insert(n.to_string(), family.clone());
            }
        }
    }
    (schema, stage)
}

#[test]
fn modules_use_only_what_the_architecture_allows() {
    let doc = std::fs::read_to_string(root().join("docs/ARCHITECTURE.md")).unwrap();
    let r = rules(&doc);
    let files = sources(&root().join("src"));
    let v = violations(&r, &files);
    assert!(v.is_empty(), "architecture violations:\n  {}", v.join("\n  "));
    // Every top-level module and every stage module is named by the document.
    for (m, _) in &files {
        if m.len() >= 2 && m[0] == "stages" {
            assert!(
                r.floor.contains(&m[1]) || r.families.contains(&m[1]),
                "src/stages/{}: neither in the shared floor nor a family of docs/ARCHITECTURE.md",
                m[1]
            );
        }
    }
}

#[test]
fn every_command_has_its_schema_and_its_stage_in_one_family() {
    let doc = std::fs::read_to_string(root().join("docs/ARCHITECTURE.md")).unwrap();
    let r = rules(&doc);
    let files = sources(&root().join("src"));
    let (schema, stage) = command_families(&files);
    assert!(schema.len() >= 40, "schemas found: {}", schema.len());
    for (cmd, fam) in &stage {
        let s = schema.get(cmd).unwrap_or_else(|| panic!("{cmd} has a stage but no schema"));
        assert_eq!(s, fam, "{cmd}: schema in catalog/commands/{s}, stage in stages::{fam}");
        assert!(r.families.contains(fam), "{cmd}: family {fam} is not listed in docs/ARCHITECTURE.md");
    }
}

/// The checker is shown to fail once, on test-only edges: the import loop of the old tree (IMPR_RESU's
/// writer calling back into the mesh stage) and a library that reaches for concepts.
#[test]
fn a_test_only_forbidden_edge_is_caught() {
    let doc = std::fs::read_to_string(root().join("docs/ARCHITECTURE.md")).unwrap();
    let r = rules(&doc);
    let mut files = sources(&root().join("src"));
    let path = |s: &str| s.split('/').map(String::from).collect::<Vec<_>>();
    files.push((path("stages/print/extra"), "use super::super::mesh::describe;\n".into()));
    files.push((path("stages/mesh/extra"), "fn f() { crate::stages::print::impr_resu(); }".into()));
    files.push((path("xfem/extra"), "use crate::concepts::ConceptRef;".into()));
    files.push((path("stages/core/extra"), "use crate::stages::solve::statics;".into()));
    let v = violations(&r, &files);
    for want in [
        "stages::print::extra uses stages::mesh::describe",
        "stages::mesh::extra uses stages::print::impr_resu",
        "xfem::extra uses concepts::ConceptRef",
        "stages::core::extra uses stages::solve::statics",
    ] {
        assert!(v.iter().any(|l| l.starts_with(want)), "not caught: {want}\n{v:#?}");
    }
    assert_eq!(v.len(), 4, "{v:#?}");
    // `super::super::` climbs two levels.
    let m: Vec<String> = path("stages/print/extra");
    assert!(edges(&m, "use super::super::mesh::describe;").contains(&path("stages/mesh/describe")));
}

#[test]
fn edges_resolve_super_and_brace_lists() {
    let m: Vec<String> = ["stages", "print", "med"].iter().map(|s| s.to_string()).collect();
    let e = edges(&m, "use super::{list_of, selected_steps};\nuse crate::mesh::{CellType, Mesh};\nlet x = crate_x::y;");
    let got: Vec<String> = e.iter().map(|p| p.join("::")).collect();
    assert_eq!(
        got,
        [
            "mesh",
            "mesh::CellType",
            "mesh::Mesh",
            "stages::print",
            "stages::print::list_of",
            "stages::print::selected_steps"
        ]
    );
}

/// The files a file's code names (the module files its `crate::`/`super::` paths land in), itself excluded.
fn file_edges(files: &[(Vec<String>, String)]) -> BTreeMap<Vec<String>, BTreeSet<Vec<String>>> {
    let modules: BTreeSet<&Vec<String>> = files.iter().map(|(m, _)| m).collect();
    let mut out = BTreeMap::new();
    for (m, text) in files {
        let mut targets = BTreeSet::new();
        for e in edges(m, text) {
            // The longest prefix of the path that is a file of ours.
            let Some(k) = (1..=e.len()).rev().find(|&k| modules.contains(&e[..k].to_vec())) else { continue };
            if e[..k] != m[..] {
                targets.insert(e[..k].to_vec());
            }
        }
        out.insert(m.clone(), targets);
    }
    out
}

/// The import cycles among files: every strongly connected component of more than one file (Tarjan).
fn cycles(files: &[(Vec<String>, String)]) -> Vec<Vec<String>> {
    let graph = file_edges(files);
    let nodes: Vec<&Vec<String>> = graph.keys().collect();
    let index_of: BTreeMap<&Vec<String>, usize> = nodes.iter().enumerate().map(|(i, n)| (*n, i)).collect();
    let adj: Vec<Vec<usize>> =
        nodes.iter().map(|n| graph[*n].iter().filter_map(|t| index_of.get(t).copied()).collect()).collect();
    struct T {
        index: Vec<Option<usize>>,
        low: Vec<usize>,
        on: Vec<bool>,
        stack: Vec<usize>,
        next: usize,
        out: Vec<Vec<usize>>,
    }
    fn visit(v: usize, adj: &[Vec<usize>], t: &mut T) {
        t.index[v] = Some(t.next);
        t.low[v] = t.next;
        t.next += 1;
        t.stack.push(v);
        t.on[v] = true;
        for &w in &adj[v] {
            match t.index[w] {
                None => {
                    visit(w, adj, t);
                    t.low[v] = t.low[v].min(t.low[w]);
                }
                Some(iw) if t.on[w] => t.low[v] = t.low[v].min(iw),
                _ => {}
            }
        }
        if Some(t.low[v]) == t.index[v] {
            let mut comp = Vec::new();
            while let Some(w) = t.stack.pop() {
                t.on[w] = false;
                comp.push(w);
                if w == v {
                    break;
                }
            }
            if comp.len() > 1 {
                t.out.push(comp);
            }
        }
    }
    let n = nodes.len();
    let mut t =
        T { index: vec![None; n], low: vec![0; n], on: vec![false; n], stack: Vec::new(), next: 0, out: Vec::new() };
    for v in 0..n {
        if t.index[v].is_none() {
            visit(v, &adj, &mut t);
        }
    }
    let mut out: Vec<Vec<String>> = t
        .out
        .into_iter()
        .map(|c| {
            let mut names: Vec<String> = c.into_iter().map(|i| format!("src/{}", nodes[i].join("/"))).collect();
            names.sort();
            names
        })
        .collect();
    out.sort();
    out
}

/// No file of `src/` imports, through others, a file that imports it: every module reads as a
/// pipeline, each layer below the ones that use it.
#[test]
fn no_import_cycles() {
    let files = sources(&root().join("src"));
    let c = cycles(&files);
    assert!(
        c.is_empty(),
        "import cycles among files:\n  {}",
        c.iter().map(|c| c.join(" ↔ ")).collect::<Vec<_>>().join("\n  ")
    );
}

/// The cycle check is shown to fail once, on a test-only loop: a physics library that calls back into
/// the driver that uses it.
#[test]
fn a_test_only_import_cycle_is_caught() {
    let mut files = sources(&root().join("src"));
    let path = |s: &str| s.split('/').map(String::from).collect::<Vec<_>>();
    files.push((path("fem/extra_a"), "use super::extra_b::B;\n".into()));
    files.push((path("fem/extra_b"), "fn f() { crate::fem::extra_a::g(); }".into()));
    let c = cycles(&files);
    assert!(c.iter().any(|c| c == &["src/fem/extra_a", "src/fem/extra_b"]), "{c:#?}");
}

/// The keywords every solving command shares, read once into `stages::core::settings::Settings`.
const SHARED_SOLVING_KEYWORDS: [&str; 13] = [
    "MODELE",
    "CHAM_MATER",
    "EXCIT",
    "INCREMENT",
    "CONVERGENCE",
    "NEWTON",
    "SOLVEUR",
    "ARCHIVAGE",
    "ETAT_INIT",
    "COMPORTEMENT",
    "SCHEMA_THM",
    "CONTACT",
    "OPTION",
];

/// The lookups of a solving command's shared keywords made by the solving family's own files: each is
/// `file: lookup`. `Args` lookups are calls of a method on a keyword's name (`a.fact("EXCIT")`).
fn shared_keyword_lookups(files: &[(Vec<String>, String)]) -> Vec<String> {
    const LOOKUPS: [&str; 21] = [
        "get",
        "declares",
        "has",
        "given",
        "vals",
        "val",
        "text",
        "texts",
        "real",
        "reals",
        "int",
        "ints",
        "concept",
        "concepts",
        "facts",
        "fact",
        "req_text",
        "req_real",
        "req_concept",
        "concept_of",
        "has_if_declared",
    ];
    let mut out = Vec::new();
    for (m, text) in files {
        if m.len() < 2 || m[0] != "stages" || m[1] != "solve" {
            continue;
        }
        for kw in SHARED_SOLVING_KEYWORDS {
            for l in LOOKUPS {
                let call = format!(".{l}(\"{kw}\")");
                if code(text).contains(&call) {
                    out.push(format!("src/{}: {call}", m.join("/")));
                }
            }
        }
    }
    out
}

/// The physics seam: the solving stages (`stages/solve`) get their shared keywords typed from
/// `core::settings`, and never read them again. Shown to fail once on a test-only file.
#[test]
fn solving_stages_read_their_shared_keywords_through_the_settings() {
    let mut files = sources(&root().join("src"));
    assert!(shared_keyword_lookups(&files).is_empty(), "{:#?}", shared_keyword_lookups(&files));
    let settings = files.iter().find(|(m, _)| m.join("/") == "stages/core/settings").expect("core::settings");
    for kw in SHARED_SOLVING_KEYWORDS {
        assert!(code(&settings.1).contains(&format!("\"{kw}\"")), "core::settings does not read {kw}");
    }
    files.push((
        vec!["stages".into(), "solve".into(), "extra".into()],
        "fn f(a: &Args) { a.fact(\"CONVERGENCE\"); }".into(),
    ));
    assert_eq!(shared_keyword_lookups(&files), ["src/stages/solve/extra: .fact(\"CONVERGENCE\")"]);
}
