//! The rigid layer, the wall-distance stiffening and the sub-steps of
//! `verbss-mpi deform` on the path where no rank holds the whole mesh
//! (`verbss_mpi::near_wall`), on 1, 2 and 3 ranks: the moved mesh, the
//! reported quality and the gathered file are those of the single-process
//! stepper with the same treatments (to 1e-10 of the largest
//! displacement), and rank 0 states the single process's number of
//! rigid-layer nodes. The inputs: partitioned MSH fixtures, with a moving
//! group that some ranks hold no node of, the SU2 NACA0012 airfoil, and
//! the three-element airfoil with fixed walls inside the domain.

use std::path::Path;

use verbss::deform::Deformer;
use verbss::io::gmsh::partitioned::read_share;
use verbss::motion::Attachment;
use verbss::near_wall::{Layer, Robust};
use verbss::settings::{Preset, Reference};
use verbss::Error;
use verbss_mpi::share::partitions_of;

mod common;
mod like_one_process;

use like_one_process::{
    asset, deforms_like_one_process_with, ptscotch_ready, single_with, NearWall,
};
use verbss::motion::Motion;

/// The three-element airfoil of `cases/meshes` written as SU2 in `dir`.
fn three_element_su2(dir: &Path) -> std::path::PathBuf {
    let su2 = dir.join("three.su2");
    let msh = verbss::io::read(&asset("../../cases/meshes/three-element.msh")).unwrap();
    verbss::io::write(&su2, &msh, &verbss::io::WriteOptions::default()).unwrap();
    su2
}

/// The rigid layer `layer` and the stiffening exponent 1, for both runs.
fn treatments<'a>(layer: Layer, args: &'a [&'a str]) -> NearWall<'a> {
    let mut robust = Robust::off();
    robust.layer = layer;
    robust.stiffening = 1.0;
    NearWall {
        method: "verbss",
        robust,
        args,
        slides: &[],
        steps: 2,
        stages: "sweeps",
    }
}

/// Runs `mesh` like one process with `near_wall` and checks that rank 0
/// of each run states the single process's layer node count; returns it.
fn layer_like_one_process(
    mesh: &Path,
    group: &str,
    motion: &[&str],
    reference: Reference,
    scale: f64,
    env: &[(&str, &str)],
    near_wall: &NearWall,
) -> usize {
    let (stdouts, layer) =
        deforms_like_one_process_with(mesh, group, motion, reference, scale, env, near_wall);
    for (k, stdout) in stdouts.iter().enumerate() {
        let line = format!("rigid layer: {layer} nodes, ");
        assert_eq!(
            stdout.matches(&line).count(),
            1,
            "{} ranks: {stdout}",
            k + 1
        );
    }
    layer
}

/// The ranks of `np` that hold no node of `group` in their share of the
/// partitioned MSH file `path` of `partitions` partitions.
fn ranks_without(path: &Path, partitions: usize, group: &str, np: usize) -> Vec<usize> {
    (0..np)
        .filter(|&r| {
            let range = partitions_of(partitions, np, r, path).unwrap();
            let share = read_share(path, range).unwrap();
            share
                .group_nodes
                .iter()
                .find(|(g, _)| g == group)
                .is_none_or(|(_, nodes)| nodes.is_empty())
        })
        .collect()
}

/// The channel is too narrow for a layer around its hole (every node is
/// nearer a tenth of the way to the outer walls than the layer's
/// thickness: `GAP_SHARE`): no layer node on one process or on the ranks,
/// and the stiffening alone. Cut in 3, rank 1 holds no node of the hole.
#[test]
fn a_given_layer_around_the_channel_hole_moves_as_on_one_process() {
    if !common::mpi_ready() {
        return;
    }
    let mesh = asset("gmsh/channel_hole_part3_v41_ascii.msh");
    assert_eq!(ranks_without(&mesh, 3, "wall", 3), [1]);
    let scale = (0.02f64 * 0.02 + 0.01 * 0.01).sqrt();
    let args = ["--rigid-layer", "0.15", "--stiffening", "1"];
    let layer = layer_like_one_process(
        &mesh,
        "wall",
        &["--translate", "0.02,0.01"],
        Reference::Updated,
        scale,
        &[],
        &treatments(Layer::Thickness(0.15), &args),
    );
    assert_eq!(layer, 0);
}

/// The outlet of the box cut in 6 is on no node of rank 1 of 2 and rank 2
/// of 3: they spread its distances from their ghosts and take its size
/// from the others.
#[test]
fn the_automatic_layer_of_a_box_face_some_ranks_do_not_hold_moves_as_on_one_process() {
    if !common::mpi_ready() {
        return;
    }
    let mesh = asset("gmsh/box_part6_v41_ascii.msh");
    assert_eq!(ranks_without(&mesh, 6, "outlet", 2), [1]);
    assert_eq!(ranks_without(&mesh, 6, "outlet", 3), [2]);
    let args = ["--rigid-layer", "auto", "--stiffening", "1"];
    layer_like_one_process(
        &mesh,
        "outlet",
        &["--translate", "0.1,0.05,0"],
        Reference::Fixed,
        0.11,
        &[],
        &treatments(Layer::Auto, &args),
    );
}

/// The airfoil's automatic layer holds hundreds of nodes. The stiffened
/// sweeps of one process and of the ranks (other node orders) agree to
/// 1e-9 of the trailing edge's displacement (0.75·sin 2° ≈ 0.026, given as
/// `scale` 0.26 to the comparisons of 1e-10 of it).
#[test]
fn the_automatic_layer_of_the_naca0012_airfoil_turns_as_on_one_process() {
    if !ptscotch_ready() {
        return;
    }
    let args = ["--rigid-layer", "auto", "--stiffening", "1"];
    let motion = ["--rotate", "2", "--center", "0.25,0"];
    let layer = layer_like_one_process(
        &asset("su2/mesh_NACA0012_inv.su2"),
        "airfoil",
        &motion,
        Reference::Updated,
        0.26,
        &[("VERBSS_MPI_CHUNK_LINES", "5000")],
        &treatments(Layer::Auto, &args),
    );
    assert!(layer > 100, "{layer}");
}

/// The three-element airfoil (written as SU2) with its flap turned 5°: the
/// slat and the main element are fixed walls inside the domain, bodies
/// that stay, whose layers hold their nodes in place and whose distances
/// bound the flap's layer.
#[test]
fn the_flap_turns_between_fixed_walls_as_on_one_process() {
    if !ptscotch_ready() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let su2 = three_element_su2(dir.path());
    let args = ["--rigid-layer", "auto", "--stiffening", "1"];
    let motion = ["--rotate", "5", "--center", "1,0"];
    // The flap's trailing edge is about 0.25 from its centre: 0.25·sin 5°.
    let layer = layer_like_one_process(
        &su2,
        "flap",
        &motion,
        Reference::Updated,
        0.022,
        &[],
        &treatments(Layer::Auto, &args),
    );
    assert!(layer > 1000, "{layer}");
}

/// The hole of the channel lifted by 0.27 in one step inverts a cell in
/// one increment (exit code 3 with `--substeps 0`, the element and the
/// count named as one process names them, the failed state written as
/// pieces) and is reached in two with `--substeps 6`: the increments, the
/// moved mesh and the report are the single process's.
#[test]
fn sub_steps_lift_the_channel_hole_as_on_one_process() {
    if !common::mpi_ready() {
        return;
    }
    let mesh = asset("gmsh/channel_hole_part3_v41_ascii.msh");
    let motion = ["--translate", "0,0.27"];
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("moved.pvtu");
    let mut args = vec![
        "deform",
        mesh.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--moving",
        "wall",
        "--method",
        "verbss",
        "--substeps",
        "0",
    ];
    args.extend_from_slice(&motion);
    let whole = verbss::io::read(&mesh).unwrap();
    let translation = Motion::Translation {
        displacement: [0.0, 0.27, 0.0],
    };
    // What one process says of the step, around the centroid and volume.
    let (head, tail) = {
        let mut settings = Preset::Verbss.settings(1);
        settings.robust.substeps = 0;
        let attachments = [Attachment {
            groups: vec!["wall".into()],
            motion: translation.clone(),
        }];
        let mut d = Deformer::new(&whole, &attachments, settings).unwrap();
        match d.step(1) {
            Err(Error::Inverted { element, count, .. }) => (
                format!("error: step 1: element {element} inverted at "),
                format!("({count} inverted element(s))\nthe last valid mesh (step 0) is in "),
            ),
            other => panic!("one process: {other:?}"),
        }
    };
    for np in 1..=3 {
        let o = like_one_process::verbss_mpi_with(np, &args, dir.path(), &[]);
        assert_eq!(o.status.code(), Some(3), "{np} ranks");
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(stderr.matches(&head).count(), 1, "{head}: {stderr}");
        assert_eq!(stderr.matches(&tail).count(), 1, "{tail}: {stderr}");
        let failed = dir.path().join("moved.failed.pvtu");
        assert!(stderr.contains(&format!("the failed state in {}", failed.display())));
        let cells: usize = (0..np)
            .map(|r| {
                let piece = dir.path().join(format!("moved.failed_{r}.vtu"));
                verbss::io::read(&piece).unwrap().cell_count()
            })
            .sum();
        assert_eq!(cells, whole.cell_count(), "{np} ranks");
    }
    let mut robust = Robust::off();
    robust.substeps = 6;
    let (_, reports, _) = single_with(
        &whole,
        ("wall", &[]),
        translation,
        1,
        Reference::Updated,
        robust,
        Preset::Verbss,
    );
    assert_eq!(reports[1].substeps, 2);
    // The first increment inverts a cell and is solved again to round-off
    // (stage gmres) before it is halved.
    let near_wall = NearWall {
        method: "verbss",
        robust,
        args: &["--substeps", "6"],
        slides: &[],
        steps: 1,
        stages: "sweeps → gmres",
    };
    let (stdouts, _) = deforms_like_one_process_with(
        &mesh,
        "wall",
        &motion,
        Reference::Updated,
        0.27,
        &[],
        &near_wall,
    );
    assert_eq!(stdouts.len(), 3);
}

/// The default method, `robust`: the automatic rigid layer, the
/// stiffening and the blended rigid motion, in `steps` steps whose
/// progress lines name `stages`.
fn default_method(steps: usize, stages: &str) -> NearWall<'_> {
    NearWall {
        method: "robust",
        robust: Robust::recommended(),
        args: &[],
        slides: &[],
        steps,
        stages,
    }
}

/// The default method moves the channel's hole by the blend alone (its
/// translation's weight a distributed harmonic solve), and where the
/// blended start is weak (the hole pushed 0.3 along the channel in one
/// step, the relocation off) solves the springs from the plain start
/// instead, as one process.
#[test]
fn the_default_method_moves_the_channel_hole_as_on_one_process() {
    if !common::mpi_ready() {
        return;
    }
    let mesh = asset("gmsh/channel_hole_part3_v41_ascii.msh");
    let blended = default_method(2, "blended motion only");
    let motion = ["--translate", "0.02,0.01"];
    deforms_like_one_process_with(
        &mesh,
        "wall",
        &motion,
        Reference::Updated,
        0.022,
        &[],
        &blended,
    );
    // Without the relocation of the worst cells' nodes, which makes this
    // blended start good enough.
    let mut plain = default_method(1, "sweeps");
    plain.args = &["--relocate", "off"];
    plain.robust.relocate = false;
    let motion = ["--translate", "0.3,0"];
    deforms_like_one_process_with(&mesh, "wall", &motion, Reference::Updated, 0.3, &[], &plain);
}

/// The default method turns the NACA0012 airfoil by the blend: its rigid
/// fit summed over the ranks and its angle's weight from each node's
/// nearest wall and far-field node, the same on every cut.
#[test]
fn the_default_method_turns_the_naca0012_as_on_one_process() {
    if !ptscotch_ready() {
        return;
    }
    // The trailing edge moves by 0.75·sin 10° ≈ 0.13.
    let motion = ["--rotate", "10", "--center", "0.25,0"];
    let (_, layer) = deforms_like_one_process_with(
        &asset("su2/mesh_NACA0012_inv.su2"),
        "airfoil",
        &motion,
        Reference::Updated,
        0.13,
        &[],
        &default_method(2, "blended motion only"),
    );
    assert!(layer > 100, "{layer}");
}

/// The default method turns the three-element airfoil's flap between the
/// slat and the main element, fixed walls whose nodes are the angle
/// weight's other prescribed nodes.
#[test]
fn the_default_method_turns_the_flap_between_fixed_walls_as_on_one_process() {
    if !ptscotch_ready() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let su2 = three_element_su2(dir.path());
    let motion = ["--rotate", "10", "--center", "1,0"];
    deforms_like_one_process_with(
        &su2,
        "flap",
        &motion,
        Reference::Updated,
        0.043,
        &[],
        &default_method(2, "blended motion only"),
    );
}
