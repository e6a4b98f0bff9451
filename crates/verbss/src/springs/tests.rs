//! The springs against hand computations, and re-assembly into a kept
//! pattern against a fresh assembly.

use super::*;
use crate::mesh::{samples, CellKind, Cells};

/// One equilateral-ish triangle with node 2 unknown:
/// edges to 0 and 1, and the ball-vertex spring to edge (0, 1).
#[test]
fn triangle_row_by_hand() {
    let mut cells = Cells::new();
    cells.push(CellKind::Triangle, &[0, 1, 2]);
    let coords = vec![0.0, 0.0, 2.0, 0.0, 0.5, 1.0];
    let mesh = Mesh::new(2, coords.clone(), cells, vec![]).unwrap();
    let conn = Connectivity::new(&mesh);
    let position = [u32::MAX, u32::MAX, 0];
    let b = assemble(&conn, &coords, &[2], &position, Springs::BallVertex).unwrap();
    // Edge to node 0: L = √1.25, n = −(0.5, 1)/L. Edge to node 1: L = √3.25,
    // n = (1.5, −1)/L. Ball-vertex: p = (0.5, 0), h = 1, n = (0, −1),
    // weights (0.75, 0.25).
    let outer = |k: f64, n: [f64; 2]| [k * n[0] * n[0], k * n[1] * n[0], k * n[1] * n[1]];
    let l0 = 1.25f64.sqrt();
    let l1 = 3.25f64.sqrt();
    let e0 = outer(1.0 / l0, [0.5 / l0, 1.0 / l0]);
    let e1 = outer(1.0 / l1, [1.5 / l1, -1.0 / l1]);
    let bv = outer(1.0, [0.0, -1.0]);
    let expect_k: Vec<f64> = (0..3).map(|k| e0[k] + e1[k] + bv[k]).collect();
    let expect_b0: Vec<f64> = (0..3).map(|k| e0[k] + 0.75 * bv[k]).collect();
    let expect_b1: Vec<f64> = (0..3).map(|k| e1[k] + 0.25 * bv[k]).collect();
    let close = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-15);
    assert!(close(&b.diag, &expect_k), "{:?}", b.diag);
    assert_eq!(b.fixed_nodes, [0, 1]);
    assert!(close(&b.fixed_blocks[..3], &expect_b0));
    assert!(close(&b.fixed_blocks[3..], &expect_b1));
    assert!(b.neighbours.is_empty());
    let spring = assemble(&conn, &coords, &[2], &position, Springs::Edge).unwrap();
    assert!(close(&spring.fixed_blocks, &[e0, e1].concat()));
}

#[test]
fn collapsed_cells_are_reported() {
    let mut cells = Cells::new();
    cells.push(CellKind::Triangle, &[0, 1, 2]);
    let coords = vec![0.0, 0.0, 2.0, 0.0, 0.5, 0.0];
    let mesh = Mesh::new(2, coords.clone(), cells, vec![]).unwrap();
    let conn = Connectivity::new(&mesh);
    let position = [u32::MAX, u32::MAX, 0];
    let e = assemble(&conn, &coords, &[2], &position, Springs::BallVertex).unwrap_err();
    assert_eq!(
        e.to_string(),
        "invalid mesh: node 3 lies on a facet of cell 1 (a collapsed cell: zero ball-vertex \
         spring length)"
    );
    let coords = vec![0.0, 0.0, 2.0, 0.0, 0.0, 0.0];
    let e = assemble(&conn, &coords, &[2], &position, Springs::Edge).unwrap_err();
    assert_eq!(
        e.to_string(),
        "invalid mesh: nodes 3 and 1 coincide (an edge of zero length)"
    );
}

/// The cells' numbers follow the springs' order of the cells: as an offset
/// and a 32-bit index when the file numbers its cells consecutively, listed
/// otherwise, and the message of a collapsed cell names the file's number.
#[test]
fn cell_numbers_follow_the_order_of_the_cells() {
    let order = [2, 0, 1];
    let consecutive = CellTags::ordered(&[7, 8, 9], order.iter().copied());
    assert!(matches!(
        consecutive,
        CellTags::Consecutive { first: 7, .. }
    ));
    let listed = CellTags::ordered(&[10, 4, 11], order.iter().copied());
    assert!(matches!(listed, CellTags::Listed(_)));
    for (tags, expected) in [(&consecutive, [9, 7, 8]), (&listed, [11, 10, 4])] {
        let got: Vec<u64> = (0..3).map(|c| tags.tag(c)).collect();
        assert_eq!(got, expected);
    }
    let mut cells = Cells::new();
    cells.push(CellKind::Triangle, &[0, 1, 2]);
    let coords = vec![0.0, 0.0, 2.0, 0.0, 0.5, 0.0];
    let mut mesh = Mesh::new(2, coords.clone(), cells, vec![]).unwrap();
    mesh.cell_tags = vec![42];
    let conn = Connectivity::new(&mesh);
    let position = [u32::MAX, u32::MAX, 0];
    let e = assemble(&conn, &coords, &[2], &position, Springs::BallVertex).unwrap_err();
    assert!(e.to_string().contains("of cell 42 "), "{e}");
}

/// A deterministic jitter in `[-amount, amount)`.
fn jitter(seed: u64, amount: f64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        amount * (2.0 * (state >> 11) as f64 / (1u64 << 53) as f64 - 1.0)
    }
}

/// The interior nodes of `mesh` as unknowns: their order and each node's position.
fn interior(mesh: &Mesh) -> (Vec<usize>, Vec<u32>) {
    let boundary = topology::boundary_nodes(mesh);
    let order: Vec<usize> = (0..mesh.node_count()).filter(|&i| !boundary[i]).collect();
    let mut position = vec![u32::MAX; mesh.node_count()];
    for (p, &i) in order.iter().enumerate() {
        position[i] = p as u32;
    }
    (order, position)
}

/// `mesh`'s coordinates moved by a further jitter of `amount` of the spacing `h`.
fn moved(mesh: &Mesh, seed: u64, amount: f64, h: f64) -> Vec<f64> {
    let mut shift = jitter(seed, amount * h);
    mesh.coords.iter().map(|x| x + shift()).collect()
}

/// Grids of every kind `samples::jittered_grid` makes, with and without
/// stiffness factors; the 2D triangles with more rows than one batch of
/// chunks of re-assembly.
fn cases() -> Vec<(Mesh, Vec<f64>, f64)> {
    let mut out = Vec::new();
    let kinds = [
        (2, 0),
        (2, 1),
        (2, 2),
        (3, 0),
        (3, 1),
        (3, 2),
        (3, 3),
        (3, 4),
    ];
    for (k, &(dim, kind)) in kinds.iter().enumerate() {
        let n = 5;
        let h = 1.0 / (n - 1) as f64;
        let mesh = samples::jittered_grid(dim, n, kind, jitter(k as u64, 0.15 * h)).unwrap();
        let phi = (0..mesh.node_count())
            .map(|i| 1.0 + (i % 3) as f64)
            .collect();
        out.push((mesh, phi, h));
    }
    let n = 150;
    let h = 1.0 / (n - 1) as f64;
    let big = samples::jittered_grid(2, n, 0, jitter(99, 0.15 * h)).unwrap();
    out.push((big, Vec::new(), h));
    out
}

#[test]
fn reassembly_into_the_kept_pattern_equals_a_fresh_assembly() {
    let (mut reassembled, mut first_in_place) = (0, 0);
    for (seed, (mesh, phi, h)) in cases().into_iter().enumerate() {
        for stiffness in [Vec::new(), phi] {
            let mut conn = Connectivity::new(&mesh);
            conn.stiffness = stiffness;
            let (order, position) = interior(&mesh);
            let later = moved(&mesh, seed as u64 + 10, 0.1, h);
            for springs in [Springs::Edge, Springs::BallVertex] {
                let before = assemble(&conn, &mesh.coords, &order, &position, springs).unwrap();
                let fresh = assemble(&conn, &later, &order, &position, springs).unwrap();
                let mut kept = before.clone();
                if reassemble(&conn, &later, &order, &position, springs, &mut kept).unwrap() {
                    assert_eq!(kept, fresh);
                    reassembled += 1;
                } else {
                    let pattern = |b: &NodeBlocks| {
                        (
                            b.offsets.clone(),
                            b.neighbours.clone(),
                            b.fixed_nodes.clone(),
                        )
                    };
                    assert_ne!(pattern(&before), pattern(&fresh));
                }
                let reused =
                    assemble_reusing(&conn, &later, &order, &position, springs, Some(before));
                assert_eq!(reused.unwrap(), fresh);
                let first = assemble_reusing(&conn, &later, &order, &position, springs, None);
                assert_eq!(first.unwrap(), fresh);
                let mut full = refill::full_pattern(&conn, &order, &position);
                if reassemble(&conn, &later, &order, &position, springs, &mut full).unwrap() {
                    assert_eq!(full, fresh);
                    first_in_place += 1;
                }
            }
        }
    }
    assert!(reassembled >= 20, "only {reassembled} re-assemblies fitted");
    assert!(
        first_in_place >= 10,
        "only {first_in_place} first assemblies in place"
    );
}

#[test]
fn a_system_of_other_unknowns_is_not_reassembled_into() {
    let (mesh, _, h) = cases().swap_remove(5);
    let conn = Connectivity::new(&mesh);
    let (order, position) = interior(&mesh);
    let later = moved(&mesh, 3, 0.1, h);
    let fewer = &order[1..];
    let mut shifted = vec![u32::MAX; mesh.node_count()];
    for (p, &i) in fewer.iter().enumerate() {
        shifted[i] = p as u32;
    }
    let springs = Springs::BallVertex;
    let mut other = assemble(&conn, &mesh.coords, fewer, &shifted, springs).unwrap();
    assert!(!reassemble(&conn, &later, &order, &position, springs, &mut other).unwrap());
    let mut reordered = assemble(&conn, &mesh.coords, &order, &position, springs).unwrap();
    let mut swapped = position.clone();
    swapped.swap(order[0], order[1]);
    let mut swapped_order = order.clone();
    swapped_order.swap(0, 1);
    let fits = reassemble(
        &conn,
        &later,
        &swapped_order,
        &swapped,
        springs,
        &mut reordered,
    );
    assert!(!fits.unwrap());
    let fresh = assemble(&conn, &later, &order, &position, springs).unwrap();
    let reused = assemble_reusing(&conn, &later, &order, &position, springs, Some(other));
    assert_eq!(reused.unwrap(), fresh);
}

#[test]
fn assembly_does_not_depend_on_the_number_of_threads() {
    for (seed, (mesh, phi, h)) in cases().into_iter().enumerate() {
        let mut conn = Connectivity::new(&mesh);
        conn.stiffness = phi;
        let (order, position) = interior(&mesh);
        let later = moved(&mesh, seed as u64 + 20, 0.1, h);
        let run = || {
            let fresh =
                assemble(&conn, &mesh.coords, &order, &position, Springs::BallVertex).unwrap();
            let mut kept = fresh.clone();
            let fits = reassemble(
                &conn,
                &later,
                &order,
                &position,
                Springs::BallVertex,
                &mut kept,
            );
            (fresh, fits.unwrap(), kept)
        };
        let pool = |threads| rayon::ThreadPoolBuilder::new().num_threads(threads).build();
        let one = pool(1).unwrap().install(run);
        let three = pool(3).unwrap().install(run);
        assert!(one == three, "mesh {seed}");
    }
}

/// A mesh's cells written as polygons and polyhedra of the same nodes and
/// facets get the same springs as the paper's kinds: their edges are the
/// same, and their facets not containing a node are the same segments,
/// triangles and quadrilaterals (a face of five or more nodes is the only
/// new case, [`polygon_face_weights_lie_in_the_unit_interval_and_sum_to_one`]).
#[test]
fn general_cells_of_the_paper_s_shapes_get_the_paper_s_springs() {
    let mut seed = 7u64;
    let mut jitter = move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        0.2 * ((seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5)
    };
    for (dim, kind) in [(2, 2), (3, 0), (3, 1), (3, 2), (3, 4)] {
        let mesh = samples::jittered_grid(dim, 4, kind, &mut jitter).unwrap();
        let general = samples::as_general(&mesh);
        let n = mesh.node_count();
        let order: Vec<usize> = (0..n).collect();
        let position: Vec<u32> = (0..n as u32).collect();
        let a = assemble(
            &Connectivity::new(&mesh),
            &mesh.coords,
            &order,
            &position,
            Springs::BallVertex,
        )
        .unwrap();
        let b = assemble(
            &Connectivity::new(&general),
            &general.coords,
            &order,
            &position,
            Springs::BallVertex,
        )
        .unwrap();
        assert_eq!(a.offsets, b.offsets, "{dim}D kind {kind}");
        assert_eq!(a.neighbours, b.neighbours, "{dim}D kind {kind}");
        let close = |x: &[f64], y: &[f64]| {
            x.iter()
                .zip(y)
                .all(|(p, q)| (p - q).abs() <= 1e-12 * (1.0 + p.abs()))
        };
        assert!(close(&a.diag, &b.diag), "{dim}D kind {kind}");
        assert!(close(&a.blocks, &b.blocks), "{dim}D kind {kind}");
    }
}

/// A hexagon's node pulled by its far sides: each ball-vertex spring's
/// weights (on a polyhedron's pentagonal face, through the face centre) lie
/// in `[0, 1]` and sum to 1, so every row's blocks sum to its diagonal.
#[test]
fn polygon_face_weights_lie_in_the_unit_interval_and_sum_to_one() {
    // A pentagonal prism: two pentagons and five quadrilaterals.
    let ring: Vec<[f64; 2]> = (0..5)
        .map(|k| {
            let a = 2.0 * std::f64::consts::PI * k as f64 / 5.0;
            [a.cos(), a.sin()]
        })
        .collect();
    let mut coords = Vec::new();
    for z in [0.0, 0.8] {
        for p in &ring {
            coords.extend_from_slice(&[p[0], p[1], z]);
        }
    }
    coords.extend_from_slice(&[0.1, 0.05, 1.5]);
    let bottom: Vec<usize> = (0..5).rev().collect();
    let top: Vec<usize> = (5..10).collect();
    let mut faces = vec![bottom, top];
    for k in 0..5 {
        faces.push(vec![k, (k + 1) % 5, 5 + (k + 1) % 5, 5 + k]);
    }
    let mut cells = Cells::new();
    cells.push_polyhedron(faces.iter().map(Vec::as_slice));
    // A pentagonal pyramid on top: node 10 sees the top pentagon.
    let mut faces = vec![(5..10).rev().collect::<Vec<_>>()];
    for k in 0..5 {
        faces.push(vec![5 + k, 5 + (k + 1) % 5, 10]);
    }
    cells.push_polyhedron(faces.iter().map(Vec::as_slice));
    let mesh = Mesh::new(3, coords.clone(), cells, vec![]).unwrap();
    let conn = Connectivity::new(&mesh);
    let order: Vec<usize> = (0..11).collect();
    let position: Vec<u32> = (0..11).collect();
    let b = assemble(&conn, &coords, &order, &position, Springs::BallVertex).unwrap();
    for r in 0..11 {
        let mut sum = [0.0; 6];
        for e in b.offsets[r]..b.offsets[r + 1] {
            for (s, v) in sum.iter_mut().zip(&b.blocks[6 * e..6 * e + 6]) {
                *s += v;
            }
        }
        for (s, d) in sum.iter().zip(&b.diag[6 * r..6 * r + 6]) {
            assert!((s - d).abs() < 1e-12, "row {r}");
        }
    }
    let mut w = Vec::new();
    let pentagon: Vec<[f64; 3]> = (5..10)
        .map(|i| crate::geometry::point::<3>(&coords, i))
        .collect();
    for x in [[0.1, 0.05, 1.5], [3.0, 0.0, 0.8], [0.0, -2.0, 0.0]] {
        crate::geometry::nearest_on_polygon(&x, &pentagon, &mut w);
        assert!(w.iter().all(|&v| (0.0..=1.0).contains(&v)), "{w:?}");
        assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-14, "{w:?}");
    }
}
