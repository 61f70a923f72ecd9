//! MED I/O throughput on a generated HEXA20 box of about 1 M nodes:
//! `med::write_mesh` and `med::read_mesh` (best of 3, MB/s of the file),
//! then the two big datasets (`NOE/COO`, `MAI/H20/NOD`) read raw through the
//! `hdf5` crate and through h5py (Debian `python3-h5py`, run with
//! /usr/bin/python3) in the same run, and the ratios.
//! Run: `cargo bench --bench med_io`. `BENCH_N=40` makes a smaller box.

use aster::mesh::generate::box_mesh;
use aster::mesh::CellType;
use hdf5_metno as hdf5;
use std::process::Command;
use std::time::Instant;

const ROUNDS: usize = 3;

fn best<T>(mut f: impl FnMut() -> T) -> (f64, T) {
    let mut out = None;
    let mut t = f64::INFINITY;
    for _ in 0..ROUNDS {
        let t0 = Instant::now();
        let v = f();
        t = t.min(t0.elapsed().as_secs_f64());
        out = Some(v);
    }
    (t, out.unwrap())
}

const STEP: &str = "-0000000000000000001-0000000000000000001";

const H5PY: &str = r#"
import sys, time, h5py
path, mesh, rounds = sys.argv[1], sys.argv[2], int(sys.argv[3])
step = "-0000000000000000001-0000000000000000001"
best = float("inf")
for _ in range(rounds):
    t0 = time.perf_counter()
    with h5py.File(path, "r") as f:
        coo = f[f"ENS_MAA/{mesh}/{step}/NOE/COO"][...]
        nod = f[f"ENS_MAA/{mesh}/{step}/MAI/H20/NOD"][...]
    best = min(best, time.perf_counter() - t0)
print(best, coo.nbytes + nod.nbytes)
"#;

fn main() {
    let n: usize = std::env::var("BENCH_N").ok().and_then(|s| s.parse().ok()).unwrap_or(62);
    let t0 = Instant::now();
    let mesh = box_mesh(CellType::Hexa20, &[n, n, n], &[1.0, 1.0, 1.0]).expect("box");
    let tgen = t0.elapsed().as_secs_f64();
    println!(
        "HEXA20 box {n}x{n}x{n}: {} nodes, {} cells ({} HEXA20), generated in {tgen:.2} s",
        mesh.nnodes(),
        mesh.ncells(),
        n * n * n
    );
    let dir = std::env::temp_dir().join(format!("aster-rs-bench-med-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("box.med");

    let (tw, _) = best(|| aster::med::write_mesh(&path, &mesh, "BOX").expect("write"));
    let size = std::fs::metadata(&path).unwrap().len() as f64;
    let mb = size / 1e6;
    println!("file: {mb:.1} MB");
    println!("write_mesh: {tw:.3} s  {:.0} MB/s", mb / tw);
    let (tr, back) = best(|| aster::med::read_mesh(&path, Some("BOX")).expect("read"));
    assert_eq!(back.nnodes(), mesh.nnodes());
    assert_eq!(back.cells, mesh.cells);
    println!("read_mesh:  {tr:.3} s  {:.0} MB/s", mb / tr);
    drop(back);

    // The two big datasets, raw, through the hdf5 crate.
    let (traw, bytes) = best(|| {
        let f = hdf5::File::open(&path).expect("open");
        let coo = f.dataset(&format!("ENS_MAA/BOX/{STEP}/NOE/COO")).unwrap().read_raw::<f64>().unwrap();
        let nod = f.dataset(&format!("ENS_MAA/BOX/{STEP}/MAI/H20/NOD")).unwrap().read_raw::<i32>().unwrap();
        coo.len() * 8 + nod.len() * 4
    });
    let dmb = bytes as f64 / 1e6;
    println!("datasets NOE/COO + MAI/H20/NOD: {dmb:.1} MB");
    println!("  hdf5 crate raw: {traw:.3} s  {:.0} MB/s", dmb / traw);

    let py =
        Command::new("/usr/bin/python3").arg("-c").arg(H5PY).arg(&path).arg("BOX").arg(ROUNDS.to_string()).output();
    match py {
        Ok(o) if o.status.success() => {
            let s = String::from_utf8_lossy(&o.stdout);
            let mut w = s.split_whitespace();
            let th: f64 = w.next().and_then(|x| x.parse().ok()).expect("h5py time");
            let hb: f64 = w.next().and_then(|x| x.parse().ok()).expect("h5py bytes");
            assert_eq!(hb as usize, bytes, "h5py read other sizes");
            println!("  h5py:           {th:.3} s  {:.0} MB/s", dmb / th);
            println!("ratio hdf5 crate raw / h5py (same datasets): {:.2}", traw / th);
            println!(
                "ratio read_mesh (whole mesh: names, families, groups, permutation) / h5py (2 datasets): {:.2}",
                tr / th
            );
        }
        Ok(o) => println!("SKIPPED h5py: {}", String::from_utf8_lossy(&o.stderr).lines().last().unwrap_or("")),
        Err(e) => println!("SKIPPED h5py: /usr/bin/python3: {e}"),
    }
    let _ = std::fs::remove_dir_all(&dir);
}
