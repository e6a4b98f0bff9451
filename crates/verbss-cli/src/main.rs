//! The `verbss` command-line tool: thin argument parsing, progress and printing
//! over the `verbss` library.
//!
//! Exit codes: 0 success, 2 bad input (file, argument, setting), 3 a step
//! inverted an element, 4 a step no solver could solve to a trusted result.

#![forbid(unsafe_code)]

use std::process::ExitCode;

use clap::{Parser, Subcommand};
use verbss_cli::{convert, deform, demo, quality, render, run};

/// Mesh motion for unstructured 2D/3D hybrid meshes by Vertex-Ball Spring Smoothing.
#[derive(Parser)]
#[command(name = "verbss", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Measure element quality: counts, groups, histogram, inverted elements.
    Quality(quality::QualityArgs),
    /// Convert a mesh between formats, chosen by extension (.msh, .su2, .vtu, .cgns).
    Convert(convert::ConvertArgs),
    /// Move groups by a translation, a rotation or given positions, in N steps.
    Deform(Box<deform::DeformArgs>),
    /// Run a case file: moving boundaries over time steps, with outputs.
    Run(run::RunArgs),
    /// Run the paper's pitching–plunging NACA0012 case with no input files.
    Demo(demo::DemoArgs),
    /// Draw a mesh coloured by element quality to a .png or .svg picture.
    Render(render::RenderArgs),
}

fn main() -> ExitCode {
    quiet_caught_solver_panics_and_closed_pipes();
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Quality(args) => quality::run(args),
        Command::Convert(args) => convert::run(args),
        Command::Deform(args) => deform::run(*args),
        Command::Run(args) => run::run(args),
        Command::Demo(args) => demo::run(args),
        Command::Render(args) => render::run(args),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

/// The sparse LU the library uses panics on an exact zero pivot; the library
/// catches that panic and reports a singular system as an error, so its
/// message must not reach the user as if the program had crashed. And when
/// the reader of standard output goes away (`verbss quality m.su2 | head`),
/// printing fails: the program stops quietly with the shell's code for a
/// closed pipe (128 + SIGPIPE = 141), as other command-line tools do.
fn quiet_caught_solver_panics_and_closed_pipes() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        if info.location().is_some_and(|l| l.file().contains("/faer-")) {
            return;
        }
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
