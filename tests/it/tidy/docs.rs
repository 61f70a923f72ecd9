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
