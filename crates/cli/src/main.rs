//! `aster`: read, check, explain and run code_aster command files.
//!
//! Exit codes follow the contract in the README: 0 success, 1 a failed
//! check (parse/check errors, a NOOK test), 2 an error that stopped the run,
//! 3 (`check`) nothing wrong but something aster does not support.

mod cmd;

use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "aster",
    version,
    about = "Read, check and run code_aster command files"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Parse command files; print the AST with --json.
    Parse {
        files: Vec<PathBuf>,
        /// Print the AST of each file as JSON.
        #[arg(long)]
        json: bool,
    },
    /// Print a command file in canonical form.
    Fmt { file: PathBuf },
    /// Validate command files against the catalog (commands are not run).
    Check {
        files: Vec<PathBuf>,
        /// Emit the evaluated program (`commands`) as JSON.
        #[arg(long, value_name = "WHAT")]
        emit: Option<String>,
        /// How diagnostics are printed: `human` (stderr), `json` (JSON
        /// Lines, one object per file), `sarif` (SARIF 2.1.0), `github`
        /// (GitHub Actions annotations). Exit 0 clean, 1 errors, 3 only
        /// constructs aster does not support.
        #[arg(long, value_enum, default_value = "human")]
        format: cmd::check::Format,
    },
    /// Explain a command or a keyword: `aster explain CMD[/KEYWORD/...]`.
    Explain { path: String },
    /// Rewrite code_aster 11/14/15 command files in code_aster 17 spelling
    /// (comments and layout kept); print a unified diff, or --write.
    ///
    /// Example: `aster migrate study.comm` (diff), `aster migrate --write *.comm`.
    /// Exit 0 when every legacy construct was rewritten, 1 when some are
    /// left (listed on stderr), 2 when a file cannot be read or parsed.
    Migrate {
        /// The command files.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// Rewrite the files in place instead of printing a diff.
        #[arg(long)]
        write: bool,
    },
    /// Describe a mesh file.
    Mesh {
        file: PathBuf,
        /// Print a JSON summary (nodes, cells per type, groups).
        #[arg(long)]
        json: bool,
        /// Convert to another format (`mail`, `med`, `vtu`), written to --out.
        #[arg(long, value_name = "FORMAT")]
        to: Option<String>,
        #[arg(long, value_name = "PATH")]
        out: Option<PathBuf>,
    },
    /// Run a case (.comm or .export) and its TEST_RESU checks.
    Run {
        case: PathBuf,
        /// Mesh file for unit 20 when no .export names one.
        #[arg(long)]
        mesh: Option<PathBuf>,
        /// Directory for files the case writes (IMPR_RESU, IMPR_TABLE, the
        /// `.export`'s result files); default `<case>-out/` in the current
        /// directory.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Write a report of every TEST_RESU comparison and every command's
        /// time: `--report json FILE` or `--report junit FILE`.
        #[arg(long, num_args = 2, value_names = ["FORMAT", "FILE"])]
        report: Vec<String>,
        /// No live progress on stderr (the `.mess` file still gets it).
        #[arg(short, long)]
        quiet: bool,
        /// Write every result (all steps: displacement, stresses, contact
        /// status…) for ParaView, no IMPR_RESU needed: DIR/<RESULT>.pvd and
        /// DIR/<RESULT>_<NUME_ORDRE>.vtu.
        #[arg(long, value_name = "DIR")]
        vtu: Option<PathBuf>,
    },
    /// Serve the Language Server Protocol on stdin/stdout (docs/editors.md).
    Lsp {
        /// Accepted for editors that pass it; stdio is the only transport.
        #[arg(long)]
        stdio: bool,
    },
    /// Sweep contact methods and parameters on a scene (TOML spec); write a
    /// CSV, error/time, convergence and stability charts, and a summary.
    Study {
        spec: PathBuf,
        #[arg(long, default_value = "study-out")]
        out: PathBuf,
    },
}

/// The stack of the thread that runs a command. Every recursive pass of the
/// syntax and the evaluator is bounded (`aster_syntax::limits`,
/// `aster_eval::limits`) to fit in a main thread's usual 8 MB with a 2x
/// margin (measured: the deepest evaluation the limits allow takes under
/// 4 MB in the `ci` profile); the command runs on a thread with more, so
/// that the margin holds for any build profile.
const STACK_BYTES: usize = 64 << 20;

fn main() -> ExitCode {
    let cli = Cli::parse();
    let worker = std::thread::Builder::new()
        .name("aster".into())
        .stack_size(STACK_BYTES)
        .spawn(move || run(cli));
    match worker.map(|w| w.join()) {
        Ok(Ok(code)) => ExitCode::from(code),
        Ok(Err(_)) => ExitCode::from(101),
        Err(e) => {
            eprintln!("aster: cannot start the worker thread: {e}");
            ExitCode::from(2)
        }
    }
}

fn run(cli: Cli) -> u8 {
    match cli.command {
        Command::Parse { files, json } => cmd::parse::run(&files, json),
        Command::Fmt { file } => cmd::fmt::run(&file),
        Command::Check {
            files,
            emit,
            format,
        } => cmd::check::run(&files, emit.as_deref(), format),
        Command::Migrate { files, write } => cmd::migrate::run(&files, write),
        Command::Explain { path } => cmd::explain::run(&path),
        Command::Mesh {
            file,
            json,
            to,
            out,
        } => cmd::mesh::run(&file, json, to.as_deref(), out.as_deref()),
        Command::Run {
            case,
            mesh,
            out,
            report,
            quiet,
            vtu,
        } => cmd::run::run(
            &case,
            mesh.as_deref(),
            out.as_deref(),
            &report,
            quiet,
            vtu.as_deref(),
        ),
        Command::Study { spec, out } => cmd::study::run(&spec, &out),
        Command::Lsp { .. } => cmd::lsp::run(),
    }
}
