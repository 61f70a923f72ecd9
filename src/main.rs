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
    /// the embedded demo scene (comm/hardening_curve.comm).
    Run {
        case: Option<PathBuf>,
        /// Map a logical unit to a file: N=PATH (read if it exists, else written).
        #[arg(long = "unit", value_name = "N=PATH")]
        units: Vec<String>,
        /// Folder for the .mess and .resu files (default: current folder).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Do not echo the message file to stdout.
        #[arg(short, long)]
        quiet: bool,
        /// Write a machine-readable summary (used by `aster suite`).
        #[arg(long, hide = true)]
        summary: Option<PathBuf>,
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
        /// JUnit XML report path (default: OUT/junit.xml).
        #[arg(long)]
        junit: Option<PathBuf>,
    },
    /// Show the command catalogue.
    Catalog {
        /// Print docs/SUPPORTED.md.
        #[arg(long)]
        markdown: bool,
    },
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
        Cmd::Run { case, units, out, quiet, summary } => {
            let units = match units.iter().map(|u| parse_unit(u)).collect::<Result<Vec<_>, _>>() {
                Ok(u) => u,
                Err(e) => {
                    eprintln!("aster: {e}");
                    return ExitCode::from(2);
                }
            };
            let opts = RunOptions { out_dir: out, units, echo: !quiet };
            let outcome = match &case {
                None => runner::run_default(&opts),
                Some(c) if c.extension().map(|e| e == "export").unwrap_or(false) => runner::run_export(c, &opts),
                Some(c) => runner::run_comm(c, &opts),
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
        Cmd::Suite { dir, jobs, out, junit } => {
            let out = out.unwrap_or_else(|| PathBuf::from("aster-suite"));
            let exe = match std::env::current_exe() {
                Ok(e) => e,
                Err(e) => {
                    eprintln!("aster: {e}");
                    return ExitCode::from(2);
                }
            };
            let results = match suite::run_suite(&exe, &dir, &out, jobs) {
                Ok(r) => r,
                Err(e) => {
                    eprintln!("aster: {}: {e}", dir.display());
                    return ExitCode::from(2);
                }
            };
            print!("{}", suite::table(&results));
            let jpath = junit.unwrap_or_else(|| out.join("junit.xml"));
            if let Err(e) = std::fs::write(&jpath, suite::junit(&results)) {
                eprintln!("aster: {}: {e}", jpath.display());
            }
            if results.iter().all(|r| r.diagnostic == "OK") {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(1)
            }
        }
        Cmd::Catalog { markdown } => {
            let cat = catalogue();
            if markdown {
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
