//! The `anysl` command-line tool. The whole tool is this library, and `src/main.rs` calls
//! [`main`]: a library starts compiling as soon as its dependencies' metadata exist, so the
//! tool's own code (most of a cold build) compiles alongside `anysl-jit` instead of after it.

mod demo;
mod interp_bench;
#[cfg(feature = "jit")]
mod jit;
mod kernels;
mod native;
mod render;
mod report;
mod rib;
mod rslc;
mod table1;
mod workload;

use clap::{Parser, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(name = "anysl", version, about = "One shader, any renderer: type-replacement shading")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render the gallery with every renderer into `out/` and print a small Table-1 benchmark.
    Demo {
        /// Where pictures go.
        #[arg(long, default_value = "out")]
        out: PathBuf,
    },
    /// Render one picture of a scene preset with one shader and renderer.
    Render(render::RenderArgs),
    /// The RenderMan Shading Language compiler: check, info, ir, rust, eval.
    Rslc {
        #[command(subcommand)]
        cmd: rslc::RslcCommand,
    },
    /// Write the accuracy-against-cost report (HTML with plots and pictures) and print where it is.
    Report {
        /// Folder of `index.html`.
        #[arg(long, default_value = "out/report")]
        out: PathBuf,
        /// Tiny sizes (seconds; for tests, not for reading).
        #[arg(long)]
        quick: bool,
    },
    /// The run-time LLVM JIT (cargo feature `jit`).
    #[cfg(feature = "jit")]
    Jit {
        #[command(subcommand)]
        cmd: JitCommand,
    },
    /// Benchmarks.
    Bench {
        #[command(subcommand)]
        which: BenchCommand,
    },
}

#[cfg(feature = "jit")]
#[derive(Subcommand)]
enum JitCommand {
    /// Cross-check: JIT f32 / 8-wide / dual against the monomorphized shader (hand-written
    /// generic Rust for the Table-1 shaders, the interpreter at the same type otherwise) on
    /// random points; max error in ulps. Surface, displacement, volume and imager shaders (each
    /// through its own entry); light shaders are skipped. Default files: shaders/rsl (with the
    /// standard volumes and imager), scenes/, the conformance suite and tests/data/rsl/stages.
    Check {
        /// `.sl` files (default: every shader in shaders/rsl, shaders/rsl/standard/{volume,imager},
        /// scenes/, tests/data/rsl/conformance and tests/data/rsl/stages).
        files: Vec<PathBuf>,
        /// Random points per comparison.
        #[arg(long, default_value_t = 10000)]
        points: usize,
        /// Print every comparison (default: failures and Table-1 shaders).
        #[arg(long)]
        verbose: bool,
    },
}

#[derive(Subcommand)]
enum BenchCommand {
    /// Shading points/s of every shader × instantiation (single-threaded), with errors vs f64.
    Kernels {
        /// Also write the rows as JSON to this file.
        #[arg(long)]
        json: Option<PathBuf>,
        /// Shading points per run.
        #[arg(long, default_value_t = 32768)]
        points: usize,
        /// Timed runs per row (the median is reported).
        #[arg(long, default_value_t = 7)]
        runs: usize,
        /// Only these shaders (repeatable).
        #[arg(long = "shader")]
        shaders: Vec<String>,
        /// Only these instantiations (repeatable; `f32` always runs as the speedup base).
        #[arg(long = "inst")]
        instantiations: Vec<String>,
    },
    /// The AnySL paper's Table 1: frames/s and shading speedup of the packet renderer per
    /// shader × f32 / f32x4 / f32x8 / f32x16 / native-f32x8, with PSNR against f64.
    Table1 {
        /// Worker threads (default: all cores; the paper's figures are single-threaded: 1).
        #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
        threads: Option<u32>,
        /// Also write the rows as JSON to this file.
        #[arg(long)]
        json: Option<PathBuf>,
        /// Image side in pixels.
        #[arg(long, default_value_t = 512, value_parser = clap::value_parser!(u32).range(8..=8192))]
        size: u32,
        /// Timed runs per row (medians reported).
        #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u32).range(1..=1000))]
        runs: u32,
        /// Only these shaders (repeatable; default: all ten).
        #[arg(long = "shader")]
        shaders: Vec<String>,
    },
    /// The batched interpreter's points/s at batch sizes 1, 16, 256, 4096 against compiled
    /// Rust f32 and f32x8, with max abs error against f64, on the Table-1 `.sl` shaders.
    Interp {
        /// Also write the rows as JSON to this file.
        #[arg(long)]
        json: Option<PathBuf>,
        /// Shading points per run (rounded up to a multiple of 4096).
        #[arg(long, default_value_t = 16384)]
        points: usize,
        /// Timed runs per row (the median is reported).
        #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..=1000))]
        runs: u32,
        /// Only these shaders (repeatable).
        #[arg(long = "shader")]
        shaders: Vec<String>,
    },
    /// The JIT per Table-1 shader: cold compile time by stage (median), points/s of jit-f32 /
    /// x4 / x8 / x16 against aot-f32 / aot-f32x8 (hand-written generic Rust) and the
    /// interpreter, max abs error against f64.
    #[cfg(feature = "jit")]
    Jit {
        /// Also write the rows as JSON to this file.
        #[arg(long)]
        json: Option<PathBuf>,
        /// Shading points per run.
        #[arg(long, default_value_t = 32768)]
        points: usize,
        /// Timed runs per row (the median is reported).
        #[arg(long, default_value_t = 7)]
        runs: usize,
        /// Cold compiles per variant (the median is reported).
        #[arg(long, default_value_t = 5)]
        compiles: usize,
        /// Only these shaders (repeatable).
        #[arg(long = "shader")]
        shaders: Vec<String>,
    },
    /// The shared shading workload (`shaders/assets/workload_ref/shading_workload.md`): four
    /// shaders on a 512×512 sphere image per system and thread count, as the document's TSV,
    /// with max abs error against its reference arrays.
    Workload {
        /// Worker threads per shading call (repeatable; default: 1 and 2).
        #[arg(long = "threads", value_parser = clap::value_parser!(u32).range(1..=256))]
        threads: Vec<u32>,
        /// Also write the rows (with pixels off by more than 1e-3) as JSON to this file.
        #[arg(long)]
        json: Option<PathBuf>,
        /// Timed calls per row after the first (the median is reported).
        #[arg(long, default_value_t = 21, value_parser = clap::value_parser!(u32).range(1..=1000))]
        runs: u32,
        /// Only these shaders (repeatable: plastic, checker, wood, granite).
        #[arg(long = "shader")]
        shaders: Vec<String>,
        /// Only these systems (repeatable, e.g. anysl-f32x8).
        #[arg(long = "system")]
        systems: Vec<String>,
    },
}

fn progress_bar(show: bool) -> ProgressBar {
    if !show {
        return ProgressBar::hidden();
    }
    let pb = ProgressBar::new(0);
    pb.set_style(
        ProgressStyle::with_template("{spinner} [{elapsed_precise}] {bar:30} {pos}/{len} {msg}")
            .expect("valid template"),
    );
    pb
}

/// The sequence every `bench` command follows: run the benchmark behind a progress bar (on a
/// terminal), print its report, then write its rows as JSON to `json` when given. `note_to_stderr`
/// keeps stdout machine-readable for commands whose report is a TSV.
fn bench<R: serde::Serialize>(
    run: impl FnOnce(&ProgressBar) -> Result<Vec<R>, String>,
    report: impl FnOnce(&[R]),
    json: Option<PathBuf>,
    note_to_stderr: bool,
) -> Result<(), String> {
    let pb = progress_bar(std::io::IsTerminal::is_terminal(&std::io::stderr()));
    let rows = run(&pb)?;
    pb.finish_and_clear();
    report(&rows);
    if let Some(path) = json {
        let text = serde_json::to_string_pretty(&rows).map_err(|e| e.to_string())?;
        std::fs::write(&path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        if note_to_stderr {
            eprintln!("rows written to {}", path.display());
        } else {
            println!("rows written to {}", path.display());
        }
    }
    Ok(())
}

fn bench_kernels(opts: kernels::KernelOpts, json: Option<PathBuf>) -> Result<(), String> {
    if opts.points == 0 {
        return Err("--points must be at least 1".into());
    }
    let report = |rows: &[kernels::KernelRow]| {
        kernels::print_table(rows);
        println!();
        println!(
            "mean speedup over f32 (arithmetic / geometric), {} points, median of {} runs:",
            opts.points, opts.runs
        );
        for (inst, am, gm) in kernels::summary(rows) {
            println!("  {inst:<13} {am:>6.2}x / {gm:>6.2}x");
        }
    };
    bench(|pb| kernels::run(&opts, pb), report, json, false)
}

fn bench_interp(opts: &interp_bench::InterpOpts, json: Option<PathBuf>) -> Result<(), String> {
    if opts.points == 0 {
        return Err("--points must be at least 1".into());
    }
    bench(|pb| interp_bench::run(opts, pb), |rows| interp_bench::print_table(rows), json, false)
}

/// Parses the command line and runs the command.
#[must_use]
pub fn main() -> ExitCode {
    // A closed pipe (`anysl rslc eval … | head`) ends the process quietly, as it does other
    // Unix tools, instead of a panic in the next `println!`.
    #[cfg(unix)]
    // SAFETY: setting a signal's disposition to the default before any thread is started.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Demo { out } => demo(&out),
        Command::Render(args) => match &args.scene_file {
            Some(file) => rib::run(file, &args),
            None => render::run(&args),
        },
        Command::Rslc { cmd } => match rslc::run(&cmd) {
            Ok(code) => return ExitCode::from(code),
            Err(e) => Err(e),
        },
        Command::Report { out, quick } => {
            report::run(&report::ReportOpts { out, quick }).map(|p| println!("report written to {}", p.display()))
        }
        #[cfg(feature = "jit")]
        Command::Jit { cmd: JitCommand::Check { files, points, verbose } } => {
            if jit::check(&files, points.max(16), verbose) {
                Ok(())
            } else {
                Err("jit check: mismatches (see above)".to_string())
            }
        }
        Command::Bench { which } => match which {
            #[cfg(feature = "jit")]
            BenchCommand::Jit { json, points, runs, compiles, shaders } => {
                let opts =
                    jit::JitBenchOpts { points: points.max(16), runs: runs.max(1), compiles: compiles.max(1), shaders };
                bench(|_| jit::bench(&opts), |rows| jit::print_table(rows), json, false)
            }
            BenchCommand::Kernels { json, points, runs, shaders, instantiations } => {
                bench_kernels(kernels::KernelOpts { points, runs, shaders, instantiations }, json)
            }
            BenchCommand::Table1 { threads, json, size, runs, shaders } => {
                let opts = table1::Table1Opts {
                    size,
                    runs: runs as usize,
                    threads: threads.map_or(0, |t| t as usize),
                    shaders,
                };
                bench(|pb| table1::run(&opts, pb), |rows| table1::report(rows, &opts), json, false)
            }
            BenchCommand::Workload { threads, json, runs, shaders, systems } => {
                let opts = workload::WorkloadOpts {
                    threads: if threads.is_empty() {
                        vec![1, 2]
                    } else {
                        threads.iter().map(|&t| t as usize).collect()
                    },
                    runs: runs as usize,
                    shaders,
                    systems,
                };
                bench(|pb| workload::run(&opts, pb), |rows| workload::print_tsv(rows), json, true)
            }
            BenchCommand::Interp { json, points, runs, shaders } => {
                bench_interp(&interp_bench::InterpOpts { points, runs: runs as usize, shaders }, json)
            }
        },
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn demo(out: &std::path::Path) -> Result<(), String> {
    let pb = progress_bar(std::io::IsTerminal::is_terminal(&std::io::stderr()));
    demo::run(out, &table1::Table1Opts { size: 256, runs: 1, threads: 1, shaders: Vec::new() }, &pb)
}
