//! A deforming step gives the same bits on any number of worker threads:
//! the blended rigid motion (its distance walks, its Laplace solve, its
//! per-node move), the springs' solve and the check all run on the one pool
//! that `threads` sizes.

use std::path::PathBuf;

use verbss::prelude::*;

fn mesh(name: &str) -> Mesh {
    let path = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/meshes/gmsh"
    ));
    verbss::io::read(&path.join(name)).unwrap()
}

/// The coordinates after each of `steps` steps of `attachments` on `mesh`
/// with the product's default settings on `threads` threads.
fn run(mesh: &Mesh, attachments: &[Attachment], steps: usize, threads: usize) -> Vec<Vec<f64>> {
    let mut settings = Settings::robust(steps);
    settings.solve.threads = threads;
    let mut deformer = Deformer::new(mesh, attachments, settings).unwrap();
    (1..=steps)
        .map(|n| {
            let report = deformer.step(n).unwrap();
            assert!(report.converged && report.inverted == 0, "{report:?}");
            deformer.current().coords.clone()
        })
        .collect()
}

fn same_bits(a: &[Vec<f64>], b: &[Vec<f64>]) -> bool {
    a.iter()
        .flatten()
        .zip(b.iter().flatten())
        .all(|(x, y)| x.to_bits() == y.to_bits())
}

#[test]
fn a_bending_half_sphere_moves_the_same_on_one_two_and_three_threads() {
    let mesh = mesh("half_sphere_v41_ascii.msh");
    // The sphere (centre (0.5, 0, 0.5), radius 0.2) bends up from its
    // root on the symmetry plane y = 0, which its other nodes slide on.
    let attachments = [
        Attachment {
            groups: vec!["sphere".into()],
            motion: Motion::Bending {
                root: [0.5, 0.0, 0.5],
                span_axis: [0.0, 1.0, 0.0],
                direction: [0.0, 0.0, 1.0],
                span: 0.2,
                tip: 0.06,
            },
        },
        Attachment {
            groups: vec!["symmetry".into()],
            motion: Motion::Slide { normal: None },
        },
        Attachment {
            groups: vec!["farfield".into()],
            motion: Motion::Fixed,
        },
    ];
    let one = run(&mesh, &attachments, 2, 1);
    assert_ne!(one[1], mesh.coords);
    for threads in [2, 3] {
        let other = run(&mesh, &attachments, 2, threads);
        assert!(same_bits(&one, &other), "{threads} threads differ from 1");
    }
}

#[test]
fn a_translated_airfoil_moves_the_same_on_one_two_and_three_threads() {
    // The directional weight (2D) and its isotropic retry.
    let mesh = naca0012(&AirfoilGrid::default()).unwrap();
    let attachments = [Attachment {
        groups: vec!["airfoil".into()],
        motion: Motion::Translation {
            displacement: [0.1, 0.2, 0.0],
        },
    }];
    let one = run(&mesh, &attachments, 2, 1);
    for threads in [2, 3] {
        let other = run(&mesh, &attachments, 2, threads);
        assert!(same_bits(&one, &other), "{threads} threads differ from 1");
    }
}
