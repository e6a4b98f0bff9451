//! `verbss-mpi deform` with a `.pvtu` output or `--pieces`: no rank holds
//! the whole mesh. Each rank reads its share — its own partitions of a
//! partitioned MSH 4.1 file ([`verbss_mpi::share::read_rank_share`]; with
//! `--split`, only its partitions' files of a split set,
//! [`verbss_mpi::share::read_rank_split`]), its PT-Scotch part of an SU2
//! file that rank 0 streams or of a CGNS file every rank reads in blocks
//! ([`crate::part_format`]) — adds the ghost layer and runs the
//! one deformer on its part ([`verbss_mpi::domain`]): the same job as
//! `verbss deform` ([`verbss_cli::deform::DeformArgs::prepare_on`]), the
//! same step loop and report ([`verbss_cli::run::execute`]), every option
//! but those that need the whole mesh in one process. Every rank writes its
//! own cells ([`crate::pieces_out`]); `--gather` also writes the whole
//! moved mesh from rank 0 ([`crate::gather`]).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::bail;
use verbss::io::gmsh::partitioned::Share;
use verbss::io::{Format, WriteOptions};
use verbss_cli::deform::DeformArgs;
use verbss_cli::run::execute;
use verbss_mpi::domain::PartDomain;
use verbss_mpi::share::{agree, global_numbers, read_rank_split};
use verbss_mpi::Comm;

use crate::gather;
use crate::part_format::{part_format, partitions_read};
use crate::pieces_out::{has_extension, prepare_output, Pieces};
use crate::run::told;

/// Whether `verbss-mpi deform` takes this path without `--pieces`: a
/// `.pvtu` output, which only a partitioned MSH 4.1, an SU2 or a CGNS
/// input is written to.
pub fn applies(args: &DeformArgs) -> bool {
    args.output().extension().is_some_and(|e| e == "pvtu")
}

/// This rank's share of the input, and what it says of where the share
/// comes from (the start of its line): of the first file of a split set
/// with `split`, else through the input format's
/// [`PartFormat`](crate::part_format::PartFormat).
fn read_input(
    world: &Comm,
    input: &Path,
    output: &Path,
    split: bool,
) -> anyhow::Result<(Share, String)> {
    if split {
        let share = told(read_rank_split(world, input))?;
        let from = partitions_read(world, &share, input)?;
        return Ok((share, from));
    }
    let reader = Format::from_path(input).ok().and_then(part_format);
    match reader {
        Some(reader) if reader.holds_parts(input)? => reader.read_part(world, input),
        _ => bail!(
            "{}: a .pvtu output or --pieces is written rank by rank, from a partitioned MSH \
             4.1 input (`gmsh -part N -format msh41`), an SU2 input or a CGNS input, and {} is \
             none of them: give another output format, or partition the mesh",
            output.display(),
            input.display()
        ),
    }
}

/// Refuses, with the reason, the options that need the whole mesh in one
/// process.
fn check_options(args: &DeformArgs) -> anyhow::Result<()> {
    let whole_mesh = [
        (args.given("solver"), "--solver (the direct solve)"),
        (args.given("accel"), "--accel (the multigrid)"),
        (args.zone_given(), "--zone"),
        (args.pictures_given(), "--html and --gif"),
    ];
    if let Some((_, option)) = whole_mesh.iter().find(|(given, _)| *given) {
        bail!(
            "{}: a partitioned input is read rank by rank, where {option} is not available \
             (it needs the whole mesh in one process)",
            args.mesh().display()
        );
    }
    Ok(())
}

/// Runs the job on every rank (see the module documentation); with
/// `gather`, rank 0 also writes the whole moved mesh there. With `split`,
/// the input is the first file of a split set.
pub fn run_parts(
    args: DeformArgs,
    gather: Option<PathBuf>,
    split: bool,
) -> anyhow::Result<ExitCode> {
    let world = Comm::world();
    let root = world.rank() == 0;
    check_options(&args)?;
    if let Some(path) = gather.as_ref().filter(|p| !has_extension(p, "vtu")) {
        bail!(
            "--gather {}: the gathered mesh is written as one .vtu file",
            path.display()
        );
    }
    let (share, from) = read_input(&world, args.mesh(), args.output(), split)?;
    let names: Vec<String> = share.group_nodes.iter().map(|(g, _)| g.clone()).collect();
    let part = told(PartDomain::new(
        &world,
        &share.mesh,
        &global_numbers(&share),
        &names,
    ))?;
    let mut prepared = told(agree(
        &world,
        args.prepare_on(
            part.mesh.clone(),
            &part.numbering(),
            WriteOptions::default(),
        )
        .map_err(|e| verbss::Error::InvalidSetting(e.to_string())),
        "could not prepare the job",
    ))?;
    let mut pieces = Pieces::new(&world, &args, &share, part.local())?;
    prepare_output(
        &world,
        (&pieces, &mut prepared, gather.as_deref()),
        args.mesh(),
        split,
    )?;
    let job = &prepared.job;
    if let Some(path) = &gather {
        gather::check_tags(&world, path, &share.mesh)?;
    }
    let local = part.local().to_vec();
    let part_nodes = part.mesh.node_count();
    let part_cells = part.mesh.cell_count();
    let mut deformer =
        told(part.deformer(&job.attachments, job.deformer_settings(&prepared.recorder)))?;
    if !prepared.quiet {
        println!(
            "rank {}: {from}: {} nodes and {} cells read; with the ghost layer {part_nodes} \
             nodes and {part_cells} cells",
            world.rank(),
            share.mesh.node_count(),
            share.mesh.cell_count(),
        );
        let (layer, thickness) = deformer.rigid_layer();
        if root && !thickness.is_empty() {
            let t: Vec<String> = thickness.iter().map(|t| format!("{t:.6e}")).collect();
            println!(
                "rigid layer: {layer} nodes, {} thick around each body",
                t.join(", ")
            );
        }
    }
    let quiet = prepared.quiet || !root;
    let mut summary = execute(
        job,
        &mut deformer,
        quiet,
        root,
        &mut prepared.recorder,
        &mut pieces,
    )?;
    summary.ranks = Some(world.size() as usize);
    if summary.failure.is_none() {
        if let Some(path) = &gather {
            let coords: Vec<f64> = local
                .iter()
                .flat_map(|&p| {
                    let dim = share.mesh.dim;
                    deformer.current().coords[dim * p..dim * (p + 1)].to_vec()
                })
                .collect();
            gather::gather(&world, path, &share, deformer.solver().part(), &coords)?;
        }
    }
    Ok(summary.print(job, root))
}
