//! Hand-made elements. Reference values marked "VTK" were computed with VTK
//! 9.7.2's vtkMeshQuality on the same coordinates (double-precision points).

use super::*;
use crate::geometry::corner_jacobian;
use crate::mesh::{samples, Cells};

const SQRT3: f64 = 1.732_050_807_568_877_2;

/// Flat coordinates and node list `0..n` of one cell.
fn cell(points: &[&[f64]]) -> (Vec<f64>, Vec<usize>) {
    (points.concat(), (0..points.len()).collect())
}

fn quality(kind: CellKind, points: &[&[f64]], sign: i8) -> f64 {
    let (coords, nodes) = cell(points);
    match points[0].len() {
        2 => cell_quality::<2>(kind, &nodes, &coords, sign),
        _ => cell_quality::<3>(kind, &nodes, &coords, sign),
    }
}

fn own_orientation(kind: CellKind, points: &[&[f64]]) -> i8 {
    let (coords, nodes) = cell(points);
    match points[0].len() {
        2 => cell_orientation::<2>(kind, &nodes, &coords),
        _ => cell_orientation::<3>(kind, &nodes, &coords),
    }
}

fn worst_of(kind: CellKind, points: &[&[f64]], sign: i8) -> Corner {
    let (coords, nodes) = cell(points);
    match points[0].len() {
        2 => worst_corner::<2>(kind, &nodes, &coords, sign),
        _ => worst_corner::<3>(kind, &nodes, &coords, sign),
    }
}

fn close(a: f64, b: f64, tol: f64) {
    assert!((a - b).abs() <= tol, "{a} vs {b}");
}

const UNIT_CUBE: [&[f64]; 8] = [
    &[0., 0., 0.],
    &[1., 0., 0.],
    &[1., 1., 0.],
    &[0., 1., 0.],
    &[0., 0., 1.],
    &[1., 0., 1.],
    &[1., 1., 1.],
    &[0., 1., 1.],
];

#[test]
fn equilateral_triangle_and_tetrahedron_are_one() {
    let tri: [&[f64]; 3] = [&[0., 0.], &[1., 0.], &[0.5, SQRT3 / 2.]];
    close(quality(CellKind::Triangle, &tri, 1), 1.0, 1e-15);
    let tet: [&[f64]; 4] = [
        &[1., 1., 1.],
        &[-1., 1., -1.],
        &[1., -1., -1.],
        &[-1., -1., 1.],
    ];
    assert_eq!(own_orientation(CellKind::Tetra, &tet), 1);
    close(quality(CellKind::Tetra, &tet, 1), 1.0, 1e-15);
}

#[test]
fn right_triangle_and_corner_tetrahedron() {
    // Right isosceles: r = (2 − √2)/2, R = √2/2, ρ = 2r/R = 2√2 − 2 (VTK: RR 1.2071067811865475).
    let tri: [&[f64]; 3] = [&[0., 0.], &[1., 0.], &[0., 1.]];
    close(
        quality(CellKind::Triangle, &tri, 1),
        2.0 * 2f64.sqrt() - 2.0,
        1e-15,
    );
    close(
        quality(CellKind::Triangle, &tri, 1),
        1.0 / 1.2071067811865475,
        1e-15,
    );
    // Corner of the unit cube: ρ = √3 − 1 (VTK: RR 1.3660254037844395).
    let tet: [&[f64]; 4] = [&[0., 0., 0.], &[1., 0., 0.], &[0., 1., 0.], &[0., 0., 1.]];
    close(quality(CellKind::Tetra, &tet, 1), SQRT3 - 1.0, 1e-15);
    close(
        quality(CellKind::Tetra, &tet, 1),
        1.0 / 1.3660254037844395,
        1e-15,
    );
}

#[test]
fn skewed_simplices_match_vtk_radius_ratio() {
    let tri: [&[f64]; 3] = [&[0., 0.], &[3., 0.2], &[1.0, 0.5]];
    close(
        quality(CellKind::Triangle, &tri, 1),
        1.0 / 6.181903261994067,
        1e-12,
    );
    let tet: [&[f64]; 4] = [
        &[0., 0., 0.],
        &[1., 0.1, 0.],
        &[0.3, 0.8, 0.1],
        &[0.2, 0.3, 0.4],
    ];
    close(
        quality(CellKind::Tetra, &tet, 1),
        1.0 / 1.4310450157168166,
        1e-12,
    );
}

#[test]
fn unit_square_and_cube_are_one() {
    let square: [&[f64]; 4] = [&[0., 0.], &[1., 0.], &[1., 1.], &[0., 1.]];
    assert_eq!(quality(CellKind::Quad, &square, 1), 1.0);
    assert_eq!(quality(CellKind::Hexahedron, &UNIT_CUBE, 1), 1.0);
}

#[test]
fn skewed_quad_and_hexahedron_match_vtk_scaled_jacobian() {
    let quad: [&[f64]; 4] = [&[0., 0.], &[2., 0.2], &[1.7, 1.5], &[-0.3, 1.1]];
    close(quality(CellKind::Quad, &quad, 1), 0.9861570423161173, 1e-12);
    let hex: [&[f64]; 8] = [
        &[0., 0., 0.],
        &[1.2, 0.1, 0.],
        &[1.1, 1., 0.1],
        &[0., 0.9, 0.],
        &[0.1, 0., 1.],
        &[1., 0.1, 1.2],
        &[1.3, 1.2, 1.1],
        &[-0.1, 1., 0.9],
    ];
    close(
        quality(CellKind::Hexahedron, &hex, 1),
        0.8664533809810637,
        1e-12,
    );
}

#[test]
fn hexahedron_corners_and_centre() {
    // A cube whose top face is turned by 60°: the corners give √(2/3) (VTK),
    // the principal axes at the centre stay orthogonal.
    let t = std::f64::consts::FRAC_PI_3;
    let top: Vec<[f64; 3]> = [[0., 0.], [1., 0.], [1., 1.], [0., 1.]]
        .iter()
        .map(|[x, y]| {
            let (u, v) = (x - 0.5, y - 0.5);
            [
                0.5 + u * t.cos() - v * t.sin(),
                0.5 + u * t.sin() + v * t.cos(),
                1.0,
            ]
        })
        .collect();
    let mut hex: Vec<&[f64]> = UNIT_CUBE[..4].to_vec();
    hex.extend(top.iter().map(|p| &p[..]));
    close(
        quality(CellKind::Hexahedron, &hex, 1),
        0.8164965809277259,
        1e-12,
    );
    let nodes: Vec<usize> = (0..8).collect();
    let p = gather::<3>(&hex.concat(), &nodes);
    close(measures::hexahedron_centre(&p, 1.0), 1.0, 1e-15);
    // A sheared cube (parallelepiped): the centre axes are its edges, 1/√1.25.
    let sheared: Vec<f64> = UNIT_CUBE
        .concat()
        .chunks(3)
        .flat_map(|x| [x[0] + 0.5 * x[1], x[1], x[2]])
        .collect();
    let p = gather::<3>(&sheared, &nodes);
    close(
        measures::hexahedron_centre(&p, 1.0),
        1.25f64.sqrt().recip(),
        1e-15,
    );
    close(
        measures::hexahedron_centre(&p, -1.0),
        -(1.25f64.sqrt().recip()),
        1e-15,
    );
}

#[test]
fn reference_wedges_and_pyramids() {
    // Right unit wedge: corners 1 and 2 have scaled Jacobian 1/√2, times 2/√3 (VTK 0.816496580927726).
    let right: [&[f64]; 6] = [
        &[0., 0., 0.],
        &[1., 0., 0.],
        &[0., 1., 0.],
        &[0., 0., 1.],
        &[1., 0., 1.],
        &[0., 1., 1.],
    ];
    close(
        quality(CellKind::Wedge, &right, 1),
        (2f64 / 3.0).sqrt(),
        1e-15,
    );
    close(
        quality(CellKind::Wedge, &right, 1),
        0.816496580927726,
        1e-12,
    );
    let h = SQRT3 / 2.;
    let equilateral: [&[f64]; 6] = [
        &[0., 0., 0.],
        &[1., 0., 0.],
        &[0.5, h, 0.],
        &[0., 0., 1.],
        &[1., 0., 1.],
        &[0.5, h, 1.],
    ];
    close(quality(CellKind::Wedge, &equilateral, 1), 1.0, 1e-15);
    let skewed: [&[f64]; 6] = [
        &[0., 0., 0.],
        &[1., 0., 0.1],
        &[0.4, 0.9, 0.],
        &[0.1, 0.1, 1.],
        &[1.1, 0., 1.2],
        &[0.5, 1., 0.9],
    ];
    close(
        quality(CellKind::Wedge, &skewed, 1),
        0.8616517119911004,
        1e-12,
    );

    let base: [&[f64]; 4] = [&[0., 0., 0.], &[1., 0., 0.], &[1., 1., 0.], &[0., 1., 0.]];
    let pyramid = |apex: &[f64]| -> f64 {
        let mut p = base.to_vec();
        p.push(apex);
        quality(CellKind::Pyramid, &p, 1)
    };
    // All edges of length 1: the ideal pyramid.
    close(pyramid(&[0.5, 0.5, 0.5f64.sqrt()]), 1.0, 1e-15);
    // Taller and shorter than ideal (VTK; the tall one is past the fold at 1).
    close(pyramid(&[0.5, 0.5, 1.]), 0.9113378920963651, 1e-12);
    close(pyramid(&[0.5, 0.5, 2.]), 0.4190262407031392, 1e-12);
    close(pyramid(&[0., 0., 1.]), 0.5773502691896258, 1e-12);
    let skewed: [&[f64]; 5] = [
        &[0., 0., 0.],
        &[1., 0., 0.],
        &[1.1, 0.9, 0.],
        &[0., 1., 0.1],
        &[0.3, 0.6, 0.8],
    ];
    close(
        quality(CellKind::Pyramid, &skewed, 1),
        0.8552056323940969,
        1e-12,
    );
}

#[test]
fn clockwise_quad_is_good_relative_to_itself() {
    let cw: [&[f64]; 4] = [&[0., 0.], &[0., 1.], &[1., 1.], &[1., 0.]];
    assert_eq!(own_orientation(CellKind::Quad, &cw), -1);
    assert_eq!(quality(CellKind::Quad, &cw, -1), 1.0);
    assert!(!worst_of(CellKind::Quad, &cw, -1).inverted());
    // Against a counter-clockwise reference it is inverted, with area −1/2 at every corner.
    let w = worst_of(CellKind::Quad, &cw, 1);
    assert!(w.inverted());
    assert_eq!(w.volume, -0.5);
    assert_eq!(quality(CellKind::Quad, &cw, 1), 0.0);
}

#[test]
fn reversed_three_dimensional_cells_measure_the_same() {
    let mut flipped = UNIT_CUBE[4..].to_vec();
    flipped.extend_from_slice(&UNIT_CUBE[..4]);
    assert_eq!(own_orientation(CellKind::Hexahedron, &flipped), -1);
    assert_eq!(quality(CellKind::Hexahedron, &flipped, -1), 1.0);
    let wedge: [&[f64]; 6] = [
        &[0., 0., 0.],
        &[0., 1., 0.],
        &[1., 0., 0.],
        &[0., 0., 1.],
        &[0., 1., 1.],
        &[1., 0., 1.],
    ];
    assert_eq!(own_orientation(CellKind::Wedge, &wedge), -1);
    close(
        quality(CellKind::Wedge, &wedge, -1),
        (2f64 / 3.0).sqrt(),
        1e-15,
    );
}

#[test]
fn tangled_quads_are_inverted() {
    // Bow-tie: two corners each way, the sum is zero, so the cell is flat.
    let bowtie: [&[f64]; 4] = [&[0., 0.], &[1., 0.], &[0., 1.], &[1., 1.]];
    assert_eq!(own_orientation(CellKind::Quad, &bowtie), 0);
    assert!(worst_of(CellKind::Quad, &bowtie, 0).inverted());
    assert_eq!(quality(CellKind::Quad, &bowtie, 0), 0.0);
    // Arrowhead: counter-clockwise overall, one re-entrant corner (J = −2 there; VTK −0.8).
    let dart: [&[f64]; 4] = [&[0., 0.], &[2., 0.], &[0.5, 0.5], &[0., 2.]];
    assert_eq!(own_orientation(CellKind::Quad, &dart), 1);
    let w = worst_of(CellKind::Quad, &dart, 1);
    assert!(w.inverted());
    assert_eq!((w.corner, w.volume), (2, -1.0));
    close(w.scaled, -0.8, 1e-15);
    assert_eq!(quality(CellKind::Quad, &dart, 1), 0.0);
}

#[test]
fn flattened_tetrahedron_is_inverted() {
    let flat: [&[f64]; 4] = [&[0., 0., 0.], &[1., 0., 0.], &[0., 1., 0.], &[1., 1., 0.]];
    assert_eq!(own_orientation(CellKind::Tetra, &flat), 0);
    let w = worst_of(CellKind::Tetra, &flat, 0);
    assert!(w.inverted());
    assert_eq!(w.volume, 0.0);
    assert_eq!(quality(CellKind::Tetra, &flat, 0), 0.0);
    // Nearly flat to rounding: still zero.
    let rounded: [&[f64]; 4] = [
        &[0., 0., 0.],
        &[1., 0., 0.],
        &[0., 1., 0.],
        &[0.3, 0.3, 1e-14],
    ];
    assert_eq!(own_orientation(CellKind::Tetra, &rounded), 0);
    assert!(worst_of(CellKind::Tetra, &rounded, 1).inverted());
}

#[test]
fn corners_agree_with_the_geometry_kernel() {
    let hex: Vec<f64> = UNIT_CUBE.concat().iter().map(|x| x * 1.5 + 0.1).collect();
    let nodes: Vec<usize> = (0..8).collect();
    let p = gather::<3>(&hex, &nodes);
    for c in CellKind::Hexahedron.table().corners {
        assert_eq!(
            measures::corner(&p, c).0,
            corner_jacobian::<3>(&hex, &nodes, c)
        );
    }
}

/// Two triangles and a quad: 0 counter-clockwise, 1 clockwise, 2 counter-clockwise.
fn small_mesh() -> Mesh {
    let coords = vec![0., 0., 1., 0., 1., 1., 0., 1., 2., 0., 2., 1.];
    let mut cells = Cells::new();
    cells.push(CellKind::Triangle, &[0, 1, 2]);
    cells.push(CellKind::Triangle, &[0, 3, 2]);
    cells.push(CellKind::Quad, &[1, 4, 5, 2]);
    Mesh::new(2, coords, cells, vec![]).unwrap()
}

#[test]
fn mesh_orientation_quality_and_report() {
    let mesh = small_mesh();
    let reference = orientation(&mesh);
    assert_eq!(reference, [1, -1, 1]);
    let q = qualities(&mesh, &mesh.coords, &reference);
    close(q[0], 2.0 * 2f64.sqrt() - 2.0, 1e-15);
    close(q[1], 2.0 * 2f64.sqrt() - 2.0, 1e-15);
    assert_eq!(q[2], 1.0);
    assert!(inverted_cells(&mesh, &mesh.coords, &reference).is_empty());
    let r = report(&mesh, &mesh.coords, &reference);
    assert_eq!(r.inverted, 0);
    assert_eq!(r.quality, Summary::new(&q));
}

#[test]
fn deformed_state_reports_where_a_cell_inverted() {
    let mesh = small_mesh();
    let reference = orientation(&mesh);
    // Node 2 pushed to (1.5, -1): triangle 0 flips, triangle 1 (clockwise) stays
    // clockwise, the quad becomes re-entrant at node 2.
    let mut coords = mesh.coords.clone();
    coords[4..6].copy_from_slice(&[1.5, -1.0]);
    assert_eq!(inverted_cells(&mesh, &coords, &reference), [0, 2]);
    let inv = inversions(&mesh, &coords, &reference);
    assert_eq!(inv[0].cell, 0);
    assert_eq!(inv[0].centroid, [2.5 / 3.0, -1.0 / 3.0]);
    assert_eq!(inv[0].volume, -0.5);
    assert_eq!(orientation_at(&mesh, &coords)[0], -1);
    let q = qualities(&mesh, &coords, &reference);
    assert_eq!((q[0], q[2]), (0.0, 0.0));
    assert!(q[1] > 0.0);
    assert_eq!(report(&mesh, &coords, &reference).inverted, 2);
}

#[test]
#[should_panic(expected = "coordinates for 4 numbers, the mesh has 12")]
fn wrong_coordinate_count_is_a_programming_error() {
    let mesh = small_mesh();
    qualities(&mesh, &[0.0; 4], &[1, 1, 1]);
}

#[test]
fn results_do_not_depend_on_the_number_of_threads() {
    let mesh = small_mesh();
    let mut coords = mesh.coords.clone();
    coords[4..6].copy_from_slice(&[1.5, -1.0]);
    let run = || {
        let reference = orientation(&mesh);
        (
            qualities(&mesh, &coords, &reference),
            inversions(&mesh, &coords, &reference),
            report(&mesh, &coords, &reference),
        )
    };
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(run);
    let four = rayon::ThreadPoolBuilder::new()
        .num_threads(4)
        .build()
        .unwrap()
        .install(run);
    assert_eq!(one, four);
}

/// Numbers in `[-1, 1)` from a fixed sequence.
fn numbers(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        2.0 * (state >> 11) as f64 / (1u64 << 53) as f64 - 1.0
    }
}

/// [`worst`] as every kind computes it: each corner with its own edge lengths.
fn worst_by_corner<const D: usize>(table: &KindTable, p: &[[f64; D]], s: f64) -> Corner {
    let mut out = Corner {
        corner: 0,
        scaled: f64::INFINITY,
        volume: 0.0,
    };
    for (k, c) in table.corners.iter().enumerate() {
        let (j, lengths) = measures::corner(p, c);
        let scaled = measures::scaled(s * j, lengths);
        if scaled < out.scaled || k == 0 {
            out = Corner {
                corner: k,
                scaled,
                volume: s * j / factorial(D),
            };
        }
    }
    out
}

#[test]
fn simplex_corners_sharing_edge_lengths_are_the_corner_formula_bit_for_bit() {
    let mut next = numbers(7);
    let bits = |c: Corner| (c.corner, c.scaled.to_bits(), c.volume.to_bits());
    for k in 0..4000 {
        let s = if k % 2 == 0 { 1.0 } else { -1.0 };
        let mut tet: [[f64; 3]; 4] = std::array::from_fn(|_| [next(), next(), next()]);
        let mut tri: [[f64; 2]; 3] = std::array::from_fn(|_| [next(), next()]);
        if k % 7 == 0 {
            // A collapsed edge: a corner of zero length product.
            tet[3] = tet[1];
            tri[2] = tri[0];
        }
        let table = CellKind::Tetra.table();
        assert_eq!(
            bits(worst(table, &tet, s)),
            bits(worst_by_corner(table, &tet, s))
        );
        let table = CellKind::Triangle.table();
        assert_eq!(
            bits(worst(table, &tri, s)),
            bits(worst_by_corner(table, &tri, s))
        );
    }
}

#[test]
fn the_one_pass_check_equals_the_separate_measures_for_any_threads() {
    // 12³ cubes of 6 tetrahedra: more cells than two parallel pieces.
    let n = 13;
    let reference_mesh = crate::mesh::samples::jittered_grid(3, n, 2, || 0.0).unwrap();
    let reference = orientation(&reference_mesh);
    let mut shift = numbers(3);
    let mesh = crate::mesh::samples::jittered_grid(3, n, 2, || 0.0).unwrap();
    let h = 1.0 / (n - 1) as f64;
    let coords: Vec<f64> = mesh.coords.iter().map(|x| x + 0.45 * h * shift()).collect();
    assert!(mesh.cells.len() > 2 * CELLS);
    let run = || qualities_and_inversions(&mesh, &coords, &reference);
    let pool = |threads| rayon::ThreadPoolBuilder::new().num_threads(threads).build();
    let one = pool(1).unwrap().install(run);
    let four = pool(4).unwrap().install(run);
    assert_eq!(one, four);
    let separate = (
        qualities(&mesh, &coords, &reference),
        inversions(&mesh, &coords, &reference),
    );
    assert_eq!(one, separate);
    assert!(!one.1.is_empty(), "the jitter inverts some cells");
    assert_eq!(
        report(&mesh, &coords, &reference).inverted,
        one.1.len(),
        "report counts the same cells"
    );
}

/// checkMesh's tests see the faces, not the kind: a grid's cells written as
/// polygons and polyhedra of the same faces get the same verdicts, number
/// for number; a cube grid's polyhedra and a square grid's polygons have
/// quality 1, and a tangled cell fails both ways.
#[test]
fn general_cells_get_the_verdicts_of_the_paper_s_kinds() {
    for (dim, kind) in [(2, 1), (2, 0), (3, 0), (3, 1), (3, 2), (3, 3)] {
        let mesh = samples::jittered_grid(dim, 4, kind, || 0.0).unwrap();
        let general = samples::as_general(&mesh);
        let reference = orientation(&general);
        assert!(reference.iter().all(|&s| s == 1), "{dim}D kind {kind}");
        let q = qualities(&general, &general.coords, &reference);
        if kind == if dim == 2 { 1 } else { 0 } {
            assert!(q.iter().all(|&v| (v - 1.0).abs() < 1e-12), "{q:?}");
        }
        let mut seed = 3u64;
        let mut coords = mesh.coords.clone();
        for x in &mut coords {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            *x += 0.6 * ((seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5) / 3.0;
        }
        let fixed = verdicts(&mesh, &coords, &orientation(&mesh));
        let same = verdicts(&general, &coords, &reference);
        assert_eq!(fixed, same, "{dim}D kind {kind}");
        let bad: Vec<usize> = (0..same.len())
            .filter(|&c| same[c].failure().is_some())
            .collect();
        let found: Vec<usize> = inversions(&general, &coords, &reference)
            .iter()
            .map(|i| i.cell)
            .collect();
        assert_eq!(found, bad, "{dim}D kind {kind}");
    }
}
