//! docs/SUPPORTED.md is generated from the catalogue and must stay in step with it.

#[test]
fn supported_md_is_up_to_date() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/SUPPORTED.md");
    let want = aster::catalog::catalogue().markdown(&|n| aster::stages::stage(n).is_some());
    let have = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        have == want,
        "docs/SUPPORTED.md is out of date: regenerate it with\n  cargo run -- catalog --markdown > docs/SUPPORTED.md"
    );
}

/// The rows of the markdown table that follows `heading` in `text`: its cells, trimmed.
fn table_after(text: &str, heading: &str) -> Vec<Vec<String>> {
    let start = text.find(heading).unwrap_or_else(|| panic!("tests/README.md has no section '{heading}'"));
    text[start..]
        .lines()
        .skip_while(|l| !l.starts_with('|'))
        .take_while(|l| l.starts_with('|'))
        .skip(2)
        .map(|l| l.trim_matches('|').split('|').map(|c| c.trim().to_string()).collect())
        .collect()
}

#[test]
fn tests_readme_maps_every_command_and_legacy_case() {
    let readme = std::fs::read_to_string(crate::common::root().join("tests/README.md")).unwrap();
    let commands = table_after(&readme, "## Commands and their tests");
    let catalogue = aster::catalog::catalogue();
    let running: Vec<&str> = catalogue.names().into_iter().filter(|n| aster::stages::stage(n).is_some()).collect();
    for name in &running {
        let row = commands.iter().find(|r| r[0] == *name);
        let row = row.unwrap_or_else(|| panic!("tests/README.md: {name} runs but has no row"));
        assert!(row[1..].iter().any(|c| c != "—"), "tests/README.md: no test exercises {name}");
    }
    for row in &commands {
        assert!(running.contains(&row[0].as_str()), "tests/README.md: {} does not run (yet)", row[0]);
    }
    let Some(dir) = crate::common::astest_dir() else { return };
    let cases = table_after(&readme, "## Legacy cases and their tests");
    let passing = std::fs::read_to_string(crate::common::root().join("tests/passing.txt")).unwrap();
    let passing: Vec<(&str, &str)> = passing
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| {
            let mut w = l.split_whitespace();
            (w.next().unwrap(), w.next().unwrap_or(""))
        })
        .collect();
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "export") {
            let case = p.file_stem().unwrap().to_string_lossy().to_string();
            let row = cases.iter().find(|r| r[0] == case);
            let row = row.unwrap_or_else(|| panic!("tests/README.md: legacy case {case} has no row"));
            let want = match passing.iter().find(|p| p.0 == case) {
                Some((_, ok)) => format!("passing, {ok} OK"),
                None => "stops (the conformance table says where)".to_string(),
            };
            assert_eq!(row[2], want, "tests/README.md: the state of {case} disagrees with tests/passing.txt");
        }
    }
}

/// docs/ARCHITECTURE.md's code map has a section for every top-level module of src/ (a `### ` heading that
/// names `src/<module>/` or `src/<module>.rs`), so a new library cannot land undescribed.
#[test]
fn architecture_md_describes_every_top_level_module() {
    let root = crate::common::root();
    let doc = std::fs::read_to_string(root.join("docs/ARCHITECTURE.md")).unwrap();
    let headings: Vec<&str> = doc.lines().filter(|l| l.starts_with("### ")).collect();
    let mut missing = Vec::new();
    for entry in std::fs::read_dir(root.join("src")).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        if name == "lib.rs" {
            continue;
        }
        let named = if name.ends_with(".rs") { format!("`src/{name}`") } else { format!("`src/{name}/`") };
        if !headings.iter().any(|h| h.contains(&named)) {
            missing.push(named);
        }
    }
    missing.sort();
    assert!(missing.is_empty(), "docs/ARCHITECTURE.md has no code-map section for {}", missing.join(", "));
}
