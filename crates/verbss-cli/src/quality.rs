//! `verbss quality MESH [--json] [--zone K]`: counts, groups, quality
//! histogram, inverted elements; of every zone of a multi-zone SU2 file
//! unless `--zone` names one.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use serde_json::Value;
use verbss::{io, quality};

/// Arguments of `verbss quality`.
#[derive(Args)]
pub struct QualityArgs {
    /// The mesh (.msh, .su2, .vtu, .cgns).
    mesh: PathBuf,
    /// Print one JSON object instead of a table (of a multi-zone file
    /// without --zone: `{"zones": [...]}`, one object per zone with its `zone`).
    #[arg(long)]
    json: bool,
    /// Only this zone of a multi-zone SU2 file (IZONE= K) [default: every zone].
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    zone: Option<u32>,
}

/// Runs `verbss quality`.
pub fn run(args: QualityArgs) -> anyhow::Result<ExitCode> {
    let zones = match args.zone {
        Some(k) => vec![io::read_zone(&args.mesh, k as usize)?.0],
        None => io::read_zones(&args.mesh)?,
    };
    for mesh in &zones {
        crate::input::note_left_out(&args.mesh, mesh);
    }
    let values: Vec<Value> = zones.iter().map(quality::summary_json).collect();
    let count = values.len();
    if count == 1 {
        if args.json {
            println!("{}", serde_json::to_string(&values[0])?);
        } else {
            println!("{}", args.mesh.display());
            print_table(&values[0]);
        }
        return Ok(ExitCode::SUCCESS);
    }
    if args.json {
        let zones: Vec<Value> = values
            .into_iter()
            .zip(1..)
            .map(|(mut v, k)| {
                v["zone"] = k.into();
                v
            })
            .collect();
        println!(
            "{}",
            serde_json::to_string(&serde_json::json!({ "zones": zones }))?
        );
    } else {
        for (v, k) in values.iter().zip(1..) {
            println!("{} zone {k} of {count}", args.mesh.display());
            print_table(v);
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// The table of one zone's summary.
fn print_table(v: &Value) {
    println!("  dimension  {}", v["dimension"]);
    println!("  nodes      {}", v["nodes"]);
    println!("  elements   {}", v["elements"]);
    let (kinds, groups) = (v["kinds"].as_object(), v["groups"].as_object());
    // One column for the counts: past the longest kind or group name.
    let width = kinds
        .into_iter()
        .chain(groups)
        .flat_map(|m| m.keys())
        .map(|name| name.chars().count())
        .fold(12, usize::max);
    for (name, count) in kinds.into_iter().flatten() {
        println!("    {name:<width$} {count}");
    }
    println!("  groups (distinct nodes)");
    for (name, count) in groups.into_iter().flatten() {
        println!("    {name:<width$} {count}");
    }
    let q = &v["quality"];
    println!(
        "  quality    min {:.4}  mean {:.4}",
        q["min"].as_f64().unwrap_or(f64::NAN),
        q["mean"].as_f64().unwrap_or(f64::NAN)
    );
    if let Some(bins) = q["bins"].as_array() {
        let total = v["elements"].as_u64().unwrap_or(0).max(1) as f64;
        for b in bins {
            let count = b["count"].as_u64().unwrap_or(0);
            println!(
                "    {:.2}–{:.2}  {:>9}  {:5.1}%",
                b["lo"].as_f64().unwrap_or(0.0),
                b["hi"].as_f64().unwrap_or(0.0),
                count,
                100.0 * count as f64 / total
            );
        }
    }
    println!("  inverted   {}", v["inverted"]);
    let c = &v["checkmesh"];
    println!(
        "  checkMesh  {} negative-volume cells, {} incorrectly oriented faces, {} open cells, \
         {} of aspect ratio above 1000",
        c["negative_volume_cells"],
        c["incorrectly_oriented_faces"],
        c["open_cells"],
        c["high_aspect_ratio_cells"]
    );
}
