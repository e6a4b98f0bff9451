//! Tests of coincident nodes (interfaces, baffles, duplicates) and of
//! periodic pairs.

use super::*;
use crate::mesh::{CellKind, Cells, Coupling, Group, Interface, Transform};

fn attach(groups: &[&str], motion: Motion) -> Attachment {
    Attachment {
        groups: groups.iter().map(|g| g.to_string()).collect(),
        motion,
    }
}

fn translation(x: f64, y: f64) -> Motion {
    Motion::Translation {
        displacement: [x, y, 0.0],
    }
}

/// A 2D mesh of blocks of unit quads, each block `(x0, nx, ny)` with its
/// own nodes, and groups of the lines between the given node positions:
/// `(name, [(x, y) …])` takes every block side along those points.
struct Blocks {
    coords: Vec<f64>,
    cells: Cells,
    /// Per block, its node at `(i, j)`.
    nodes: Vec<Vec<Vec<usize>>>,
}

impl Blocks {
    fn new(blocks: &[(f64, usize, usize)]) -> Blocks {
        let mut b = Blocks {
            coords: Vec::new(),
            cells: Cells::new(),
            nodes: Vec::new(),
        };
        for &(x0, nx, ny) in blocks {
            let mut at = vec![vec![0; ny + 1]; nx + 1];
            for (i, column) in at.iter_mut().enumerate() {
                for (j, node) in column.iter_mut().enumerate() {
                    *node = b.coords.len() / 2;
                    b.coords.extend([x0 + i as f64, j as f64]);
                }
            }
            for i in 0..nx {
                for j in 0..ny {
                    let q = [at[i][j], at[i + 1][j], at[i + 1][j + 1], at[i][j + 1]];
                    b.cells.push(CellKind::Quad, &q);
                }
            }
            b.nodes.push(at);
        }
        b
    }

    /// The group `name` of the sides of block `k` from node `(i, j)` over
    /// `steps` unit steps `(di, dj)`, for each run.
    fn group(&self, name: &str, runs: &[(usize, [usize; 2], [isize; 2], usize)]) -> Group {
        let mut facets = Cells::new();
        for &(k, [i, j], [di, dj], steps) in runs {
            for s in 0..steps as isize {
                let p = |s: isize| {
                    self.nodes[k][(i as isize + s * di) as usize][(j as isize + s * dj) as usize]
                };
                facets.push(CellKind::Line, &[p(s), p(s + 1)]);
            }
        }
        Group {
            name: name.into(),
            tag: None,
            facets,
        }
    }

    fn mesh(self, groups: Vec<Group>, interfaces: Vec<Interface>) -> Mesh {
        let mut mesh = Mesh::new(2, self.coords, self.cells, groups).unwrap();
        mesh.origin.interfaces = interfaces;
        mesh
    }
}

/// Two blocks of 2 × 2 quads side by side, [0, 2] and [2, 4] × [0, 2],
/// not joined: their sides at x = 2 (`l_side`, `r_side`) coincide. The
/// other sides are `left` and `right`.
fn two_blocks(interfaces: Vec<Interface>) -> Mesh {
    let b = Blocks::new(&[(0.0, 2, 2), (2.0, 2, 2)]);
    let groups = vec![
        b.group(
            "left",
            &[
                (0, [0, 0], [1, 0], 2),
                (0, [0, 0], [0, 1], 2),
                (0, [0, 2], [1, 0], 2),
            ],
        ),
        b.group("l_side", &[(0, [2, 0], [0, 1], 2)]),
        b.group("r_side", &[(1, [0, 0], [0, 1], 2)]),
        b.group(
            "right",
            &[
                (1, [0, 0], [1, 0], 2),
                (1, [2, 0], [0, 1], 2),
                (1, [0, 2], [1, 0], 2),
            ],
        ),
    ];
    b.mesh(groups, interfaces)
}

fn sliding() -> Vec<Interface> {
    vec![Interface {
        sides: [vec!["l_side".into()], vec!["r_side".into()]],
        coupling: Coupling::Sliding,
    }]
}

#[test]
fn the_sides_of_a_sliding_interface_move_each_with_its_own_group() {
    let mesh = two_blocks(sliding());
    let motion = attach(&["left", "l_side"], translation(0.0, 0.5));
    let mut d = Deformer::new(&mesh, &[motion], Settings::new(2)).unwrap();
    for n in 1..=2 {
        assert_eq!(d.step(n).unwrap().inverted, 0);
    }
    let x = &d.current().coords;
    for i in mesh.group("l_side").unwrap().nodes() {
        assert_eq!(x[2 * i + 1], mesh.point(i)[1] + 0.5);
    }
    for i in mesh.group("r_side").unwrap().nodes() {
        assert_eq!(&x[2 * i..2 * i + 2], mesh.point(i));
    }
}

#[test]
fn a_baffle_is_accepted_held_and_refused_when_its_sides_would_part() {
    // Without the interface the coincident sides are a baffle: held, it
    // is accepted; moved on one side only, or sliding, refused.
    let mesh = two_blocks(Vec::new());
    Deformer::new(&mesh, &[attach(&["left"], Motion::Fixed)], Settings::new(1)).unwrap();
    let motion = attach(&["left", "l_side"], translation(0.0, 0.5));
    let e = Deformer::new(&mesh, &[motion], Settings::new(1))
        .err()
        .unwrap()
        .to_string();
    assert_eq!(
        e,
        "invalid setting: nodes 7 and 10 at (2.000000, 0.000000) are the two sides of a baffle \
         (on groups left, l_side and r_side, right), which must move together: node 7 moves and \
         node 10 is held; move both sides with one motion or hold both"
    );
    let slide = attach(&["l_side", "r_side"], Motion::Slide { normal: None });
    let e = Deformer::new(&mesh, &[slide], Settings::new(1))
        .err()
        .unwrap()
        .to_string();
    assert!(e.ends_with("which must move together: they would slide apart; move both sides with one motion or hold both"), "{e}");
}

#[test]
fn coincident_nodes_off_every_group_are_duplicates() {
    // Without `r_side`, the right block's node at (2, 1) is on no group
    // (its corners stay on `right`).
    let mut mesh = two_blocks(sliding());
    mesh.groups.retain(|g| g.name != "r_side");
    let e = Deformer::new(
        &mesh,
        &[attach(&["left"], translation(0.0, 0.5))],
        Settings::new(1),
    )
    .err()
    .unwrap()
    .to_string();
    assert_eq!(
        e,
        "invalid mesh: nodes 8 and 11 are at the same position (2.000000, 1.000000): duplicate nodes"
    );
}

/// A strip of 3 × 2 unit quads with `lo` (x = 0) and `hi` (x = 3) a
/// periodic pair by `transform`, `bottom` and `top`.
fn strip(transform: Transform) -> Mesh {
    let b = Blocks::new(&[(0.0, 3, 2)]);
    let groups = vec![
        b.group("lo", &[(0, [0, 0], [0, 1], 2)]),
        b.group("hi", &[(0, [3, 0], [0, 1], 2)]),
        b.group("bottom", &[(0, [0, 0], [1, 0], 3)]),
        b.group("top", &[(0, [0, 2], [1, 0], 3)]),
    ];
    let periodic = Interface {
        sides: [vec!["lo".into()], vec!["hi".into()]],
        coupling: Coupling::Periodic(transform),
    };
    b.mesh(groups, vec![periodic])
}

#[test]
fn a_periodic_pair_moved_by_its_transform_is_kept_and_any_other_motion_refused() {
    let mesh = strip(Transform::Translation([3.0, 0.0, 0.0]));
    // Both sides' bottom corners moved by one translation: they match.
    let shift = attach(&["bottom"], translation(0.2, 0.1));
    let mut d = Deformer::new(&mesh, &[shift], Settings::new(2)).unwrap();
    for n in 1..=2 {
        assert_eq!(d.step(n).unwrap().inverted, 0);
    }
    // Turned, the corners part at the first step.
    let turn = Motion::Rotation {
        center: [1.5, 0.0, 0.0],
        axis: [0.0, 0.0, 1.0],
        angle: 4f64.to_radians(),
    };
    let mut d = Deformer::new(&mesh, &[attach(&["bottom"], turn)], Settings::new(2)).unwrap();
    let e = d.step(1).unwrap_err().to_string();
    assert!(
        e.starts_with(
            "invalid setting: step 1: the periodic patches lo and hi no longer match: node 1 of \
             lo, moved by their translation by (3.000000, 0.000000, 0.000000) to "
        ) && e.contains("from its partner, node 10 of hi at"),
        "{e}"
    );
    // One side moved, the other held: refused before the first step.
    let e = Deformer::new(
        &mesh,
        &[attach(&["lo"], translation(0.1, 0.0))],
        Settings::new(1),
    )
    .err()
    .unwrap()
    .to_string();
    assert_eq!(
        e,
        "invalid setting: the periodic patches lo and hi would no longer match: node 1 of lo \
         moves and its partner, node 10 of hi, is held; move both sides with one motion, or \
         hold both (the default for a group no motion names)"
    );
    // A transform that does not take one side onto the other.
    let wrong = strip(Transform::Translation([2.0, 0.0, 0.0]));
    let e = Deformer::new(&wrong, &[attach(&["top"], Motion::Fixed)], Settings::new(1))
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.starts_with("invalid mesh: the periodic patches lo and hi do not match: node 1 of lo at (0.000000, 0.000000), moved by their translation by (2.000000, 0.000000, 0.000000) to (2.000000, 0.000000), has no node of hi within"),
        "{e}"
    );
}
