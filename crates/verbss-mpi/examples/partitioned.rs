//! One solve on a partitioned MSH 4.1 file with no rank holding the whole
//! mesh: each rank reads its own partitions ([`verbss_mpi::share`]), the
//! flow-solver entry ([`verbss_mpi::coupled::LocalSolver`]) adds the ghost
//! layer and sweeps, and each rank writes its cells.
//!
//! ```text
//! mpirun -np P target/debug/examples/partitioned MESH.msh OUT.pvtu GROUP DX,DY[,DZ]
//! ```
//!
//! `GROUP` (comma separated groups) is translated by `DX,DY[,DZ]`, the
//! other boundary nodes stay, in one step of `--method verbss` to eq.-8
//! tolerance 1e-10. Every rank prints what it holds; rank `r` writes
//! `OUT-STEM_r.vtu` (its cells, moved, with `displacement`, `node_tag`,
//! `quality`, `rank`, `cell_tag`), rank 0 `OUT.pvtu`. Exit code 2 on bad
//! input (rank 0 prints the message), 3 when a cell inverts.

use std::process::ExitCode;

#[cfg(with_mpi)]
fn main() -> ExitCode {
    let Some(mpi) = verbss_mpi::Mpi::init() else {
        eprintln!("error: MPI could not be initialised");
        return ExitCode::from(2);
    };
    let world = mpi.world();
    let code = match run::run(&world) {
        Ok(code) => code,
        Err(e) => {
            if world.rank() == 0 {
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
        "error: this example needs MPI, and this build of verbss-mpi has none ({})",
        verbss_mpi::missing().unwrap_or("unknown reason")
    );
    ExitCode::from(2)
}

#[cfg(with_mpi)]
mod run {
    use std::path::PathBuf;
    use std::process::ExitCode;

    use anyhow::{bail, Context};
    use verbss::quality;
    use verbss::solve::SolveParams;
    use verbss_mpi::coupled::LocalSolver;
    use verbss_mpi::pieces::{write_local_piece, write_pvtu};
    use verbss_mpi::share::{global_numbers, prescribe, read_rank_share};
    use verbss_mpi::Comm;

    /// Reads, solves and writes (see the example's documentation).
    pub fn run(world: &Comm) -> anyhow::Result<ExitCode> {
        let args: Vec<String> = std::env::args().skip(1).collect();
        let [mesh, out, groups, translation] = &args[..] else {
            bail!("usage: partitioned MESH.msh OUT.pvtu GROUP DX,DY[,DZ]");
        };
        let out = PathBuf::from(out);
        if out.extension().is_none_or(|e| e != "pvtu") {
            bail!("{}: the output is a .pvtu file", out.display());
        }
        let share = read_rank_share(world, mesh.as_ref())?;
        let dim = share.mesh.dim;
        let d: Vec<f64> = translation
            .split(',')
            .map(str::parse)
            .collect::<Result<_, _>>()
            .with_context(|| format!("'{translation}': expected DX,DY[,DZ]"))?;
        if d.len() != dim || d.iter().any(|x| !x.is_finite()) {
            bail!("'{translation}': expected {dim} finite numbers for a {dim}D mesh");
        }
        let moving: Vec<String> = groups.split(',').map(String::from).collect();
        let (roles, mut u) = prescribe(&share, &moving, |_| d.clone())?;
        let global = global_numbers(&share);
        let mut solver = LocalSolver::new(world, &share.mesh, &global, &roles, &[])?;
        let part = solver.part();
        println!(
            "rank {}: read {} nodes and {} cells; with the ghost layer {} nodes and {} cells",
            world.rank(),
            share.mesh.node_count(),
            share.mesh.cell_count(),
            part.node_count(),
            part.cells.len()
        );
        let mut params = SolveParams::default();
        params.tolerance = 1e-10;
        let info = solver.solve(&share.mesh.coords, &mut u, &params)?;
        if world.rank() == 0 {
            println!("{} sweeps, converged: {}", info.iterations, info.converged);
        }
        let mut moved = share.mesh.clone();
        for (x, du) in moved.coords.iter_mut().zip(&u) {
            *x += du;
        }
        let reference = quality::orientation(&share.mesh);
        let inverted = quality::inverted_cells(&share.mesh, &moved.coords, &reference).len() as u64;
        let inverted = world.sum(inverted);
        let mut displacement = vec![0.0; 3 * share.mesh.node_count()];
        for (i, chunk) in u.chunks(dim).enumerate() {
            displacement[3 * i..3 * i + dim].copy_from_slice(chunk);
        }
        let quality = quality::qualities(&share.mesh, &moved.coords, &reference);
        let dir = match out.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let name = out
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        write_local_piece(&dir, &name, world.rank(), &moved, displacement, quality)?;
        world.barrier();
        if world.rank() == 0 {
            write_pvtu(&dir, &name, world.size())?;
        }
        if inverted > 0 {
            if world.rank() == 0 {
                eprintln!("error: {inverted} cells inverted");
            }
            return Ok(ExitCode::from(3));
        }
        Ok(ExitCode::SUCCESS)
    }
}
