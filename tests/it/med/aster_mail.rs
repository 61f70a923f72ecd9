//! LIRE_MAILLAGE FORMAT='ASTER': every `.mail` mesh of Code_Aster's 2025 verification corpus
//! (../shared/corpus/astest-2025) is read, or refused by name for a section we do not read yet; the
//! counts are printed. Skips with a message where the corpus is absent.

use aster::mesh::aster_text;

#[test]
fn every_corpus_mail_file_reads_or_is_refused_by_name() {
    let dir = crate::common::root().join("../shared/corpus/astest-2025");
    let Ok(entries) = std::fs::read_dir(&dir) else {
        eprintln!("SKIPPED: {} is absent", dir.display());
        return;
    };
    let mut files: Vec<_> =
        entries.map(|e| e.unwrap().path()).filter(|p| p.extension().is_some_and(|x| x == "mail")).collect();
    files.sort();
    let (mut ok, mut nodes, mut cells) = (0, 0, 0);
    let mut refused: std::collections::BTreeMap<String, usize> = Default::default();
    let mut broken = Vec::new();
    for f in &files {
        let src = String::from_utf8_lossy(&std::fs::read(f).unwrap()).into_owned();
        let name = f.file_name().unwrap().to_string_lossy().into_owned();
        match aster_text::read(&src, &name) {
            Ok(m) => {
                ok += 1;
                nodes += m.nnodes();
                cells += m.ncells();
                // Every cell has its type's node count and every group member is an entity.
                for (c, t) in m.cells.iter().zip(&m.cell_types) {
                    assert_eq!(c.len(), t.nnodes(), "{name}");
                }
            }
            Err(e) if e.contains("is not supported") => {
                let what = e.split(": ").nth(1).unwrap_or(&e).to_string();
                *refused.entry(what).or_default() += 1;
            }
            Err(e) => broken.push(e),
        }
    }
    println!("aster_mail: {} files, {ok} read ({nodes} nodes, {cells} cells), refused: {refused:?}", files.len());
    assert!(broken.is_empty(), "{} of {} files fail to read:\n{}", broken.len(), files.len(), broken.join("\n"));
    assert!(ok * 10 >= files.len() * 9, "fewer than 90 % of the .mail files read: {ok} of {}", files.len());
}
