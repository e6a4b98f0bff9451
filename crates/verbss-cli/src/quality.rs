//! `verbss quality MESH [--json]`: counts, groups, quality histogram, inverted elements.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use serde_json::Value;
use verbss::quality;

use crate::input::read_mesh;

/// Arguments of `verbss quality`.
#[derive(Args)]
pub struct QualityArgs {
    /// The mesh (.msh, .su2, .vtu, .cgns).
    mesh: PathBuf,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    json: bool,
}

/// Runs `verbss quality`.
pub fn run(args: QualityArgs) -> anyhow::Result<ExitCode> {
    let mesh = read_mesh(&args.mesh)?;
    let value = quality::summary_json(&mesh);
    if args.json {
        println!("{}", serde_json::to_string(&value)?);
    } else {
        print_table(&args.mesh, &value);
    }
    Ok(ExitCode::SUCCESS)
}

fn print_table(path: &std::path::Path, v: &Value) {
    println!("{}", path.display());
    println!("  dimension  {}", v["dimension"]);
    println!("  nodes      {}", v["nodes"]);
    println!("  elements   {}", v["elements"]);
    if let Some(kinds) = v["kinds"].as_object() {
        for (name, count) in kinds {
            println!("    {name:<12} {count}");
        }
    }
    println!("  groups (distinct nodes)");
    if let Some(groups) = v["groups"].as_object() {
        for (name, count) in groups {
            println!("    {name:<12} {count}");
        }
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
}
