//! What `verbss-mpi deform` without the whole mesh ([`crate::parts`])
//! writes, rank by rank, as [`Outputs`]: every rank's piece of the moved
//! mesh (a `.vtu` piece and rank 0 the `.pvtu`, or a partition of a split
//! MSH 4.1 set), the series of every K-th step as `.vtu` pieces joined by a
//! `.pvtu` per step and a `.pvd`, and after a failed step the failed state
//! as `.vtu` pieces `OUT-STEM.failed_RANK.vtu` joined by
//! `OUT-STEM.failed.pvtu`, as `verbss deform` writes `OUT-STEM.failed.vtu`.
//! Before the solve, the output's folder is made and the input kept unless
//! `--overwrite` says otherwise.

use std::path::{Path, PathBuf};

use anyhow::bail;
use verbss::deform::Snapshot;
use verbss::io::gmsh::partitioned::Share;
use verbss::io::gmsh::split::split_file;
use verbss::io::gmsh::split_write::{SplitModel, SplitPiece};
use verbss::io::outputs::{Input, Output, MESH};
use verbss::{quality, Mesh};
use verbss_cli::deform::DeformArgs;
use verbss_cli::overwrite::check_outputs;
use verbss_cli::run::{file_stem, output_dir, Job, Outputs, Prepared};
use verbss_mpi::pieces::{
    decode_entities, encode_entities, encode_groups, msh_facet_tags, piece_path, split_groups,
    split_path, write_local_piece, write_msh_piece,
};
use verbss_mpi::share::agree;
use verbss_mpi::Comm;

use crate::run::{join_pieces, told};

/// The pieces a rank writes of its share.
pub struct Pieces<'a> {
    world: &'a Comm,
    share: &'a Share,
    /// The part index of each of the share's nodes.
    local: Vec<usize>,
    output: PathBuf,
    /// MSH pieces binary (`true`) or ASCII, `None` for as the input.
    binary: Option<bool>,
    overwrite: bool,
    orientation: Vec<i8>,
    /// The series written so far: time and `.pvtu` name.
    series: Vec<(f64, String)>,
}

impl<'a> Pieces<'a> {
    /// The pieces of `share` (its node `i` the part's node `local[i]`) that
    /// `args` ask for: a `.pvtu` output, or MSH pieces for a `.msh` one.
    pub fn new(
        world: &'a Comm,
        args: &DeformArgs,
        share: &'a Share,
        local: &[usize],
    ) -> anyhow::Result<Pieces<'a>> {
        let output = args.output().to_path_buf();
        if !has_extension(&output, "pvtu") && !has_extension(&output, "msh") {
            bail!(
                "{}: a partitioned input is written rank by rank: the output is a .pvtu file \
                 (one .vtu piece per rank beside it) or a .msh name (one MSH 4.1 piece per \
                 rank beside it)",
                output.display()
            );
        }
        let binary = match has_extension(&output, "msh") {
            true => args.split_encoding()?,
            false => None,
        };
        Ok(Pieces {
            world,
            share,
            local: local.to_vec(),
            binary,
            overwrite: args.overwrite(),
            orientation: quality::orientation(&share.mesh),
            output,
            series: Vec::new(),
        })
    }

    /// The files the `ranks` write of `job`: the pieces of the moved mesh
    /// (`-o`), of the series (`--every`) and of the failed state.
    fn files(&self, job: &Job, ranks: i32) -> Vec<Output> {
        let dir = output_dir(&self.output);
        let stem = file_stem(&self.output);
        let vtu = |flag: &str, name: &str| -> Vec<Output> {
            let pieces = (0..ranks).map(|r| Output::new(flag, piece_path(&dir, name, r)));
            pieces
                .chain([Output::new(flag, dir.join(format!("{name}.pvtu")))])
                .collect()
        };
        let mut files: Vec<Output> = match has_extension(&self.output, "msh") {
            true => (1..=ranks as usize)
                .map(|k| Output {
                    overwrite: Some(self.overwrite),
                    ..Output::new("-o", split_path(&dir, &stem, k))
                })
                .collect(),
            false => vtu("-o", &stem),
        };
        if job.series {
            let steps = std::iter::once(0).chain(job.written_steps(job.settings.steps));
            for n in steps {
                files.extend(vtu("--every", &format!("{stem}_{n:04}")));
            }
            files.push(Output::new("--every", dir.join(format!("{stem}.pvd"))));
        }
        files.extend(vtu("the failed state", &format!("{stem}.failed")));
        files
    }

    /// The share's coordinates in the part's `coords`.
    fn share_coords(&self, coords: &[f64]) -> Vec<f64> {
        let dim = self.share.mesh.dim;
        self.local
            .iter()
            .flat_map(|&p| &coords[dim * p..dim * (p + 1)])
            .copied()
            .collect()
    }
}

impl Outputs for Pieces<'_> {
    /// `OUT-STEM_NNNN_RANK.vtu`, rank 0 `OUT-STEM_NNNN.pvtu` and
    /// `OUT-STEM.pvd` rewritten with it added (time `n·dt`).
    fn step(&mut self, job: &Job, s: &Snapshot) -> anyhow::Result<()> {
        let dir = output_dir(&self.output);
        let name = format!("{}_{:04}", file_stem(&self.output), s.report.step);
        let coords = self.share_coords(&s.coords);
        write_vtu_pieces(
            self.world,
            (&dir, &name),
            &self.share.mesh,
            &coords,
            &self.orientation,
        )?;
        self.series.push((
            s.report.step as f64 * job.settings.dt,
            format!("{name}.pvtu"),
        ));
        let pvd = dir.join(format!("{}.pvd", file_stem(&self.output)));
        let written = match self.world.rank() {
            0 => verbss::io::pvd::write(&pvd, &self.series),
            _ => Ok(()),
        };
        told(agree(self.world, written, "could not write the .pvd"))
    }

    fn last(&mut self, _: &Job, coords: &[f64], _: usize) -> anyhow::Result<PathBuf> {
        let coords = self.share_coords(coords);
        write(
            self.world,
            (&self.output, self.binary),
            self.share,
            &coords,
            &self.orientation,
        )?;
        Ok(PathBuf::from(written_name(&self.output, self.world.size())))
    }

    fn failed(&mut self, _: &Job, s: &Snapshot) -> anyhow::Result<PathBuf> {
        let coords = self.share_coords(&s.coords);
        write_failed(
            self.world,
            &self.output,
            &self.share.mesh,
            &coords,
            &self.orientation,
        )
    }
}

/// Whether `path` has the extension `ext`, in any case.
pub fn has_extension(path: &Path, ext: &str) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case(ext))
}

/// Before the solve (collective): makes the folders of the output, of the
/// report and of the gathered mesh (`gather`), and fails on every rank
/// where a file the ranks write ([`Pieces::files`], the report, `gather`)
/// is an input (`input`, or with `split` the files of its set; a rank's
/// MSH piece may be one with `--overwrite`), another output or no regular
/// file.
pub fn prepare_output(
    world: &Comm,
    (pieces, prepared, gather): (&Pieces, &mut Prepared, Option<&Path>),
    input: &Path,
    split: bool,
) -> anyhow::Result<()> {
    let check = |prepared: &mut Prepared| -> anyhow::Result<()> {
        let job = &mut prepared.job;
        let outputs = [Some(pieces.output.as_path()), job.report.as_deref(), gather];
        for folder in outputs.into_iter().flatten().map(output_dir) {
            std::fs::create_dir_all(&folder).map_err(|e| {
                anyhow::anyhow!("{}: cannot make the folder: {e}", folder.display())
            })?;
        }
        if split {
            job.inputs.retain(|i| i.what != MESH);
            for k in 1..=pieces.share.partitions {
                let path = split_file(input, k)?;
                job.inputs.push(Input { what: MESH, path });
            }
        }
        let mut files = pieces.files(job, world.size());
        files.extend(gather.map(|p| Output::new("--gather", p)));
        Ok(check_outputs(&prepared.job, &prepared.recorder, files)?)
    };
    let checked = check(prepared).map_err(|e| verbss::Error::InvalidSetting(e.to_string()));
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
