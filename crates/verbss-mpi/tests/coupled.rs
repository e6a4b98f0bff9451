//! The flow-solver entry point ([`verbss_mpi::coupled::LocalSolver`]) on
//! partitions it did not make: each rank gets a contiguous block of the
//! file's cells with its nodes numbered backwards, as a flow solver might
//! hold them. The converged displacements match the exact (direct) solution
//! of one process, and 1, 2 and 3 ranks agree to rounding.
//!
//! The test re-runs this test binary under `mpirun` with the ignored
//! `worker` test, which writes each rank's displacements to a file. Without
//! MPI (in this build or `mpirun`) the tests skip with a notice.

use std::path::{Path, PathBuf};

use verbss::solve::{default_roles, Engine, Method, NodeRole, SolveParams, Solver};
use verbss::Mesh;

mod common;

fn mesh_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/meshes")
        .join(name)
}

/// The case: roles (boundary fixed) and prescribed displacement (the
/// moving group translated).
fn case(mesh: &Mesh, group: &str) -> (Vec<NodeRole>, Vec<f64>) {
    let roles = default_roles(mesh);
    let dim = mesh.dim;
    let mut u = vec![0.0; dim * mesh.node_count()];
    for i in mesh.group(group).unwrap().nodes() {
        u[dim * i + 1] = 0.01;
        u[dim * i] = 0.02;
    }
    (roles, u)
}

/// Worker, one per rank (run by `mpirun` from the tests below): the
/// local mesh of this rank, the solve, and `gid u…` lines in
/// `$VERBSS_MPI_OUT.RANK`.
#[cfg(with_mpi)]
#[test]
#[ignore = "run under mpirun by the other tests"]
fn worker() {
    use std::collections::HashMap;
    use verbss::Cells;
    use verbss_mpi::coupled::LocalSolver;

    /// The eq.-8 tolerance of the distributed solves: tight, so that the
    /// sweeps' result is the converged solution.
    const TOLERANCE: f64 = 1e-13;

    let mpi = verbss_mpi::Mpi::init().unwrap();
    // The communicator as a flow solver hands it over: its Fortran handle.
    let world = verbss_mpi::Comm::from_fortran(mpi.world().fortran()).unwrap();
    let (rank, size) = (world.rank() as usize, world.size() as usize);
    let name = std::env::var("VERBSS_MPI_MESH").unwrap();
    let group = std::env::var("VERBSS_MPI_GROUP").unwrap();
    let out = std::env::var("VERBSS_MPI_OUT").unwrap();
    let mesh = verbss::io::read(&mesh_path(&name)).unwrap();
    let (roles, u) = case(&mesh, &group);
    let dim = mesh.dim;
    let cells = mesh.cell_count();
    let (first, last) = (rank * cells / size, (rank + 1) * cells / size);
    let mut used: Vec<usize> = (first..last)
        .flat_map(|c| mesh.cells.cell(c).to_vec())
        .collect();
    used.sort_unstable();
    used.dedup();
    used.reverse();
    let local: HashMap<usize, usize> = used.iter().enumerate().map(|(k, &g)| (g, k)).collect();
    let mut local_cells = Cells::new();
    for c in first..last {
        let nodes: Vec<usize> = mesh.cells.cell(c).iter().map(|v| local[v]).collect();
        local_cells.push(mesh.cells.kinds[c], &nodes);
    }
    let pick = |a: &[f64]| -> Vec<f64> {
        used.iter()
            .flat_map(|&g| a[dim * g..dim * (g + 1)].to_vec())
            .collect()
    };
    let coords = pick(&mesh.coords);
    let local_mesh = Mesh::new(dim, coords.clone(), local_cells, Vec::new()).unwrap();
    let global: Vec<u64> = used.iter().map(|&g| g as u64).collect();
    let local_roles: Vec<NodeRole> = used.iter().map(|&g| roles[g]).collect();
    let mut solver = LocalSolver::new(&world, &local_mesh, &global, &local_roles, &[]).unwrap();
    let mut displacement = pick(&u);
    let mut params = SolveParams::default();
    let info = if std::env::var("VERBSS_MPI_SOLVE").is_ok_and(|s| s == "exact") {
        // Three plain sweeps, then the solve to round-off from there.
        let mut rough = params.clone();
        (rough.max_iterations, rough.escalate) = (3, false);
        solver.solve(&coords, &mut displacement, &rough).unwrap();
        let info = solver
            .solve_exact(&coords, &mut displacement, &params)
            .unwrap();
        assert_eq!(info.stages, [verbss::solve::Stage::Gmres], "{info:?}");
        info
    } else {
        params.tolerance = TOLERANCE;
        params.max_iterations = 100_000;
        solver.solve(&coords, &mut displacement, &params).unwrap()
    };
    assert!(info.converged, "{info:?}");
    let mut text = String::new();
    for (k, &g) in used.iter().enumerate() {
        text += &format!("{g}");
        for d in 0..dim {
            text += &format!(" {:e}", displacement[dim * k + d]);
        }
        text += "\n";
    }
    std::fs::write(format!("{out}.{rank}"), text).unwrap();
}

/// Runs the worker on `np` ranks with `solve` (`sweeps` or `exact`, the
/// solve to round-off after three sweeps); every node's displacement (the
/// copies on several ranks must be equal).
fn distributed(
    np: usize,
    mesh: &str,
    group: &str,
    solve: &str,
    dim: usize,
    nodes: usize,
) -> Vec<f64> {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("u");
    let o = common::mpirun(np, dir.path())
        .env("VERBSS_MPI_SOLVE", solve)
        .env("VERBSS_MPI_MESH", mesh)
        .env("VERBSS_MPI_GROUP", group)
        .env("VERBSS_MPI_OUT", &out)
        .arg(std::env::current_exe().unwrap())
        .args(["worker", "--exact", "--ignored", "--test-threads", "1"])
        .output()
        .expect("run mpirun (Debian: openmpi-bin)");
    assert!(
        o.status.success(),
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    let mut u = vec![f64::NAN; dim * nodes];
    for r in 0..np {
        let text = std::fs::read_to_string(format!("{}.{r}", out.display())).unwrap();
        for line in text.lines() {
            let mut parts = line.split(' ');
            let g: usize = parts.next().unwrap().parse().unwrap();
            for d in 0..dim {
                let v: f64 = parts.next().unwrap().parse().unwrap();
                let slot = &mut u[dim * g + d];
                assert!(slot.is_nan() || *slot == v, "node {g}: {} and {v}", *slot);
                *slot = v;
            }
        }
    }
    assert!(u.iter().all(|v| !v.is_nan()), "every node is on some rank");
    u
}

/// The exact solution of the same system on one process (sparse LU).
fn direct(mesh: &Mesh, group: &str) -> Vec<f64> {
    let (roles, mut u) = case(mesh, group);
    let mut engine = Engine::new(mesh, &roles, &[]).unwrap();
    let mut params = SolveParams::default();
    params.method = Method::BallVertex;
    params.solver = Solver::Direct;
    engine.solve(&mesh.coords, &mut u, &params).unwrap();
    u
}

fn max_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

/// 1, 2 and 3 ranks solving with `solve` against the direct solution
/// (relative to the largest prescribed displacement, |(0.02, 0.01)|), and
/// against each other within `spread_bound`.
fn matches_direct(name: &str, group: &str, solve: &str, bound: f64, spread_bound: f64) {
    let mesh = verbss::io::read(&mesh_path(name)).unwrap();
    let exact = direct(&mesh, group);
    let scale = (0.02f64 * 0.02 + 0.01 * 0.01).sqrt();
    let (dim, n) = (mesh.dim, mesh.node_count());
    let one = distributed(1, name, group, solve, dim, n);
    let error = max_difference(&one, &exact) / scale;
    assert!(error < bound, "1 rank: error {error:e}");
    for np in [2, 3] {
        let u = distributed(np, name, group, solve, dim, n);
        let error = max_difference(&u, &exact) / scale;
        assert!(error < bound, "{np} ranks: error {error:e}");
        let spread = max_difference(&u, &one) / scale;
        assert!(spread < spread_bound, "{np} ranks against 1: {spread:e}");
    }
}

#[test]
fn naca0012_partitions_match_the_direct_solution() {
    if !common::mpi_ready() {
        return;
    }
    matches_direct(
        "su2/mesh_NACA0012_inv.su2",
        "airfoil",
        "sweeps",
        1e-10,
        1e-12,
    );
}

#[test]
fn tetrahedral_brick_partitions_match_the_direct_solution() {
    if !common::mpi_ready() {
        return;
    }
    matches_direct("su2/mesh_brick_tets_ffd.su2", "z_p", "sweeps", 1e-10, 1e-12);
}

/// The solve to round-off that judges an inverted cell (GMRES
/// preconditioned by the sweep, from three sweeps) gives the direct
/// solution on 1, 2 and 3 ranks: the hybrid channel around a hole (2D) and
/// the tetrahedral box (3D), small, since this stage takes hundreds of
/// iterations. Its inner products are summed in another order on each
/// rank count, so the ranks agree to its round-off, not to the bit.
#[test]
fn the_solve_to_round_off_matches_the_direct_solution() {
    if !common::mpi_ready() {
        return;
    }
    matches_direct(
        "gmsh/channel_hole_v41_ascii.msh",
        "wall",
        "exact",
        1e-9,
        1e-9,
    );
    matches_direct("gmsh/box_v41_ascii.msh", "inlet", "exact", 1e-9, 1e-9);
}
