//! The cost of one distributed sweep on 8 to 1,024 ranks, from real METIS
//! partitions of a mesh (no MPI needed): per rank the owned unknowns,
//! ghosts, neighbours, messages and bytes per sweep, and the modelled sweep
//! time and parallel efficiency ([`verbss_mpi::cost`]).
//!
//! ```text
//! cargo run --release -p verbss-mpi --example cost_model -- MESH --moving GROUP \
//!     [--parts 8,16,…] [--node-seconds T] [--latency A] [--bandwidth B]
//! ```
//!
//! `T`: seconds per node update measured on one rank (default 3.1e-7, the
//! 3D tetrahedral sweep of a million-node sphere, BENCHMARKS.md); `A`: seconds per
//! message (default 2e-6); `B`: bytes per second per rank (default 1e10).
//!
//! It needs METIS: built without (see `build.rs`), it says so and exits with 2.

#[cfg(with_mpi)]
fn main() -> anyhow::Result<()> {
    table::main()
}

#[cfg(not(with_mpi))]
fn main() -> std::process::ExitCode {
    eprintln!(
        "error: cost_model needs METIS, and this build of verbss-mpi has none ({})",
        verbss_mpi::missing().unwrap_or("unknown reason")
    );
    std::process::ExitCode::from(2)
}

/// The table, from METIS partitions.
#[cfg(with_mpi)]
mod table {
    use std::time::Instant;

    use anyhow::{bail, Context};
    use verbss::solve::{default_roles, NodeRole};
    use verbss::topology;
    use verbss_mpi::colouring::engine_colours;
    use verbss_mpi::cost::{count, Model};
    use verbss_mpi::partition::partition_graph;

    pub fn main() -> anyhow::Result<()> {
        let mut args = std::env::args().skip(1);
        let mut path = None;
        let mut moving = None;
        let mut parts: Vec<usize> = vec![8, 16, 32, 64, 128, 256, 512, 1024];
        let mut model = Model {
            node: 3.1e-7,
            latency: 2e-6,
            per_byte: 1e-10,
            dim: 3,
        };
        while let Some(a) = args.next() {
            let mut value = || args.next().with_context(|| format!("{a} needs a value"));
            match a.as_str() {
                "--moving" => moving = Some(value()?),
                "--parts" => {
                    parts = value()?
                        .split(',')
                        .map(|s| s.parse())
                        .collect::<Result<_, _>>()?
                }
                "--node-seconds" => model.node = value()?.parse()?,
                "--latency" => model.latency = value()?.parse()?,
                "--bandwidth" => model.per_byte = 1.0 / value()?.parse::<f64>()?,
                _ if path.is_none() => path = Some(a),
                _ => bail!("unexpected argument {a}"),
            }
        }
        let (Some(path), Some(moving)) = (path, moving) else {
            bail!("usage: cost_model MESH --moving GROUP [--parts 8,16,…] [--node-seconds T] [--latency A] [--bandwidth B]");
        };
        let mesh = verbss::io::read(path.as_ref())?;
        model.dim = mesh.dim;
        let graph = topology::node_graph(&mesh.cells, mesh.node_count());
        let roles = default_roles(&mesh);
        let seeds = mesh.group(&moving)?.nodes();
        let colours = engine_colours(&graph, &roles, &seeds);
        let unknowns = roles.iter().filter(|&&r| r != NodeRole::Fixed).count();
        let ncol = colours
            .iter()
            .filter(|&&c| c != u32::MAX)
            .max()
            .map_or(0, |c| c + 1);
        println!(
            "{path}: {} nodes, {} cells, {unknowns} unknown nodes, {ncol} colours; model: t = {:.3e} s/node, α = {:.1e} s, {:.1e} B/s",
            mesh.node_count(),
            mesh.cell_count(),
            model.node,
            model.latency,
            1.0 / model.per_byte
        );
        let serial = unknowns as f64 * model.node;
        println!();
        println!("| ranks | owned unknowns mean / max | ghosts mean / max | ghosts / owned | neighbours max | messages per sweep, max rank | kB per sweep, max rank | MB per sweep, all | modelled ms per sweep | speed-up | efficiency | METIS s |");
        println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
        for &p in &parts {
            let start = Instant::now();
            let owner = partition_graph(&graph, p)?;
            let metis = start.elapsed().as_secs_f64();
            let cost = count(&graph, &owner, &colours, p);
            let max = |f: &dyn Fn(&verbss_mpi::cost::RankCost) -> usize| {
                cost.ranks.iter().map(f).max().unwrap_or(0)
            };
            let mean = |f: &dyn Fn(&verbss_mpi::cost::RankCost) -> usize| {
                cost.ranks.iter().map(f).sum::<usize>() as f64 / p as f64
            };
            let values: usize = cost.ranks.iter().map(|r| r.values).sum();
            let bytes = 8 * mesh.dim;
            let t = model.seconds(&cost);
            println!(
                "| {p} | {:.0} / {} | {:.0} / {} | {:.2} | {} | {} | {:.1} | {:.2} | {:.3} | {:.0} | {:.0}% | {:.1} |",
                mean(&|r| r.owned),
                max(&|r| r.owned),
                mean(&|r| r.ghosts),
                max(&|r| r.ghosts),
                mean(&|r| r.ghosts) / mean(&|r| r.owned),
                max(&|r| r.neighbours),
                max(&|r| r.messages),
                (bytes * max(&|r| r.values)) as f64 / 1e3,
                (bytes * values) as f64 / 1e6,
                1e3 * t,
                serial / t,
                100.0 * serial / t / p as f64,
                metis
            );
        }
        Ok(())
    }
}
