//! Amplification (docs/method.md, "Amplification"): a body that deforms
//! moves no solved node farther than its farthest wall node.

use std::collections::HashMap;
use std::path::Path;

use super::*;
use crate::motion::PositionSource;

const NACA: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../assets/meshes/su2/mesh_NACA0012_inv.su2"
);

/// The airfoil's chord station where the droop starts.
const HINGE: f64 = 0.6;

/// The radius the aft part is bent with: its trailing edge moves 0.15 chord.
const BENDING_RADIUS: f64 = 0.525;

/// `(x, y)` of the NACA0012 (chord 1 on `y = 0`) drooped behind [`HINGE`]: a
/// point at station `h + s` and height `y` goes to
/// `(h, −R) + (R + y)(sin(s/R), cos(s/R))`, a cylindrical bending that keeps
/// the wall smooth and turns its trailing edge down.
fn drooped(p: &[f64]) -> Vec<f64> {
    let (s, y) = (p[0] - HINGE, p[1]);
    if s <= 0.0 {
        return p.to_vec();
    }
    let (sin, cos) = (s / BENDING_RADIUS).sin_cos();
    let r = BENDING_RADIUS + y;
    vec![HINGE + r * sin, -BENDING_RADIUS + r * cos]
}

#[test]
fn a_drooped_airfoil_moves_no_node_farther_than_its_wall() {
    let mesh = crate::io::read(Path::new(NACA)).unwrap();
    let table: HashMap<usize, Vec<f64>> = mesh
        .group("airfoil")
        .unwrap()
        .nodes()
        .into_iter()
        .map(|i| (i, drooped(mesh.point(i))))
        .collect();
    let largest = table
        .iter()
        .map(|(&i, q)| {
            let p = mesh.point(i);
            (q[0] - p[0]).hypot(q[1] - p[1])
        })
        .fold(0.0, f64::max);
    assert!((largest - 0.15).abs() < 0.005, "{largest}");
    let attachments = [Attachment {
        groups: vec!["airfoil".to_string()],
        motion: Motion::Positions(PositionSource::Final(table)),
    }];
    let steps = 5;
    let mut d = Deformer::new(&mesh, &attachments, Settings::robust(steps)).unwrap();
    for n in 1..=steps {
        let r = d.step(n).unwrap();
        assert_eq!(r.inverted, 0, "step {n}");
        // The largest move of a solved node over the largest of a
        // prescribed one (the wall and its rigid layer): at most 1.
        assert!(r.amplification <= 1.0, "step {n}: {}", r.amplification);
    }
}
