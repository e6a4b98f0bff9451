//! `mpirun -np N verbss-mpi deform …` on the shared meshes against the
//! single-process stepper (what `verbss deform` runs): the same output file
//! for 1, 2 and 3 ranks, per-rank pieces that cover the mesh once, and the
//! messages of bad input. Without MPI (in this build or `mpirun`) the tests
//! skip with a notice, and without python3 and meshio the pieces are not
//! read back by meshio.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

mod common;

use verbss::deform::Deformer;
use verbss::io::{self, WriteOptions};
use verbss::motion::{Attachment, Motion};
use verbss::near_wall::Robust;
use verbss::settings::{Predictor, Reference, Settings};
use verbss::Mesh;
use verbss_testkit::{needs, python};

use common::mpi_ready;

/// `mpirun --oversubscribe -np N verbss-mpi ARGS…` ([`common::mpirun`]).
fn mpirun(np: usize, args: &[&str]) -> Output {
    let session = tempfile::tempdir().unwrap();
    common::mpirun(np, session.path())
        .arg(env!("CARGO_BIN_EXE_verbss-mpi"))
        .args(args)
        .output()
        .expect("run mpirun (Debian: openmpi-bin)")
}

fn mesh(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/meshes/su2")
        .join(name)
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Enough sweeps for every step here to meet its stop (an unconverged step
/// is an error).
const MAX_SWEEPS: usize = 20_000;

/// The near-wall treatments of `verbss deform`'s default `--method robust`.
fn robust(settings: &mut Settings) {
    settings.robust = Robust::recommended();
}

/// The paper's method (`--method verbss`): no near-wall treatment.
fn paper(settings: &mut Settings) {
    settings.robust = Robust::off();
}

/// The single-process result: the stepper `verbss deform` runs, with the
/// settings `configure` gives, written in the output's format.
fn single(
    input: &Path,
    attachments: &[Attachment],
    steps: usize,
    configure: fn(&mut Settings),
    out: &Path,
) -> Mesh {
    let mesh = io::read(input).unwrap();
    let mut settings = Settings::new(steps);
    configure(&mut settings);
    // The distributed solve escalates only from unconverged sweeps to the
    // exact solve, which never happens here: the single-process reference
    // is the configured sweeps alone.
    settings.solve.escalate = false;
    settings.solve.max_iterations = MAX_SWEEPS;
    let mut d = Deformer::new(&mesh, attachments, settings).unwrap();
    for n in 1..=steps {
        d.step(n).unwrap();
    }
    io::write(out, &d.mesh(), &WriteOptions::default()).unwrap();
    d.mesh()
}

/// Largest coordinate difference relative to the largest coordinate.
fn relative_difference(a: &Mesh, b: &Mesh) -> f64 {
    let scale = a.coords.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let diff = a
        .coords
        .iter()
        .zip(&b.coords)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    diff / scale
}

/// Runs `verbss-mpi deform` on 1, 2 and 3 ranks and checks each output
/// against the single-process one (1e-12 relative; in practice the files
/// are byte for byte the same) and the pieces against the mesh.
fn same_as_single(
    input: &Path,
    extra: &[&str],
    attachments: &[Attachment],
    steps: usize,
    configure: fn(&mut Settings),
) {
    let dir = tempfile::tempdir().unwrap();
    let reference = dir.path().join("single.su2");
    let expected = single(input, attachments, steps, configure, &reference);
    let whole = io::read(input).unwrap();
    let meshio = needs(
        "python3 with meshio (pip install meshio)",
        python(&["meshio"]),
    );
    for np in 1..=3 {
        let out = dir.path().join(format!("np{np}.su2"));
        let steps = steps.to_string();
        let max_sweeps = MAX_SWEEPS.to_string();
        let mut args = vec![
            "deform",
            input.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--steps",
            &steps,
            "--max-iterations",
            &max_sweeps,
            "--quiet",
        ];
        args.extend_from_slice(extra);
        let o = mpirun(np, &args);
        assert!(o.status.success(), "{np} ranks: {}", stderr(&o));
        let got = io::read(&out).unwrap();
        assert_eq!(got.cells, expected.cells);
        assert_eq!(got.node_tags, expected.node_tags);
        let diff = relative_difference(&expected, &got);
        assert!(diff <= 1e-12, "{np} ranks: relative difference {diff:e}");
        check_pieces(dir.path(), &format!("np{np}"), np, &whole, &got, meshio);
    }
}

/// The `.pvtu` names `np` pieces; together they hold every cell once, with
/// the moved coordinates; with `meshio`, meshio reads each piece.
fn check_pieces(dir: &Path, name: &str, np: usize, whole: &Mesh, moved: &Mesh, meshio: bool) {
    let pvtu = std::fs::read_to_string(dir.join(format!("{name}.pvtu"))).unwrap();
    let mut cell_seen = vec![0u32; whole.cell_count()];
    // The pieces carry the input's tags (1..N for SU2, Gmsh's own for MSH).
    let index = |tags: &[u64]| -> std::collections::HashMap<u64, usize> {
        tags.iter().enumerate().map(|(i, &t)| (t, i)).collect()
    };
    let (node_of, cell_of) = (index(&whole.node_tags), index(&whole.cell_tags));
    for r in 0..np {
        let piece = format!("{name}_{r}.vtu");
        assert!(
            pvtu.contains(&format!(r#"<Piece Source="{piece}"/>"#)),
            "{pvtu}"
        );
        let data = io::vtu::read(&dir.join(&piece)).unwrap();
        for (i, tag) in data.mesh.node_tags.iter().enumerate() {
            assert_eq!(
                data.mesh.point(i),
                moved.point(node_of[tag]),
                "piece {r} node {tag}"
            );
        }
        for tag in &data.mesh.cell_tags {
            cell_seen[cell_of[tag]] += 1;
        }
        let rank = &data.fields.cell.iter().find(|f| f.0 == "rank").unwrap().2;
        assert!(rank.iter().all(|&v| v == r as f64));
        if meshio {
            let o = Command::new("python3")
                .args([
                    "-c",
                    "import meshio,sys; m=meshio.read(sys.argv[1]); print(sum(len(c.data) for c in m.cells))",
                ])
                .arg(dir.join(&piece))
                .output()
                .unwrap();
            assert!(o.status.success(), "{}", stderr(&o));
            let cells: usize = String::from_utf8_lossy(&o.stdout).trim().parse().unwrap();
            assert_eq!(cells, data.mesh.cell_count());
        }
    }
    assert!(cell_seen.iter().all(|&k| k == 1));
    assert!(pvtu.matches("<Piece ").count() == np);
}

/// The default `--method robust`: rigid layer, stiffened springs, sub-steps.
#[test]
fn naca0012_rotation_matches_one_process() {
    if !mpi_ready() {
        return;
    }
    let rotate = Attachment {
        groups: vec!["airfoil".into()],
        motion: Motion::Rotation {
            center: [0.25, 0.0, 0.0],
            axis: [0.0, 0.0, 1.0],
            angle: 5f64.to_radians(),
        },
    };
    same_as_single(
        &mesh("mesh_NACA0012_inv.su2"),
        &["--moving", "airfoil", "--rotate", "5", "--center", "0.25,0"],
        &[rotate],
        2,
        robust,
    );
}

/// The linear predictor (`2 u₁ − u₂`) is the one step loop's, over MPI too.
#[test]
fn linear_predictor_matches_one_process() {
    if !mpi_ready() {
        return;
    }
    let rotate = Attachment {
        groups: vec!["airfoil".into()],
        motion: Motion::Rotation {
            center: [0.25, 0.0, 0.0],
            axis: [0.0, 0.0, 1.0],
            angle: 6f64.to_radians(),
        },
    };
    same_as_single(
        &mesh("mesh_NACA0012_inv.su2"),
        &[
            "--moving",
            "airfoil",
            "--rotate",
            "6",
            "--center",
            "0.25,0",
            "--predictor",
            "linear",
        ],
        &[rotate],
        3,
        |settings| {
            robust(settings);
            settings.predictor = Predictor::Linear;
        },
    );
}

/// The paper's method on triangles and quadrilaterals.
#[test]
fn rae2822_hybrid_translation_matches_one_process() {
    if !mpi_ready() {
        return;
    }
    let translate = Attachment {
        groups: vec!["AIRFOIL".into()],
        motion: Motion::Translation {
            displacement: [0.0, 0.02, 0.0],
        },
    };
    same_as_single(
        &mesh("mesh_RAE2822_turb_ffd.su2"),
        &[
            "--moving",
            "AIRFOIL",
            "--translate",
            "0,0.02",
            "--method",
            "verbss",
        ],
        &[translate],
        1,
        paper,
    );
}

#[test]
fn tetrahedral_brick_with_sliding_sides_matches_one_process() {
    if !mpi_ready() {
        return;
    }
    let slide = Attachment {
        groups: vec!["y_m".into(), "y_p".into()],
        motion: Motion::Slide { normal: None },
    };
    let lift = Attachment {
        groups: vec!["z_p".into()],
        motion: Motion::Translation {
            displacement: [0.05, 0.0, 0.1],
        },
    };
    same_as_single(
        &mesh("mesh_brick_tets_ffd.su2"),
        &[
            "--moving",
            "z_p",
            "--translate",
            "0.05,0,0.1",
            "--slide",
            "y_m,y_p",
        ],
        &[slide, lift],
        1,
        robust,
    );
}

/// A body resting on two symmetry planes, moved along their common line:
/// the line's nodes slide along it ([`verbss::solve::NodeRole::Line`]) on
/// every rank as in one process.
#[test]
fn a_body_moved_along_two_symmetry_planes_matches_one_process() {
    if !mpi_ready() {
        return;
    }
    let slide = Attachment {
        groups: vec!["symmetry_y".into(), "symmetry_z".into()],
        motion: Motion::Slide { normal: None },
    };
    let push = Attachment {
        groups: vec!["body".into()],
        motion: Motion::Translation {
            displacement: [4.0, 0.0, 0.0],
        },
    };
    same_as_single(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("../../cases/meshes/symmetry-slice.msh"),
        &[
            "--moving",
            "body",
            "--translate",
            "4,0,0",
            "--slide",
            "symmetry_y,symmetry_z",
        ],
        &[slide, push],
        4,
        robust,
    );
}

/// The anchored reference (the default for periodic motions: springs on
/// the blended input mesh, the total displacement solved each step) over
/// MPI: three steps of a lifted face, each solved from the input mesh.
#[test]
fn anchored_reference_matches_one_process() {
    if !mpi_ready() {
        return;
    }
    let lift = Attachment {
        groups: vec!["z_p".into()],
        motion: Motion::Translation {
            displacement: [0.05, 0.0, 0.1],
        },
    };
    same_as_single(
        &mesh("mesh_brick_tets_ffd.su2"),
        &[
            "--moving",
            "z_p",
            "--translate",
            "0.05,0,0.1",
            "--reference",
            "anchored",
        ],
        &[lift],
        3,
        |settings| {
            robust(settings);
            settings.reference = Reference::Anchored;
        },
    );
}

#[test]
fn bad_input_gives_the_message_of_verbss_once() {
    if !mpi_ready() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.su2");
    let o = mpirun(
        2,
        &[
            "deform",
            mesh("mesh_NACA0012_inv.su2").to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--moving",
            "wing",
            "--translate",
            "0,1",
        ],
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let text = stderr(&o);
    assert_eq!(
        text.matches("error: unknown group 'wing' (the mesh has: airfoil, farfield)")
            .count(),
        1,
        "{text}"
    );
    // A usage error is said once, by rank 0, with clap's exit code 2.
    let o = mpirun(2, &["deform", "--bogus"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let text = stderr(&o);
    let usage = "error: unexpected argument '--bogus' found";
    assert_eq!(text.matches(usage).count(), 1, "{text}");
}

#[test]
fn methods_that_are_not_distributed_are_refused() {
    if !mpi_ready() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.su2");
    let o = mpirun(
        2,
        &[
            "deform",
            mesh("mesh_NACA0012_inv.su2").to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--moving",
            "airfoil",
            "--translate",
            "0,0.01",
            "--method",
            "laplacian",
        ],
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains(
            "error: invalid setting: verbss-mpi distributes the solve of its sweeper, which runs \
             --method robust, verbss or spring with --accel none or auto (got method laplacian, accel none)"
        ),
        "{}",
        stderr(&o)
    );
    assert!(!out.exists());
}

/// Run directly: with MPI it is a program like `verbss`; built without,
/// one line says why and what to install, exit code 2.
#[test]
fn the_binary_says_whether_it_was_built_with_mpi() {
    let o = Command::new(env!("CARGO_BIN_EXE_verbss-mpi"))
        .arg("--version")
        .output()
        .unwrap();
    match verbss_mpi::missing() {
        None => {
            assert!(o.status.success(), "{}", stderr(&o));
            assert!(String::from_utf8_lossy(&o.stdout).starts_with("verbss-mpi "));
        }
        Some(why) => {
            assert_eq!(o.status.code(), Some(2));
            let text = stderr(&o);
            assert!(
                text.starts_with(&format!(
                    "error: verbss-mpi was built without MPI/METIS ({why}): install Open MPI"
                )),
                "{text}"
            );
            assert_eq!(text.lines().count(), 1, "{text}");
        }
    }
}
