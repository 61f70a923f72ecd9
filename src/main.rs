//! The `aster` command line.

use aster::catalog::catalogue;
use aster::runner::export::Dir;
use aster::runner::{self, suite, RunOptions};
use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(name = "aster", version, about = "Run Code_Aster command files (.comm) and test cases (.export)")]
struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
}

#[derive(Subcommand)]
enum Cmd {
    /// Run a case: CASE.export, or CASE.comm with --unit mappings; with no case,
    /// the embedded demo scene (comm/junction_2d.comm), its outputs in ./aster-out.
    Run {
        case: Option<PathBuf>,
        /// Map a logical unit to a file: N=PATH (read if it exists, else written).
        #[arg(long = "unit", value_name = "N=PATH")]
        units: Vec<String>,
        /// Folder for the .mess and .resu files (default: the current folder; ./aster-out for the demo).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Do not echo the message file to stdout.
        #[arg(short, long)]
        quiet: bool,
        /// Write a machine-readable summary (used by `aster suite`).
        #[arg(long, hide = true)]
        summary: Option<PathBuf>,
        /// Stop the run with a located error past this many seconds (default: the .export's
        /// `P time_limit`, else no limit).
        #[arg(long, value_name = "SECONDS", value_parser = runner::export::parse_seconds)]
        time_limit: Option<std::time::Duration>,
    },
    /// Parse and validate command files against the catalogue; compute nothing.
    Check {
        #[arg(required = true)]
        files: Vec<PathBuf>,
    },
    /// Run every .export of a folder; one row per case and a JUnit XML report.
    Suite {
        dir: PathBuf,
        /// Cases run at once.
        #[arg(short = 'j', long, default_value_t = 1)]
        jobs: usize,
        /// Folder for per-case outputs (default: ./aster-suite).
        #[arg(long)]
        out: Option<PathBuf>,
        /// JUnit XML report path (default: OUT/junit.xml); stops.csv (what stops the cases), suite.json
        /// (every case and stop) and passing.txt (the cases that passed) go beside it.
        #[arg(long)]
        junit: Option<PathBuf>,
        /// Run only the cases this file lists (the first word of each line; `#` comments), as
        /// tests/passing.txt does.
        #[arg(long, value_name = "FILE")]
        list: Option<PathBuf>,
        /// Stops shown in the terminal summary.
        #[arg(long, default_value_t = 40)]
        top: usize,
        /// No progress bar.
        #[arg(short, long)]
        quiet: bool,
    },
    /// Meshes: summary of a file (MED, ASTER .mail, Gmsh .msh, GIBI .mgib, IDEAS .unv), conversion,
    /// structured box and ring generators.
    Mesh {
        #[command(subcommand)]
        action: MeshCmd,
    },
    /// Compare the meshes and every field of two MED files, node and cell
    /// fields (per field, step, kind of entity and component: max absolute
    /// and relative differences and where: node, cell, Gauss point, node of
    /// cell). Exit code 0 within tolerance, 1 beyond, 2 on error.
    Diff {
        a: PathBuf,
        b: PathBuf,
        /// Relative tolerance: |a-b| <= atol + rtol * max(|a|, |b|).
        #[arg(long, default_value_t = 1e-6)]
        rtol: f64,
        /// Absolute tolerance.
        #[arg(long, default_value_t = 1e-12)]
        atol: f64,
    },
    /// Run one case over a grid of variants and put error against cost:
    /// study.csv, study.md and log-log plots (SVG) in --out.
    Study {
        /// The case: CASE.comm (with --unit) or CASE.export.
        case: PathBuf,
        /// A knob: NAME=v1,v2,... overrides the top-level assignments
        /// `NAME = ...` of the command file and fills {NAME} in --mesh.
        #[arg(long = "set", value_name = "NAME=V1,V2,...")]
        knobs: Vec<String>,
        /// A generated mesh for a unit: 'UNIT=box --cell C --n NX,NY[,NZ]
        /// --size LX,LY[,LZ]' or 'UNIT=ring --cell C --n NR,NT[,NZ] --radii
        /// RI,RE [--height H]'; {NAME} takes a knob's value.
        #[arg(long = "mesh", value_name = "UNIT=SPEC")]
        meshes: Vec<String>,
        /// Map a logical unit to a file: N=PATH.
        #[arg(long = "unit", value_name = "N=PATH")]
        units: Vec<String>,
        /// Runs at once.
        #[arg(short = 'j', long, default_value_t = 1)]
        jobs: usize,
        /// Output folder (default: ./aster-study).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Error metric to plot: a POST_ERREUR option (DEPL_RELA, ENER_RELA,
        /// ...; DEPL_RELA#2 for the second call) or 'check' (the largest
        /// relative error of the ANALYTIQUE check lines). Default: all found.
        #[arg(long = "error")]
        errors: Vec<String>,
        /// A knob drawn as curves in the plots, one per setting of the
        /// other knobs (default: the knobs with the most values).
        #[arg(long = "curve")]
        curves: Vec<String>,
        /// Kill a run after this many seconds.
        #[arg(long)]
        time_limit: Option<f64>,
        /// Run each variant this many times and keep the fastest.
        #[arg(long, default_value_t = 1)]
        repeat: usize,
        /// Title of the plots (default: the case's name).
        #[arg(long)]
        title: Option<String>,
        /// No progress bar.
        #[arg(short, long)]
        quiet: bool,
    },
    /// Show the command catalogue.
    Catalog {
        /// Print docs/SUPPORTED.md.
        #[arg(long)]
        markdown: bool,
        /// Print the schema of command NAME (the format of src/catalog/generated.rs).
        #[arg(long, value_name = "NAME", conflicts_with = "markdown")]
        schema: Option<String>,
        /// With --schema: the hand-written schema of the command's stage, not the checked one.
        #[arg(long, requires = "schema")]
        hand_written: bool,
    },
}

#[derive(Subcommand)]
enum MeshCmd {
    /// Nodes, cells per type, groups with sizes and bounding box of the meshes of a file, read as
    /// LIRE_MAILLAGE reads it (the format from the extension: .med/.mmed/.rmed, .mail, .msh,
    /// .mgib, .unv/.msup; or --format).
    Info {
        file: PathBuf,
        /// Only this mesh of a MED file (default: every mesh of the file).
        #[arg(long)]
        mesh: Option<String>,
        /// MED, ASTER, GMSH, GIBI or IDEAS (default: from the extension).
        #[arg(long)]
        format: Option<String>,
        /// Also run LIRE_MAILLAGE's VERI_MAIL checks and list what they find.
        #[arg(long)]
        check: bool,
    },
    /// Convert a mesh of any format LIRE_MAILLAGE reads into MED (.med/.mmed/.rmed) or Code_Aster's
    /// text format (.mail), keeping its names, numbering and groups.
    Convert {
        input: PathBuf,
        output: PathBuf,
        /// Format of the input (default: from the extension).
        #[arg(long)]
        format: Option<String>,
        /// The mesh of a MED input (default: the first).
        #[arg(long)]
        mesh: Option<String>,
        /// Name of the mesh in the output (default: the input's mesh name, or its file stem).
        #[arg(long)]
        name: Option<String>,
    },
    /// Write a structured box mesh with named boundary groups (2D: edge
    /// groups BAS, DROITE, HAUT, GAUCHE and cell group SURFACE; 3D: face
    /// groups XMIN, XMAX, YMIN, YMAX, ZMIN, ZMAX and cell group VOLUME;
    /// each boundary name is both a cell group and a node group).
    Box {
        /// QUAD4, QUAD8, TRIA3, TRIA6 (two per quadrangle), HEXA8, HEXA20,
        /// TETRA4, TETRA10 (six per hexahedron), PENTA6 or PENTA15 (two per
        /// hexahedron).
        #[arg(long)]
        cell: String,
        /// Cells per axis (quadrangles or hexahedra): NX,NY[,NZ].
        #[arg(long, value_delimiter = ',', required = true)]
        n: Vec<usize>,
        /// Box lengths: LX,LY[,LZ].
        #[arg(long, value_delimiter = ',', required = true)]
        size: Vec<f64>,
        /// Output MED file.
        #[arg(short = 'o', long)]
        output: PathBuf,
        /// Mesh name in the file.
        #[arg(long, default_value = "MAIL")]
        name: String,
        /// Move every vertex by up to this fraction of the cell size along each axis (nodes on a face
        /// of the box stay on it): general, non-affine cells.
        #[arg(long, default_value_t = 0.0)]
        distort: f64,
        /// Move every mid-edge node off the middle of its ends by up to this fraction of the cell size
        /// along each axis: curved quadratic edges.
        #[arg(long, default_value_t = 0.0)]
        bend: f64,
        /// Seed of the random moves.
        #[arg(long, default_value_t = 1)]
        seed: u64,
    },
    /// Write a quarter of a thick ring (2D: QUAD4, QUAD8) or of a thick-walled
    /// cylinder (3D: HEXA8, HEXA20) on the circles of radii RI and RE, with
    /// the groups INT (r = RI), EXT (r = RE), BAS (y = 0), GAUCHE (x = 0) and
    /// SURFACE, or ZMIN, ZMAX and VOLUME in 3D.
    Ring {
        #[arg(long)]
        cell: String,
        /// Cells: radial, circumferential[, axial].
        #[arg(long, value_delimiter = ',', required = true)]
        n: Vec<usize>,
        /// RI,RE.
        #[arg(long, value_delimiter = ',', required = true)]
        radii: Vec<f64>,
        /// Height (3D).
        #[arg(long)]
        height: Option<f64>,
        #[arg(short = 'o', long)]
        output: PathBuf,
        #[arg(long, default_value = "MAIL")]
        name: String,
    },
}

/// The meshes of a file as LIRE_MAILLAGE reads them, with their names: every mesh of a MED file (or
/// only `only`), the one mesh of a text file (named after the file).
fn read_meshes(
    file: &std::path::Path,
    format: Option<&str>,
    only: Option<&str>,
) -> Result<Vec<(String, aster::mesh::Mesh)>, aster::diag::Error> {
    use aster::diag::Error;
    let ext = file.extension().and_then(|e| e.to_str()).unwrap_or("");
    let format = match format {
        Some(f) => f.to_ascii_uppercase(),
        None if matches!(ext.to_ascii_lowercase().as_str(), "med" | "mmed" | "rmed") => "MED".to_string(),
        None => match aster::mesh::TextFormat::from_extension(ext) {
            Some(aster::mesh::TextFormat::Aster) => "ASTER".into(),
            Some(aster::mesh::TextFormat::Gmsh) => "GMSH".into(),
            Some(aster::mesh::TextFormat::Gibi) => "GIBI".into(),
            Some(aster::mesh::TextFormat::Ideas { .. }) => "IDEAS".into(),
            None => {
                return Err(Error::runtime(format!(
                    "{}: which format? Give --format MED, ASTER, GMSH, GIBI or IDEAS",
                    file.display()
                )))
            }
        },
    };
    if format == "MED" {
        let names = match only {
            Some(m) => vec![m.to_string()],
            None => aster::med::list_meshes(file)?,
        };
        if names.is_empty() {
            return Err(Error::io(format!("MED file {}: contains no mesh", file.display())));
        }
        return names.into_iter().map(|n| aster::med::read_mesh(file, Some(&n)).map(|m| (n, m))).collect();
    }
    let text = aster::mesh::TextFormat::from_keyword(&format)
        .ok_or_else(|| Error::runtime(format!("--format {format}: expected MED, ASTER, GMSH, GIBI or IDEAS")))?;
    let bytes = std::fs::read(file).map_err(|e| Error::io(format!("{}: {e}", file.display())))?;
    let name = file.file_name().map(|f| f.to_string_lossy().into_owned()).unwrap_or_default();
    let m = text.read(&String::from_utf8_lossy(&bytes), &name).map_err(Error::io)?;
    let stem = file.file_stem().map(|f| f.to_string_lossy().into_owned()).unwrap_or_default();
    Ok(vec![(stem, m)])
}

fn mesh_command(action: MeshCmd) -> Result<(), aster::diag::Error> {
    match action {
        MeshCmd::Info { file, mesh, format, check } => {
            let meshes = read_meshes(&file, format.as_deref(), mesh.as_deref())?;
            println!("file {}", file.display());
            for (n, m) in meshes {
                print!("{}", m.describe(&n));
                if check {
                    let r = aster::mesh::check::check(&m, 1e-3);
                    if r.alarms.is_empty() && r.errors.is_empty() {
                        println!("  VERI_MAIL: nothing to report");
                    }
                    for a in &r.alarms {
                        println!("  VERI_MAIL <A>: {a}");
                    }
                    for e in &r.errors {
                        println!("  VERI_MAIL <E>: {e}");
                    }
                }
            }
            Ok(())
        }
        MeshCmd::Convert { input, output, format, mesh, name } => {
            let meshes = read_meshes(&input, format.as_deref(), mesh.as_deref())?;
            let (found, m) = meshes.into_iter().next().expect("read_meshes returns at least one mesh");
            let name = name.unwrap_or(found);
            let ext = output.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
            match ext.as_str() {
                "med" | "mmed" | "rmed" => aster::med::write_mesh(&output, &m, &name)?,
                "mail" => std::fs::write(&output, aster::mesh::aster_text::write(&m, &name))
                    .map_err(|e| aster::diag::Error::io(format!("{}: {e}", output.display())))?,
                _ => {
                    return Err(aster::diag::Error::runtime(format!(
                        "{}: the output must be a MED file (.med, .mmed, .rmed) or a .mail file",
                        output.display()
                    )))
                }
            }
            println!("wrote {}", output.display());
            print!("{}", m.describe(&name));
            Ok(())
        }
        MeshCmd::Box { cell, n, size, output, name, distort, bend, seed } => {
            let t = aster::mesh::CellType::from_name(&cell.to_ascii_uppercase()).ok_or_else(|| {
                aster::diag::Error::runtime(format!("--cell {cell}: expected {}", aster::mesh::generate::BOX_CELLS))
            })?;
            let mut m = aster::mesh::generate::box_mesh(t, &n, &size)?;
            if distort != 0.0 || bend != 0.0 {
                let d = aster::mesh::generate::Distortion { shift: distort, bend, seed };
                aster::mesh::generate::distort(&mut m, &n, &size, d)?;
                let bad = aster::fem::geometry::inverted_cells(&m);
                if let Some(&c) = bad.first() {
                    return Err(aster::diag::Error::runtime(format!(
                        "--distort {distort} --bend {bend} --seed {seed}: {} cells are inverted (the first: {}); \
                         take smaller moves",
                        bad.len(),
                        m.cell_names[c]
                    )));
                }
            }
            aster::med::write_mesh(&output, &m, &name)?;
            println!("wrote {}", output.display());
            print!("{}", m.describe(&name));
            Ok(())
        }
        MeshCmd::Ring { cell, n, radii, height, output, name } => {
            let t = aster::mesh::CellType::from_name(&cell.to_ascii_uppercase()).ok_or_else(|| {
                aster::diag::Error::runtime(format!("--cell {cell}: expected QUAD4, QUAD8, HEXA8 or HEXA20"))
            })?;
            let [ri, re] = radii[..] else {
                return Err(aster::diag::Error::runtime("--radii: expected RI,RE"));
            };
            let m = aster::mesh::generate::ring_mesh(t, &n, [ri, re], height)?;
            aster::med::write_mesh(&output, &m, &name)?;
            println!("wrote {}", output.display());
            print!("{}", m.describe(&name));
            Ok(())
        }
    }
}

#[allow(clippy::too_many_arguments)]
fn study_command(
    case: PathBuf,
    knobs: Vec<String>,
    meshes: Vec<String>,
    units: Vec<String>,
    jobs: usize,
    out: Option<PathBuf>,
    (errors, curves): (Vec<String>, Vec<String>),
    (time_limit, repeat): (Option<f64>, usize),
    title: Option<String>,
    quiet: bool,
) -> ExitCode {
    use aster::study::{self, grid};
    let parsed = (|| -> Result<study::StudyOptions, String> {
        let title =
            title.unwrap_or_else(|| case.file_stem().map(|s| s.to_string_lossy().to_string()).unwrap_or_default());
        Ok(study::StudyOptions {
            knobs: knobs.iter().map(|k| grid::Knob::parse(k)).collect::<Result<_, _>>()?,
            meshes: meshes.iter().map(|m| grid::MeshSpec::parse(m)).collect::<Result<_, _>>()?,
            units: units.iter().map(|u| parse_unit(u).map(|(n, p, _)| (n, p))).collect::<Result<_, _>>()?,
            case,
            jobs,
            out: out.unwrap_or_else(|| PathBuf::from("aster-study")),
            errors,
            curves,
            time_limit,
            repeat,
            progress: !quiet,
            title,
        })
    })();
    let opts = match parsed {
        Ok(o) => o,
        Err(e) => {
            eprintln!("aster: {e}");
            return ExitCode::from(2);
        }
    };
    let exe = match std::env::current_exe() {
        Ok(e) => e,
        Err(e) => {
            eprintln!("aster: {e}");
            return ExitCode::from(2);
        }
    };
    match study::run_study(&exe, &opts) {
        Ok(s) => {
            print!("{}\n{}", study::report::markdown(&s), study::report::pareto_summary(&s));
            for p in &s.written {
                println!("wrote {}", p.display());
            }
            if !s.runs.iter().any(|r| study::report::stopped(&r.metrics)) {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(1)
            }
        }
        Err(e) => {
            eprintln!("aster: {e}");
            ExitCode::from(2)
        }
    }
}

fn parse_unit(s: &str) -> Result<(i64, PathBuf, Dir), String> {
    let (u, p) = s.split_once('=').ok_or_else(|| format!("--unit '{s}': expected N=PATH"))?;
    let u: i64 = u.trim().parse().map_err(|_| format!("--unit '{s}': '{u}' is not a unit number"))?;
    let path = PathBuf::from(p);
    let dir = if path.exists() { Dir::InOut } else { Dir::Out };
    Ok((u, path, dir))
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.cmd {
        Cmd::Run { case, units, out, quiet, summary, time_limit } => {
            let units = match units.iter().map(|u| parse_unit(u)).collect::<Result<Vec<_>, _>>() {
                Ok(u) => u,
                Err(e) => {
                    eprintln!("aster: {e}");
                    return ExitCode::from(2);
                }
            };
            // The demo writes in a folder of its own, not among the user's files.
            let out = if case.is_none() { Some(out.unwrap_or_else(|| PathBuf::from("aster-out"))) } else { out };
            let opts = RunOptions { out_dir: out, units, echo: !quiet };
            // The runner catches panics of the interpreter and the stages with their location; this
            // catches one of the runner itself (reading units, delivering results).
            let case = match &case {
                None => runner::Case::Demo,
                Some(c) if c.extension().map(|e| e == "export").unwrap_or(false) => runner::Case::Export(c),
                Some(c) => runner::Case::Comm(c),
            };
            let outcome = runner::guard::catch(|| runner::run(case, &opts, time_limit));
            let outcome = match outcome {
                Ok(o) => o,
                Err(panic) => {
                    eprintln!("<F> {}", aster::diag::Error::internal(&panic));
                    return ExitCode::from(2);
                }
            };
            if let Some(s) = summary {
                let _ = std::fs::write(s, suite::summary_text(&outcome));
            }
            if let Some(e) = &outcome.error {
                eprintln!("<F> {e}");
                if outcome.mess.is_none() && !quiet {
                    println!(" DIAGNOSTIC JOB : {}", outcome.diagnostic);
                }
            }
            ExitCode::from(outcome.exit_code() as u8)
        }
        Cmd::Check { files } => {
            let mut bad = 0;
            for f in &files {
                match runner::check_file(f) {
                    Ok(n) => println!("{}: OK ({n} command calls checked)", f.display()),
                    Err((msg, _)) => {
                        eprintln!("{msg}");
                        bad += 1;
                    }
                }
            }
            if bad > 0 {
                eprintln!("{bad} of {} file(s) failed the check", files.len());
                ExitCode::from(2)
            } else {
                ExitCode::SUCCESS
            }
        }
        Cmd::Suite { dir, jobs, out, junit, list, top, quiet } => {
            let out = out.unwrap_or_else(|| PathBuf::from("aster-suite"));
            let exe = match std::env::current_exe() {
                Ok(e) => e,
                Err(e) => {
                    eprintln!("aster: {e}");
                    return ExitCode::from(2);
                }
            };
            let only = match &list {
                Some(l) => match std::fs::read_to_string(l) {
                    Ok(t) => Some(suite::read_list(&t)),
                    Err(e) => {
                        eprintln!("aster: {}: {e}", l.display());
                        return ExitCode::from(2);
                    }
                },
                None => None,
            };
            let results = match suite::exports_of(&dir, only.as_deref())
                .and_then(|ex| suite::run_suite(&exe, &ex, &out, jobs, !quiet))
            {
                Ok(r) => r,
                Err(e) => {
                    eprintln!("aster: {}: {e}", dir.display());
                    return ExitCode::from(2);
                }
            };
            print!("{}", suite::table(&results));
            print!("{}", runner::stops::table(&results, top));
            let jpath = junit.unwrap_or_else(|| out.join("junit.xml"));
            let beside = jpath.parent().map(PathBuf::from).unwrap_or_default();
            let reports = [
                (jpath.clone(), suite::junit(&results)),
                (beside.join("stops.csv"), runner::stops::csv(&results)),
                (beside.join("suite.json"), runner::stops::json(&results)),
                (beside.join("passing.txt"), suite::passing_list(&results)),
            ];
            for (p, text) in reports {
                match std::fs::write(&p, text) {
                    Ok(()) => println!("wrote {}", p.display()),
                    Err(e) => eprintln!("aster: {}: {e}", p.display()),
                }
            }
            if results.iter().all(|r| r.diagnostic == runner::Diagnostic::Ok) {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(1)
            }
        }
        Cmd::Mesh { action } => match mesh_command(action) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("aster: {e}");
                ExitCode::from(2)
            }
        },
        Cmd::Diff { a, b, rtol, atol } => {
            if !(rtol >= 0.0 && atol >= 0.0) {
                eprintln!("aster: --rtol and --atol must be non-negative");
                return ExitCode::from(2);
            }
            match aster::med::diff::diff_files(&a, &b, aster::med::diff::Tolerance { rtol, atol }) {
                Ok(r) => {
                    print!("{}", r.text);
                    if r.within {
                        ExitCode::SUCCESS
                    } else {
                        ExitCode::from(1)
                    }
                }
                Err(e) => {
                    eprintln!("aster: {e}");
                    ExitCode::from(2)
                }
            }
        }
        Cmd::Study { case, knobs, meshes, units, jobs, out, errors, curves, time_limit, repeat, title, quiet } => {
            study_command(case, knobs, meshes, units, jobs, out, (errors, curves), (time_limit, repeat), title, quiet)
        }
        Cmd::Catalog { markdown, schema, hand_written } => {
            let cat = catalogue();
            if let Some(name) = schema {
                let found = if hand_written { cat.hand_written(&name) } else { cat.get(&name) };
                match found {
                    Some(c) => print!("{}", aster::catalog::generated::write(c)),
                    None => {
                        eprintln!("aster: unknown command '{name}'");
                        return ExitCode::from(2);
                    }
                }
            } else if markdown {
                print!("{}", cat.markdown(&|n| aster::stages::stage(n).is_some()));
            } else {
                for c in cat.commands() {
                    let status = if aster::stages::stage(c.name).is_some() { "runs" } else { "checked only" };
                    println!("{:<20} {status:<13} {}", c.name, c.doc);
                }
            }
            ExitCode::SUCCESS
        }
    }
}
