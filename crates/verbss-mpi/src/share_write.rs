//! What `verbss-mpi deform` without the whole mesh ([`crate::share_run`])
//! writes, rank by rank: the output's folder made and the input kept
//! unless `--overwrite` says otherwise, every rank's piece of the moved
//! mesh (a `.vtu` piece and rank 0 the `.pvtu`, or a partition of a split
//! MSH 4.1 set), and after a failed step the failed state as `.vtu`
//! pieces `OUT-STEM.failed_RANK.vtu` joined by `OUT-STEM.failed.pvtu`, as
//! `verbss deform` writes `OUT-STEM.failed.vtu`.

use std::path::{Path, PathBuf};

use anyhow::bail;
use verbss::io::gmsh::partitioned::Share;
use verbss::io::gmsh::split::split_file;
use verbss::io::gmsh::split_write::{SplitModel, SplitPiece};
use verbss::{quality, Mesh};
use verbss_cli::deform::ShareJob;
use verbss_cli::overwrite::refuse_input_as_output;
use verbss_cli::run::{file_stem, output_dir};
use verbss_mpi::pieces::{
    decode_entities, encode_entities, encode_groups, msh_facet_tags, split_groups, split_path,
    write_local_piece, write_msh_piece,
};
use verbss_mpi::share::agree;
use verbss_mpi::Comm;

use crate::run::{join_pieces, told};

/// Whether `path` has the extension `ext`, in any case.
pub fn has_extension(path: &Path, ext: &str) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case(ext))
}

/// Before the solve (collective): makes the folders of the output, of the
/// report and of the gathered mesh (`gather`), and fails on every rank
/// where a rank's MSH piece would replace a file of the input (`input`, or
/// with `split` the `partitions` files of its set), unless `--overwrite`.
pub fn prepare_output(
    world: &Comm,
    (job, gather): (&ShareJob, Option<&Path>),
    input: &Path,
    split: bool,
    partitions: usize,
) -> anyhow::Result<()> {
    let dir = output_dir(&job.output);
    let check = || -> anyhow::Result<()> {
        let outputs = [Some(job.output.as_path()), job.report.as_deref(), gather];
        for folder in outputs.into_iter().flatten().map(output_dir) {
            std::fs::create_dir_all(&folder).map_err(|e| {
                anyhow::anyhow!("{}: cannot make the folder: {e}", folder.display())
            })?;
        }
        if job.overwrite || !has_extension(&job.output, "msh") {
            return Ok(());
        }
        let piece = split_path(&dir, &file_stem(&job.output), world.rank() as usize + 1);
        let inputs = if split {
            (1..=partitions)
                .map(|k| split_file(input, k))
                .collect::<verbss::Result<Vec<_>>>()?
        } else {
            vec![input.to_path_buf()]
        };
        for file in &inputs {
            refuse_input_as_output(file, &piece, false, false)?;
        }
        Ok(())
    };
    let checked = check().map_err(|e| verbss::Error::InvalidSetting(e.to_string()));
    told(agree(world, checked, "refused its output"))
}

/// What the output line names: `output`, or for MSH pieces the files of
/// the set, `OUT-STEM_1.msh` to `OUT-STEM_P.msh` for `pieces` ranks.
pub fn written_name(output: &Path, pieces: i32) -> String {
    if has_extension(output, "pvtu") {
        return output.display().to_string();
    }
    let (dir, stem) = (output_dir(output), file_stem(output));
    let first = split_path(&dir, &stem, 1);
    match pieces {
        1 => first.display().to_string(),
        p => format!(
            "{} to {}",
            first.display(),
            split_path(&dir, &stem, p as usize).display()
        ),
    }
}

/// Every rank writes its cells at `coords` as its piece beside `output`:
/// an MSH 4.1 piece for a `.msh` output (binary as `binary` says, else as
/// the input; rank 0 notes a file of the set's name past the last
/// partition, which would stop the set being read back), else a `.vtu`
/// piece and rank 0 the `.pvtu` joining them.
/// Where a rank fails, every rank stops with the lowest failing rank's
/// message.
pub fn write(
    world: &Comm,
    (output, binary): (&Path, Option<bool>),
    share: &Share,
    coords: &[f64],
    orientation: &[i8],
) -> anyhow::Result<()> {
    let dir = output_dir(output);
    let name = file_stem(output);
    if !has_extension(output, "msh") {
        return write_vtu_pieces(world, (&dir, &name), &share.mesh, coords, orientation);
    }
    let fresh = first_fresh_tag(world, share)?;
    let facet_tags = msh_facet_tags(share, fresh);
    let (model, groups) = split_model(world, share, coords, &facet_tags);
    let piece = (
        world.rank() as usize + 1,
        groups.as_slice(),
        facet_tags.as_slice(),
    );
    let binary = binary.unwrap_or(share.binary);
    let written = write_msh_piece((&dir, &name), share, &model, piece, coords, binary).map(drop);
    told(agree(world, written, "could not write its piece"))?;
    let stale = split_path(&dir, &name, world.size() as usize + 1);
    if world.rank() == 0 && stale.exists() {
        eprintln!(
            "note: {} is left from another set: remove it before reading {} as a split set",
            stale.display(),
            split_path(&dir, &name, 1).display()
        );
    }
    Ok(())
}

/// Every rank writes the failed state `coords` of its cells as
/// `OUT-STEM.failed_RANK.vtu` beside `output`, rank 0 the
/// `OUT-STEM.failed.pvtu` joining them (collective); returns that `.pvtu`.
pub fn write_failed(
    world: &Comm,
    output: &Path,
    mesh: &Mesh,
    coords: &[f64],
    orientation: &[i8],
) -> anyhow::Result<PathBuf> {
    let dir = output_dir(output);
    let name = format!("{}.failed", file_stem(output));
    write_vtu_pieces(world, (&dir, &name), mesh, coords, orientation)?;
    Ok(dir.join(format!("{name}.pvtu")))
}

/// Every rank writes its cells of `mesh` at `coords` as `dir/NAME_RANK.vtu`
/// (the displacement from the input, the quality and the rank), rank 0
/// `dir/NAME.pvtu` (collective).
fn write_vtu_pieces(
    world: &Comm,
    (dir, name): (&Path, &str),
    mesh: &Mesh,
    coords: &[f64],
    orientation: &[i8],
) -> anyhow::Result<()> {
    let dim = mesh.dim;
    let mut moved = mesh.clone();
    moved.coords = coords.to_vec();
    let mut displacement = vec![0.0; 3 * mesh.node_count()];
    for (i, (x, x0)) in coords.chunks(dim).zip(mesh.coords.chunks(dim)).enumerate() {
        for d in 0..dim {
            displacement[3 * i + d] = x[d] - x0[d];
        }
    }
    let quality = quality::qualities(mesh, coords, orientation);
    let written = write_local_piece(dir, name, world.rank(), &moved, displacement, quality);
    join_pieces(world, dir, name, written)
}

/// The first fresh element tag of this rank's MSH piece (collective): above
/// every element tag of every share, after the group facets of the lower
/// ranks, so that no two pieces give one tag to different elements
/// ([`verbss_mpi::pieces::msh_facet_tags`] takes at most one per facet).
fn first_fresh_tag(world: &Comm, share: &Share) -> anyhow::Result<u64> {
    let mesh = &share.mesh;
    let file_facets = share.labels.facet_tags.iter().flatten().flatten();
    let largest = world.max(
        mesh.cell_tags
            .iter()
            .chain(file_facets)
            .copied()
            .max()
            .unwrap_or(0),
    );
    let facets: u64 = mesh.groups.iter().map(|g| g.facets.len() as u64).sum();
    let counts: Vec<u64> = world.all_gather(&[facets]).iter().map(|c| c[0]).collect();
    // The same answer on every rank, so that all go on or all stop.
    if largest
        .checked_add(1 + counts.iter().sum::<u64>())
        .is_none()
    {
        bail!(
            "element tags up to {largest} leave no room for the tags of the group facets of \
             the MSH pieces"
        );
    }
    Ok(largest + 1 + counts[..world.rank() as usize].iter().sum::<u64>())
}

/// The model of the split set the ranks write (collective): every rank's
/// groups and partition entities ([`verbss::io::gmsh::split_write`]), the
/// same on every rank; and per group of this rank's share, its index in
/// the model.
fn split_model(
    world: &Comm,
    share: &Share,
    coords: &[f64],
    facet_tags: &[Vec<u64>],
) -> (SplitModel, Vec<usize>) {
    let mesh = &share.mesh;
    let encoded = world.all_gather(&encode_groups(mesh));
    let (groups, domain) = split_groups(&encoded, share.labels.domain.clone());
    let index: Vec<usize> = mesh
        .groups
        .iter()
        .map(|g| groups.iter().position(|m| m.name == g.name).unwrap_or(0))
        .collect();
    let mut model = SplitModel {
        dim: mesh.dim,
        groups,
        domain,
        partitions: world.size() as usize,
        entities: Vec::new(),
    };
    let piece = SplitPiece {
        mesh,
        coords,
        boundary: &share.boundary,
        groups: &index,
        facet_tags,
        partition: world.rank() as usize + 1,
    };
    let all = world.all_gather(&encode_entities(&piece.entities()));
    model.entities = decode_entities(&all);
    (model, index)
}
