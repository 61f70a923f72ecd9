//! Parse and validate the 34 command files of ../shared/astest, repeatedly;
//! report files per second for parsing alone and for the full `aster check`
//! (parse, run the Python, validate every command call against the catalogue).
//! Run: `cargo bench --bench parse`. Skips where ../shared is absent.

use std::path::{Path, PathBuf};
use std::time::Instant;

fn main() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/astest");
    let Ok(rd) = std::fs::read_dir(&dir) else {
        println!("SKIPPED: {} is absent", dir.display());
        return;
    };
    let mut files: Vec<PathBuf> = rd
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().map(|x| x == "comm").unwrap_or(false))
        .collect();
    files.sort();
    let texts: Vec<String> =
        files.iter().map(|p| String::from_utf8_lossy(&std::fs::read(p).unwrap()).into_owned()).collect();
    let bytes: usize = texts.iter().map(|t| t.len()).sum();
    let rounds = std::env::var("BENCH_ROUNDS").ok().and_then(|s| s.parse().ok()).unwrap_or(20);

    // Warm-up (also builds the catalogue once).
    for f in &files {
        aster::runner::check_file(f).expect("check");
    }

    let t0 = Instant::now();
    for _ in 0..rounds {
        for t in &texts {
            std::hint::black_box(aster::syntax::parse_module(t).expect("parse"));
        }
    }
    let parse = t0.elapsed().as_secs_f64();

    let t0 = Instant::now();
    for _ in 0..rounds {
        for f in &files {
            std::hint::black_box(aster::runner::check_file(f).expect("check"));
        }
    }
    let check = t0.elapsed().as_secs_f64();

    let n = (files.len() * rounds) as f64;
    println!("files: {} ({} KiB), rounds: {rounds}", files.len(), bytes / 1024);
    println!(
        "parse only:             {:>9.0} files/s  {:>7.2} MiB/s",
        n / parse,
        (bytes * rounds) as f64 / parse / 1048576.0
    );
    println!(
        "parse + check (catalog): {:>8.0} files/s  {:>7.2} MiB/s",
        n / check,
        (bytes * rounds) as f64 / check / 1048576.0
    );
    println!("ratio check / parse time: {:.2}", check / parse);
}
