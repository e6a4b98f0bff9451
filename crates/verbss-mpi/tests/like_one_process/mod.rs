//! What the tests of `verbss-mpi deform` with a `.pvtu` output share: the
//! run under `mpirun`, the single-process run it is compared with, and the
//! comparison. Each test file uses what it needs of it.
#![allow(dead_code)]

use std::collections::HashMap;
use std::path::Path;

use verbss::deform::{Deformer, Preset, Reference};
use verbss::motion::{Attachment, Motion};
use verbss::Mesh;

use crate::common;

/// `mpirun -np NP verbss-mpi ARGS…` with the environment variables `env`
/// (`mpirun -x` passes them to every rank).
pub fn verbss_mpi_with(
    np: usize,
    args: &[&str],
    session: &Path,
    env: &[(&str, &str)],
) -> std::process::Output {
    let mut command = common::mpirun(np, session);
    for (key, value) in env {
        command.env(key, value).args(["-x", key]);
    }
    command
        .arg(env!("CARGO_BIN_EXE_verbss-mpi"))
        .args(args)
        .output()
        .expect("run mpirun (Debian: openmpi-bin)")
}

/// The single-process run of the paper's method (the stepper of `verbss
/// deform --method verbss`, without escalation: the sweeps converge).
pub fn single(
    whole: &Mesh,
    group: &str,
    motion: Motion,
    steps: usize,
    reference: Reference,
) -> Mesh {
    let mut settings = Preset::Verbss.settings(steps);
    settings.reference = reference;
    settings.solve.tolerance = TOLERANCE;
    settings.solve.escalate = false;
    settings.solve.max_iterations = 100_000;
    let attachments = [Attachment {
        groups: vec![group.into()],
        motion,
    }];
    let mut d = Deformer::new(whole, &attachments, settings).unwrap();
    for n in 1..=steps {
        d.step(n).unwrap();
    }
    d.mesh()
}

/// Whether MPI and PT-Scotch are here (an SU2 input's path needs both);
/// otherwise the test skips.
pub fn ptscotch_ready() -> bool {
    common::mpi_ready()
        && verbss_testkit::needs(
            "PT-Scotch when verbss-mpi is built (Debian: libptscotch-dev \
             libscotchparmetis-dev, then cargo clean -p verbss-mpi)",
            verbss_mpi::ptscotch_missing().map_or(Ok(()), |why| Err(why.into())),
        )
}

/// Each node's index in `mesh` by its tag (the pieces keep the tags).
pub fn node_index(mesh: &Mesh) -> HashMap<u64, usize> {
    mesh.node_tags
        .iter()
        .enumerate()
        .map(|(i, &t)| (t, i))
        .collect()
}

/// The eq.-8 tolerance of both runs.
pub const TOLERANCE: f64 = 1e-12;

/// `verbss-mpi deform` on `mesh` with a `.pvtu` output on 1, 2 and 3 ranks
/// (the environment variables `env` set on every rank): the pieces hold
/// every cell of the file once, at the single-process run's coordinates to
/// 1e-10 of the largest displacement `scale`. The standard output of each
/// run, 1 to 3 ranks.
pub fn deforms_like_one_process(
    mesh: &Path,
    group: &str,
    motion: &[&str],
    reference: Reference,
    scale: f64,
    env: &[(&str, &str)],
) -> Vec<String> {
    let whole = verbss::io::read(mesh).unwrap();
    let name = mesh.display();
    let motion_of = match motion[0] {
        "--translate" => {
            let d: Vec<f64> = motion[1].split(',').map(|x| x.parse().unwrap()).collect();
            Motion::Translation {
                displacement: [d[0], d[1], d.get(2).copied().unwrap_or(0.0)],
            }
        }
        _ => Motion::Rotation {
            center: [0.5, 0.5, 0.5],
            axis: [0.0, 0.0, 1.0],
            angle: motion[1].parse::<f64>().unwrap().to_radians(),
        },
    };
    let one = single(&whole, group, motion_of, 2, reference);
    let index = node_index(&whole);
    let dim = whole.dim;
    let reference = match reference {
        Reference::Fixed => "fixed",
        _ => "updated",
    };
    let mut stdouts = Vec::new();
    for np in 1..=3 {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("moved.pvtu");
        let tolerance = TOLERANCE.to_string();
        let mut args = vec![
            "deform",
            mesh.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--moving",
            group,
            "--method",
            "verbss",
            "--steps",
            "2",
            "--reference",
            reference,
            "--tolerance",
            &tolerance,
            "--max-iterations",
            "100000",
        ];
        args.extend_from_slice(motion);
        let o = verbss_mpi_with(np, &args, dir.path(), env);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let mut cells = Vec::new();
        let mut worst = 0.0f64;
        for r in 0..np {
            let piece = verbss::io::read(&dir.path().join(format!("moved_{r}.vtu"))).unwrap();
            cells.extend_from_slice(&piece.cell_tags);
            for (i, t) in piece.node_tags.iter().enumerate() {
                let g = index[t];
                for d in 0..dim {
                    worst = worst.max((piece.coords[dim * i + d] - one.coords[dim * g + d]).abs());
                }
            }
        }
        cells.sort_unstable();
        let mut all = whole.cell_tags.clone();
        all.sort_unstable();
        assert_eq!(cells, all, "{name}: {np} ranks");
        assert!(worst < 1e-10 * scale, "{name}: {np} ranks: {worst:e}");
        let pvtu = std::fs::read_to_string(&out).unwrap();
        assert_eq!(pvtu.matches("<Piece ").count(), np);
        stdouts.push(String::from_utf8_lossy(&o.stdout).into_owned());
    }
    stdouts
}
