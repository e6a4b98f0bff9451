//! `mpirun -np N verbss-mpi deform MESH -o OUT …`: `verbss deform` with the
//! sweeps spread over N MPI ranks.
//!
//! The arguments are those of `verbss deform`, parsed and prepared by the
//! command line's library ([`verbss_cli::deform`]), and the steps are those
//! of the one deformer ([`verbss::deform::Deformer`]) run by `verbss`'s own
//! runner ([`verbss_cli::run::execute`]), on one of two domains:
//!
//! * every rank holds the whole mesh ([`run::run_distributed`]): the
//!   springs are solved over the ranks ([`verbss_mpi::stepper`]); rank 0
//!   prints and writes OUT and the report; every rank writes its piece
//!   `OUT-STEM_RANK.vtu` beside OUT, and rank 0 the `OUT-STEM.pvtu`
//!   joining them;
//! * a `.pvtu` output or `--pieces`, from a partitioned MSH 4.1 input, an
//!   SU2 input or a CGNS input ([`parts::run_parts`]): no rank holds the
//!   whole mesh; every rank reads only its own partitions (MSH), rank 0
//!   streams the file to the others (SU2, [`su2`]) or every rank reads its
//!   own blocks (CGNS, [`cgns`]) and PT-Scotch cuts it; every rank writes
//!   only its own cells (a `.vtu` or an MSH 4.1 piece). With `--split`, the
//!   MSH input is a set of files, one a partition (`gmsh -part_split`, or
//!   the pieces of an earlier run), each rank reading its own.
//!
//! Exit codes as `verbss`: 0 success, 2 bad input, 3 an inverted element,
//! 4 a step no solver could solve. Built without MPI or METIS (see
//! `build.rs`), it says so and exits with 2.

#![forbid(unsafe_code)]

#[cfg(with_mpi)]
mod cgns;
#[cfg(with_mpi)]
mod gather;
#[cfg(with_mpi)]
mod part_format;
#[cfg(with_mpi)]
mod parts;
#[cfg(with_mpi)]
mod pieces_out;
#[cfg(with_mpi)]
mod run;
#[cfg(with_mpi)]
mod su2;

use std::process::ExitCode;

#[cfg(with_mpi)]
use std::path::PathBuf;

#[cfg(with_mpi)]
use clap::{Args, Parser, Subcommand};
#[cfg(with_mpi)]
use verbss_cli::deform;

/// Mesh motion by Vertex-Ball Spring Smoothing over MPI ranks (run under mpirun).
#[cfg(with_mpi)]
#[derive(Parser)]
#[command(name = "verbss-mpi", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[cfg(with_mpi)]
#[derive(Subcommand)]
enum Command {
    /// Move groups by a translation, a rotation or given positions, in N steps.
    Deform(Box<MpiDeformArgs>),
}

/// The arguments of `verbss deform`, and what only `verbss-mpi deform` has.
#[cfg(with_mpi)]
#[derive(Args)]
struct MpiDeformArgs {
    #[command(flatten)]
    deform: deform::DeformArgs,
    /// With a .pvtu output from a partitioned MSH 4.1, an SU2 or a CGNS input: rank
    /// 0 also writes the whole moved mesh here as one .vtu, received rank by
    /// rank in bounded messages.
    #[arg(long, value_name = "FILE.vtu")]
    gather: Option<PathBuf>,
    /// From a partitioned MSH 4.1 or an SU2 input: no rank holds the whole
    /// mesh, each writes its own cells as a piece beside OUT: for OUT.msh,
    /// partition RANK+1 of a split set OUT-STEM_1.msh … OUT-STEM_P.msh (MSH
    /// 4.1, as `gmsh -part_split`); OUT-STEM_RANK.vtu and OUT.pvtu for OUT.pvtu
    /// (which implies --pieces).
    #[arg(long)]
    pieces: bool,
    /// MESH is the first file NAME_1.msh of a split set, NAME_1.msh to
    /// NAME_K.msh (`gmsh -part K -part_split`, or the MSH pieces of --pieces):
    /// each rank reads only its partitions' files. Needs --pieces or a .pvtu
    /// output.
    #[arg(long)]
    split: bool,
}

#[cfg(with_mpi)]
fn main() -> ExitCode {
    let Some(mpi) = verbss_mpi::Mpi::init() else {
        eprintln!("error: MPI could not be initialised");
        return ExitCode::from(2);
    };
    // A usage error, `--help` or `--version`: said once, by rank 0.
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            if run::is_root() {
                let _ = e.print();
            }
            let code = e.exit_code();
            drop(mpi);
            return ExitCode::from(u8::try_from(code).unwrap_or(2));
        }
    };
    let result = match cli.command {
        Command::Deform(args) if args.pieces || parts::applies(&args.deform) => {
            parts::run_parts(args.deform, args.gather, args.split)
        }
        Command::Deform(args) if args.split => Err(anyhow::anyhow!(
            "--split {}: a split set is read rank by rank, for --pieces or a .pvtu output",
            args.deform.mesh().display()
        )),
        Command::Deform(args) => match args.gather {
            Some(path) => Err(anyhow::anyhow!(
                "--gather {}: only a .pvtu output or --pieces (from a partitioned MSH 4.1, an \
                 SU2 or a CGNS input) is gathered; this output is already the whole mesh",
                path.display()
            )),
            None => deform::prepare(args.deform).and_then(run::run_distributed),
        },
    };
    let code = match result {
        Ok(code) => code,
        Err(e) => {
            if run::is_root() {
                eprintln!("error: {e}");
            }
            ExitCode::from(2)
        }
    };
    drop(mpi);
    code
}

#[cfg(not(with_mpi))]
fn main() -> ExitCode {
    eprintln!(
        "error: verbss-mpi was built without MPI/METIS ({}): install Open MPI and METIS \
         (Debian: libopenmpi-dev openmpi-bin libmetis-dev), then `cargo clean -p verbss-mpi` \
         and build again",
        verbss_mpi::missing().unwrap_or("unknown reason")
    );
    ExitCode::from(2)
}
