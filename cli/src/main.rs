//! The `anysl` command-line tool.

mod kernels;
mod native;

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
    /// Shade the shader collection and print the benchmark table.
    Demo {
        /// Where pictures go.
        #[arg(long, default_value = "out")]
        out: PathBuf,
    },
    /// Benchmarks.
    Bench {
        #[command(subcommand)]
        which: BenchCommand,
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

fn bench_kernels(opts: kernels::KernelOpts, json: Option<PathBuf>) -> Result<(), String> {
    if opts.points == 0 {
        return Err("--points must be at least 1".into());
    }
    let pb = progress_bar(std::io::IsTerminal::is_terminal(&std::io::stderr()));
    let rows = kernels::run(&opts, &pb)?;
    pb.finish_and_clear();
    kernels::print_table(&rows);
    println!();
    println!("mean speedup over f32 (arithmetic / geometric), {} points, median of {} runs:", opts.points, opts.runs);
    for (inst, am, gm) in kernels::summary(&rows) {
        println!("  {inst:<13} {am:>6.2}x / {gm:>6.2}x");
    }
    if let Some(path) = json {
        let text = serde_json::to_string_pretty(&rows).map_err(|e| e.to_string())?;
        std::fs::write(&path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        println!("rows written to {}", path.display());
    }
    Ok(())
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Demo { out } => demo(&out),
        Command::Bench { which } => match which {
            BenchCommand::Kernels { json, points, runs, shaders, instantiations } => {
                bench_kernels(kernels::KernelOpts { points, runs, shaders, instantiations }, json)
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
    let _ = out;
    bench_kernels(kernels::KernelOpts { points: 8192, runs: 3, shaders: Vec::new(), instantiations: Vec::new() }, None)
}
