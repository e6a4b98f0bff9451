//! `verbss demo [--out DIR]`: the paper's §4.2 case with no input files — a
//! NACA0012 airfoil pitching (θ₀ = 40°) and plunging (h₀ = 0.2 chord) about
//! its quarter chord over N = 160 steps (eq. 10), on a 4,500-node O-grid
//! built in process, moved by VerBSS (ω = 1.6, ε = 10⁻⁵ relative to each
//! step's largest boundary displacement).

use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;

use clap::Args;
use verbss::generate::{naca0012, AirfoilGrid};
use verbss::io::WriteOptions;
use verbss::motion::{Attachment, Motion};
use verbss::settings::Settings;

use crate::render::{PictureArgs, Recorder};
use crate::run::{parse_every, run_here, Job, Prepared};

/// Arguments of `verbss demo`.
#[derive(Args)]
pub struct DemoArgs {
    /// Output folder.
    #[arg(long, default_value = "out/demo")]
    out: PathBuf,
    /// No progress output.
    #[arg(long, short)]
    quiet: bool,
    /// Write every K-th step of the .vtu series (step 0 and the last step always).
    #[arg(long, value_name = "K", value_parser = parse_every, allow_hyphen_values = true, default_value_t = DEMO_EVERY)]
    every: usize,
    #[command(flatten)]
    pictures: PictureArgs,
}

/// The demo's default `--every`: 17 frames of the 160 steps, about 7 MB in all.
pub const DEMO_EVERY: usize = 10;

/// The window of the demo's pictures: the airfoil and its sweep.
const AIRFOIL_VIEW: [f64; 4] = [-0.6, 1.6, -1.0, 1.0];

/// The demo's job: mesh, motion and the product's default settings
/// ([`Settings::robust`], as `verbss deform` without options); every
/// `every`-th step written to the series.
pub fn job(out: PathBuf, every: usize) -> anyhow::Result<Job> {
    let mesh = naca0012(&AirfoilGrid::default())?;
    let motion = Motion::PitchPlunge {
        center: [0.25, 0.0, 0.0],
        axis: [0.0, 0.0, 1.0],
        pitch: 40f64.to_radians(),
        plunge: [0.0, 0.2, 0.0],
        period: None,
    };
    let settings = Settings::robust(160);
    Ok(Job {
        name: "naca0012".into(),
        source: "built-in NACA0012 O-grid".into(),
        write_options: WriteOptions::default(),
        mesh: Arc::new(mesh),
        attachments: vec![Attachment {
            groups: vec!["airfoil".into()],
            motion,
        }],
        settings,
        foam_times: None,
        every,
        series: true,
        final_mesh: true,
        report: Some(out.join("report.json")),
        extension: "su2".into(),
        dir: out,
        inputs: Vec::new(),
        overwrite: false,
        from_case: false,
    })
}

/// Runs `verbss demo`.
pub fn run(args: DemoArgs) -> anyhow::Result<ExitCode> {
    let job = job(args.out, args.every)?;
    if !args.quiet {
        println!(
            "NACA0012 pitching (40°) and plunging (0.2 chord) about the quarter chord, {} steps, {} nodes, {} triangles",
            job.settings.steps,
            job.mesh.node_count(),
            job.mesh.cell_count()
        );
    }
    let recorder = Recorder::new(
        &args.pictures,
        &job.mesh,
        job.settings.steps,
        Some(AIRFOIL_VIEW),
    );
    run_here(Prepared {
        job,
        quiet: args.quiet,
        recorder,
    })
}
