//! `aster`: read, check, explain and run code_aster command files.
//!
//! Exit codes follow the contract in the README: 0 success, 1 a failed
//! check (parse/check errors, a NOOK test), 2 an error that stopped the run,
//! 3 (`check`) nothing wrong but something aster does not support.

mod cmd;
mod style;

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
    #[command(
        after_help = "Examples:\n  aster parse study.comm            syntax errors only, exit 1 on any\n  aster parse --json study.comm     the AST as JSON\n  aster parse --json --compact *.comm  JSON Lines: one AST per line"
    )]
    Parse {
        /// Command files (.comm, .com1…); syntax only, nothing is evaluated.
        files: Vec<PathBuf>,
        /// Print the AST of each file as JSON: one object per file with
        /// `schema_version`, `kind` "ast", `path` and `body` (docs/json.md).
        #[arg(long)]
        json: bool,
        /// With --json: one object per line (JSON Lines) instead of indented.
        #[arg(long)]
        compact: bool,
    },
    /// Print command files in canonical form, check or rewrite them.
    #[command(
        after_help = "Examples:\n  aster fmt study.comm              print the canonical form\n  aster fmt --check comm/*.comm     diff of what would change; exit 1 if any\n  aster fmt --write comm/*.comm     rewrite in place (encoding kept)"
    )]
    Fmt {
        /// Command files to format.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// Change nothing: print a diff of each file that is not canonical
        /// and exit 1 if there is one (for CI and pre-commit hooks).
        #[arg(long, conflicts_with = "write")]
        check: bool,
        /// Rewrite the files in place.
        #[arg(long)]
        write: bool,
    },
    /// Validate command files against the catalog (commands are not run).
    #[command(
        after_help = "Examples:\n  aster check study.comm                 rustc-style diagnostics on stderr\n  aster check --format sarif *.comm      SARIF 2.1.0 for code-scanning\n  aster check --format github *.comm     GitHub Actions annotations\n  aster check --emit commands study.comm the evaluated commands as JSON\n  aster check --emit commands --compact --no-defaults *.comm\n                                         JSON Lines, only what was written\n\nExit: 0 clean, 1 errors, 3 only constructs `aster run` does not support."
    )]
    Check {
        /// Command files (.comm, .com1…), checked one after the other.
        files: Vec<PathBuf>,
        /// Emit the evaluated program (`commands`) as JSON: one object per
        /// file with `schema_version`, `kind` "commands", `path` and
        /// `commands`, each located by line and column (docs/json.md).
        #[arg(long, value_name = "WHAT")]
        emit: Option<String>,
        /// With --emit: one object per line (JSON Lines) instead of indented.
        #[arg(long)]
        compact: bool,
        /// With --emit: leave out the keywords the catalog filled in.
        #[arg(long)]
        no_defaults: bool,
        /// How diagnostics are printed: `human` (stderr), `json` (JSON
        /// Lines, one object per file), `sarif` (SARIF 2.1.0), `github`
        /// (GitHub Actions annotations). Exit 0 clean, 1 errors, 3 only
        /// constructs aster does not support.
        #[arg(long, value_enum, default_value = "human")]
        format: cmd::check::Format,
    },
    /// Explain a command or a keyword: `aster explain CMD[/KEYWORD/...]`.
    #[command(
        after_help = "Examples:\n  aster explain DEFI_CONTACT\n  aster explain DEFI_CONTACT/ZONE/COEF_CONT\n  aster explain STAT_NON_LINE/CONVERGENCE"
    )]
    Explain {
        /// A command, or a path of keywords under it separated by `/`
        /// (as diagnostics print it: `DEFI_CONTACT/ZONE[1]/COEF_CONT`).
        path: String,
        /// Every allowed value, however long the list.
        #[arg(long)]
        all: bool,
    },
    /// Rewrite code_aster 11/14/15 command files in code_aster 17 spelling
    /// (comments and layout kept); print a unified diff, or --write.
    #[command(
        after_help = "Examples:\n  aster migrate study.comm            a unified diff on stdout\n  aster migrate --write old/*.comm    rewrite in place (encoding kept)\n\nExit: 0 every legacy construct rewritten, 1 some left (listed on stderr),\n2 a file that cannot be read or parsed."
    )]
    Migrate {
        /// The command files.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// Rewrite the files in place instead of printing a diff.
        #[arg(long)]
        write: bool,
    },
    /// Describe a mesh file.
    #[command(
        after_help = "Examples:\n  aster mesh block.mail                     nodes, cells per type, groups\n  aster mesh --json block.med               the same as JSON\n  aster mesh result.med --to vtu --out r.vtu  convert, fields kept"
    )]
    Mesh {
        /// A mesh or result file: Aster `.mail`, MED (`.med`, `.mmed`),
        /// GMSH `.msh`, GIBI `.mgib`.
        file: PathBuf,
        /// Print a JSON summary (nodes, cells per type, groups).
        #[arg(long)]
        json: bool,
        /// Convert to another format (`mail`, `med`, `vtu`), written to --out.
        #[arg(long, value_name = "FORMAT")]
        to: Option<String>,
        /// Where --to writes (a file; with result steps, beside it a .pvd).
        #[arg(long, value_name = "PATH")]
        out: Option<PathBuf>,
    },
    /// Run a case (.comm or .export) and its TEST_RESU checks.
    #[command(
        after_help = "Examples:\n  aster run case.export                      every command file of the study\n  aster run case.comm --mesh case.mail       a lone command file and its mesh\n  aster run case.export --report junit r.xml one JUnit test per TEST_RESU check\n  aster run case.export --vtu vtu/           results for ParaView\n\nExit: 0 every check OK, 1 a NOOK, 2 an error or a refusal (located)."
    )]
    Run {
        /// The case: an `.export` (its command files run in order, its
        /// meshes on their units) or a single command file.
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
    /// Draw the tables and functions a case wrote (IMPR_TABLE, IMPR_FONCTION:
    /// TABLEAU, AGRAF or XMGRACE text) as an SVG or PNG line chart.
    #[command(
        after_help = "Examples:\n  aster plot out/fort.8                        every numeric column against INST\n  aster plot out/fort.8 --x DY --y FY --out f-u.png\n  aster plot out/fort.8 --where NOEUD=N3 --y DX   one node's rows only\n  aster plot a.agr b.agr --log-y               curves of two XMGRACE files\n\nExit: 0 the chart is written, 2 an unreadable file or an unknown column (named)."
    )]
    Plot {
        /// Text files written by IMPR_TABLE or IMPR_FONCTION (every table
        /// of each file is drawn).
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// The abscissa column (default: INST, ABSC_CURV, ABSCISSE or FREQ
        /// when present, else the first numeric column).
        #[arg(short, long, value_name = "COLUMN")]
        x: Option<String>,
        /// An ordinate column; repeat for several (default: every other
        /// numeric column but NUME_ORDRE).
        #[arg(short, long, value_name = "COLUMN")]
        y: Vec<String>,
        /// Keep only the rows whose COLUMN holds VALUE (repeatable: all
        /// must hold), e.g. `--where NOEUD=N3`.
        #[arg(long = "where", value_name = "COLUMN=VALUE")]
        filters: Vec<String>,
        /// The chart file, `.svg` or `.png` (default: `<first file>.svg` in
        /// the current directory).
        #[arg(long, value_name = "PATH")]
        out: Option<PathBuf>,
        /// The chart's title (default: the file names).
        #[arg(long)]
        title: Option<String>,
        /// Logarithmic abscissa (non-positive values are left out).
        #[arg(long)]
        log_x: bool,
        /// Logarithmic ordinate (non-positive values are left out).
        #[arg(long)]
        log_y: bool,
    },
    /// Serve the Language Server Protocol on stdin/stdout (docs/editors.md).
    #[command(
        after_help = "Example: an editor starts `aster lsp` and talks to it on stdin/stdout\n(set-ups for VS Code, Neovim, Helix and Emacs in docs/editors.md)."
    )]
    Lsp {
        /// Accepted for editors that pass it; stdio is the only transport.
        #[arg(long)]
        stdio: bool,
    },
    /// Print a shell completion script for `aster`.
    #[command(
        after_help = "Examples:\n  aster completions bash > ~/.local/share/bash-completion/completions/aster\n  aster completions zsh > ~/.zfunc/_aster\n  aster completions fish > ~/.config/fish/completions/aster.fish"
    )]
    Completions {
        /// The shell: bash, elvish, fish, powershell or zsh.
        shell: clap_complete::Shell,
    },
    /// Sweep contact methods and parameters on a scene (TOML spec); write a
    /// CSV, error/time, convergence and stability charts, and a summary.
    #[command(after_help = "Example:\n  aster study comm/study-hertz.toml --out sweep/")]
    Study {
        /// The study specification (TOML).
        spec: PathBuf,
        /// Directory for the CSV, the charts and the summary.
        #[arg(long, default_value = "study-out")]
        out: PathBuf,
    },
}

/// The stack of the thread that runs a command in an unoptimised build.
/// Every recursive pass of the syntax and the evaluator is bounded
/// (`aster_syntax::limits`, `aster_eval::limits`) to fit in a main thread's
/// usual 8 MB with a 2x margin (measured: the deepest evaluation the limits
/// allow takes under 4 MB in the `ci` profile); a debug build's frames are
/// several times larger, so there the command runs on a thread with more.
const STACK_BYTES: usize = 64 << 20;

fn main() -> ExitCode {
    quiet_on_closed_pipe();
    let cli = Cli::parse();
    aster_fem::linalg::defer_thread_pool();
    // Optimised builds run the command on the main thread: a second thread
    // costs more than its start (measured, docs/performance.md): glibc
    // gives it its own malloc arena, grown and trimmed a page at a time
    // (one `mprotect` and one page fault each, ~250 for zzzz237a), and on
    // a busy machine the main thread waits for it to be scheduled.
    if !cfg!(debug_assertions) {
        return ExitCode::from(run(cli));
    }
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

/// `aster explain X | head`: when the reader of stdout goes away, stop
/// quietly with the shell's code for SIGPIPE (141), as C tools do, instead
/// of the panic `print!` raises on a closed pipe.
fn quiet_on_closed_pipe() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let message = info
            .payload()
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| info.payload().downcast_ref::<&str>().copied())
            .unwrap_or("");
        if message.starts_with("failed printing to stdout") && message.contains("Broken pipe") {
            std::process::exit(141);
        }
        default(info);
    }));
}

fn run(cli: Cli) -> u8 {
    match cli.command {
        Command::Parse {
            files,
            json,
            compact,
        } => cmd::parse::run(&files, json, compact),
        Command::Fmt {
            files,
            check,
            write,
        } => {
            let mode = match (check, write) {
                (true, _) => cmd::fmt::Mode::Check,
                (false, true) => cmd::fmt::Mode::Write,
                (false, false) => cmd::fmt::Mode::Print,
            };
            cmd::fmt::run(&files, mode)
        }
        Command::Check {
            files,
            emit,
            compact,
            no_defaults,
            format,
        } => cmd::check::run(
            &files,
            emit.as_deref(),
            format,
            cmd::json_out::JsonOptions {
                compact,
                no_defaults,
            },
        ),
        Command::Migrate { files, write } => cmd::migrate::run(&files, write),
        Command::Explain { path, all } => cmd::explain::run(&path, all),
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
        Command::Plot {
            files,
            x,
            y,
            filters,
            out,
            title,
            log_x,
            log_y,
        } => cmd::plot::run(
            &files,
            &cmd::plot::Options {
                x: x.as_deref(),
                y: &y,
                filters: &filters,
                out: out.as_deref(),
                title: title.as_deref(),
                log_x,
                log_y,
            },
        ),
        Command::Study { spec, out } => cmd::study::run(&spec, &out),
        Command::Lsp { .. } => cmd::lsp::run(),
        Command::Completions { shell } => {
            use clap::CommandFactory;
            let mut command = Cli::command();
            clap_complete::generate(shell, &mut command, "aster", &mut std::io::stdout());
            0
        }
    }
}
