//! `--zone K`: the zone of a multi-zone SU2 file a command works on.

use std::path::Path;

use anyhow::anyhow;
use clap::Args;
use verbss::io;
use verbss::mesh::Mesh;

/// The `--zone` option.
#[derive(Args, Clone, Copy)]
pub struct ZoneArg {
    /// The zone of a multi-zone SU2 file (its IZONE= K) [default: 1, with a
    /// note when the file has several].
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    pub zone: Option<u32>,
}

/// Reads zone `zone` of `path` (1 when `None`, with a note on standard
/// error when the file has several zones unless `quiet`, as for what else
/// of the file is left out: [`crate::input::note_left_out`]); `how` says
/// how to choose another zone (`--zone K`, `zone = K`).
pub fn read(path: &Path, zone: Option<u32>, how: &str, quiet: bool) -> anyhow::Result<Mesh> {
    let (mesh, count) = io::read_zone(path, zone.map_or(1, |k| k as usize))?;
    if zone.is_none() && count > 1 && !quiet {
        eprintln!(
            "note: {} has {count} zones; using zone 1 (choose one with {how})",
            path.display()
        );
    }
    if !quiet {
        crate::input::note_left_out(path, &mesh);
    }
    Ok(mesh)
}

/// The error of a group missing from the zone read, naming the zone of
/// `path` that has it when there is one.
pub fn missing_group(e: verbss::Error, path: &Path, group: &str) -> anyhow::Error {
    let zones = io::read_zones(path).unwrap_or_default();
    match zones.iter().position(|m| m.group(group).is_ok()) {
        Some(k) if zones.len() > 1 => anyhow!("{e}; zone {} has it (give --zone {})", k + 1, k + 1),
        _ => e.into(),
    }
}
