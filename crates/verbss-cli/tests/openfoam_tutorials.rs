//! OpenFOAM's own tutorial meshes, built as their Allrun builds them, and a
//! snappyHexMesh mesh of our own (moved, and its wall deformed): polyhedra
//! read and moved, and every mesh verbss accepts passes checkMesh's cell
//! tests (docs/method.md, "Validity"). The tutorials with interfaces are in
//! `openfoam_interfaces.rs`.

use std::path::{Path, PathBuf};

mod common;

use common::foam::{
    check_mesh_failures, copy_tutorial, count_after, failures, foam, have_tutorial, have_utilities,
    start_from, write_system,
};
use common::{deform_to, stderr, verbss};
use verbss::io::WriteOptions;

#[test]
fn twisting_column_turned_half_a_turn_is_valid_for_check_mesh_or_stops_naming_the_cell() {
    let name = "mesh/moveDynamicMesh/twistingColumn";
    if !have_tutorial(name) || !have_utilities(&["blockMesh", "checkMesh"]) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("column");
    copy_tutorial(name, &case);
    foam("blockMesh", &case, &[]);
    let out = dir.path().join("turned");
    let o = deform_to(
        &case,
        &out,
        &[
            "--moving", "top", "--rotate", "180", "--axis", "0,0,1", "--center", "0,0,0",
            "--steps", "50",
        ],
    );
    // Before checkMesh's cell tests judged a step, the run ended with exit 0
    // and a mesh of 4 cells checkMesh fails (aspect ratio 3742).
    let err = stderr(&o);
    match o.status.code() {
        Some(0) => {}
        Some(3) => assert!(
            err.starts_with("error: step ") && err.contains(": element "),
            "{err}"
        ),
        _ => panic!("{err}"),
    }
    std::fs::create_dir_all(out.join("system")).unwrap();
    write_system(&out);
    assert_eq!(check_mesh_failures(&out, &[]), Vec::<String>::new());
}

/// A 3D box of 4 × 4 × 4 hexahedra (patch `walls`) made by blockMesh.
fn box_case(case: &Path) {
    write_system(case);
    let dict = "FoamFile { version 2.0; format ascii; class dictionary; object blockMeshDict; }\n\
         vertices ((0 0 0) (1 0 0) (1 1 0) (0 1 0) (0 0 1) (1 0 1) (1 1 1) (0 1 1));\n\
         blocks (hex (0 1 2 3 4 5 6 7) (4 4 4) simpleGrading (1 1 1));\n\
         boundary (walls { type wall; faces ((0 4 7 3) (1 2 6 5) (0 1 5 4) (3 7 6 2) \
         (0 3 2 1) (4 5 6 7)); });\n";
    std::fs::write(case.join("system/blockMeshDict"), dict).unwrap();
    foam("blockMesh", case, &[]);
}

#[test]
fn cells_a_case_holds_inverted_are_counted_as_check_mesh_counts_them() {
    if !have_utilities(&["blockMesh", "checkMesh"]) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("box");
    box_case(&case);
    let mesh = verbss::io::read(&case).unwrap();
    // Two interior points pushed through their neighbours: cells tangle.
    let mut coords = mesh.coords.clone();
    let at = |x: f64, y: f64, z: f64| {
        (0..mesh.node_count())
            .find(|&i| {
                let p = mesh.point(i);
                (p[0] - x).abs() + (p[1] - y).abs() + (p[2] - z).abs() < 1e-9
            })
            .unwrap()
    };
    let (a, b) = (at(0.25, 0.25, 0.25), at(0.5, 0.75, 0.5));
    for (k, (da, db)) in [(0.71, 0.05), (0.23, -0.11), (0.11, -0.62)]
        .iter()
        .enumerate()
    {
        coords[3 * a + k] += da;
        coords[3 * b + k] += db;
    }
    let moved = dir.path().join("tangled");
    verbss::io::write_moved(&moved, &mesh, &coords, &WriteOptions::default()).unwrap();
    write_system(&moved);
    let log = foam("checkMesh", &moved, &[]);
    let negative = count_after(&log, "Number of negative volume cells:").unwrap_or(0);
    let pyramids = count_after(&log, "***Error in face pyramids:").unwrap_or(0);
    assert!(negative > 0 && pyramids > 0, "{log}");
    let o = verbss(&["quality", moved.to_str().unwrap(), "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let ours = &v["checkmesh"];
    assert_eq!(ours["negative_volume_cells"], negative, "{log}");
    assert_eq!(ours["incorrectly_oriented_faces"], pyramids, "{log}");
    let stretched = log
        .find("High aspect ratio cells found")
        .map_or(0, |at| count_after(&log[at..], "number of cells").unwrap());
    assert_eq!(ours["high_aspect_ratio_cells"], stretched, "{log}");
    // Orientation comes from the faces' convention: every such cell is
    // inverted, none a valid mirrored one.
    assert!(v["inverted"].as_u64().unwrap() >= negative as u64, "{v}");
}

/// The 2D wing of the wingMotion tutorial as its Allrun makes it:
/// blockMesh and snappyHexMesh on the 3D slab, then extrudeMesh and
/// createPatch into the 2D case, whose path this returns.
fn wing_motion(dir: &Path) -> PathBuf {
    let tutorial = dir.join("wingMotion");
    copy_tutorial("incompressible/pimpleFoam/RAS/wingMotion", &tutorial);
    let slab = tutorial.join("wingMotion_snappyHexMesh");
    foam("blockMesh", &slab, &[]);
    foam("snappyHexMesh", &slab, &["-overwrite"]);
    let case = tutorial.join("wingMotion2D_simpleFoam");
    foam("extrudeMesh", &case, &[]);
    foam("createPatch", &case, &["-overwrite"]);
    case
}

#[test]
fn wing_motion_pitches_40_degrees_and_every_step_written_passes_check_mesh() {
    let name = "incompressible/pimpleFoam/RAS/wingMotion";
    let tools = [
        "blockMesh",
        "snappyHexMesh",
        "extrudeMesh",
        "createPatch",
        "checkMesh",
    ];
    if !have_tutorial(name) || !have_utilities(&tools) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let case = wing_motion(dir.path());
    let mesh = verbss::io::read(&case).unwrap();
    let polygons = mesh
        .cells
        .kinds
        .iter()
        .filter(|&&k| k == verbss::CellKind::Polygon)
        .count();
    assert_eq!((mesh.dim, mesh.cell_count(), polygons), (2, 12556, 637));
    // The tutorial's own mesh fails one check, on one face: its skewness.
    let input = check_mesh_failures(&case, &[]);
    assert!(
        input.iter().all(|l| l.contains("highly skew faces")),
        "{input:?}"
    );
    let out = dir.path().join("pitched");
    let o = deform_to(
        &case,
        &out,
        &[
            "--moving",
            "wing",
            "--rotate",
            "40",
            "--center",
            "0.25,0.007",
            "--steps",
            "40",
            "--every",
            "10",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    // Steps 10, 20, 30 and 40 of the series as times of the new case (the
    // last also in its constant/polyMesh): checkMesh finds nothing but that
    // skewness on any.
    let last = verbss::io::read(&out).unwrap();
    let frame = verbss::io::read(&dir.path().join("pitched_0040.vtu")).unwrap();
    assert_eq!(frame.coords, last.coords);
    for step in [10, 20, 30, 40] {
        let frame = dir.path().join(format!("pitched_{step:04}.vtu"));
        let coords = verbss::io::read(&frame).unwrap().coords;
        let mut options = WriteOptions::default();
        options.foam_time = Some(step.to_string());
        let moved = verbss::io::read(&out).unwrap();
        verbss::io::write_moved(&out, &moved, &coords, &options).unwrap();
    }
    write_system(&out);
    let log = foam("checkMesh", &out, &["-time", "10:40"]);
    assert_eq!(log.matches("Time = ").count(), 4, "{log}");
    let found = failures(&log);
    assert!(
        found.iter().all(|l| l.contains("highly skew faces")),
        "{log}"
    );
}

/// A sphere (patch `sphere`, radius 0.5) in a channel 6 × 2 × 2 of 60 × 20
/// × 20 cells, the sphere's cells refined once by snappyHexMesh: about
/// 27,000 cells, 1,100 of them polyhedra.
fn sphere_case(case: &Path) {
    write_system(case);
    let head = |object: &str| {
        format!("FoamFile {{ version 2.0; format ascii; class dictionary; object {object}; }}\n")
    };
    let block = "vertices ((-2 -1 -1) (4 -1 -1) (4 1 -1) (-2 1 -1) (-2 -1 1) (4 -1 1) (4 1 1) \
         (-2 1 1));\nblocks (hex (0 1 2 3 4 5 6 7) (60 20 20) simpleGrading (1 1 1));\n\
         boundary (inlet { type patch; faces ((0 4 7 3)); } outlet { type patch; faces \
         ((1 2 6 5)); } walls { type wall; faces ((0 1 5 4) (3 7 6 2) (0 3 2 1) (4 5 6 7)); });\n";
    let snappy = "castellatedMesh true; snap true; addLayers false;\n\
         geometry { sphere { type searchableSphere; centre (0 0 0); radius 0.5; } }\n\
         castellatedMeshControls { maxLocalCells 1000000; maxGlobalCells 2000000; \
         minRefinementCells 0; nCellsBetweenLevels 2; maxLoadUnbalance 0.1; \
         resolveFeatureAngle 30; allowFreeStandingZoneFaces true; features (); \
         refinementSurfaces { sphere { level (1 1); patchInfo { type wall; } } } \
         refinementRegions {} locationInMesh (3 0.5 0.5); }\n\
         snapControls { nSmoothPatch 3; tolerance 2.0; nSolveIter 30; nRelaxIter 5; \
         nFeatureSnapIter 10; implicitFeatureSnap false; explicitFeatureSnap false; \
         multiRegionFeatureSnap false; }\n\
         addLayersControls { relativeSizes true; layers {} expansionRatio 1; \
         finalLayerThickness 0.3; minThickness 0.1; nGrow 0; featureAngle 60; nRelaxIter 3; \
         nSmoothSurfaceNormals 1; nSmoothNormals 3; nSmoothThickness 10; \
         maxFaceThicknessRatio 0.5; maxThicknessToMedialRatio 0.3; minMedialAxisAngle 90; \
         nBufferCellsNoExtrude 0; nLayerIter 50; }\n\
         meshQualityControls { maxNonOrtho 65; maxBoundarySkewness 20; maxInternalSkewness 4; \
         maxConcave 80; minVol 1e-13; minTetQuality 1e-15; minArea -1; minTwist 0.02; \
         minDeterminant 0.001; minFaceWeight 0.05; minVolRatio 0.01; minTriangleTwist -1; \
         nSmoothScale 4; errorReduction 0.75; relaxed { maxNonOrtho 75; } }\n\
         mergeTolerance 1e-6;\n";
    let system = case.join("system");
    std::fs::write(system.join("blockMeshDict"), head("blockMeshDict") + block).unwrap();
    std::fs::write(
        system.join("snappyHexMeshDict"),
        head("snappyHexMeshDict") + snappy,
    )
    .unwrap();
    foam("blockMesh", case, &[]);
    foam("snappyHexMesh", case, &["-overwrite"]);
}

#[test]
fn a_snappy_hex_mesh_sphere_moves_and_passes_check_mesh() {
    if !have_utilities(&["blockMesh", "snappyHexMesh", "checkMesh"]) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("sphere");
    sphere_case(&case);
    let log = foam("checkMesh", &case, &[]);
    let mesh = verbss::io::read(&case).unwrap();
    let polyhedra = mesh
        .cells
        .kinds
        .iter()
        .filter(|&&k| k == verbss::CellKind::Polyhedron)
        .count();
    assert_eq!(count_after(&log, "polyhedra:"), Some(polyhedra), "{log}");
    assert_eq!(
        count_after(&log, "cells:"),
        Some(mesh.cell_count()),
        "{log}"
    );
    assert!(polyhedra > 500, "{polyhedra} polyhedra");
    // The default (5 steps) and the paper's method (springs on every cell,
    // the polyhedra's from their faces; one step, to keep the test short):
    // both pass checkMesh.
    for (out, method, steps) in [("blended", "robust", "5"), ("moved", "verbss", "1")] {
        let out = dir.path().join(out);
        let motion = [
            "--moving",
            "sphere",
            "--translate",
            "0.1,0.05,0",
            "--steps",
            steps,
        ];
        let o = deform_to(&case, &out, &[&motion[..], &["--method", method]].concat());
        assert!(o.status.success(), "{method}: {}", stderr(&o));
        write_system(&out);
        assert_eq!(
            check_mesh_failures(&out, &[]),
            Vec::<String>::new(),
            "{method}"
        );
    }
    // A deforming wall: the sphere stretched into an ellipsoid (x by 1.1,
    // y and z by 0.95) through given positions, in 2 steps.
    let sphere = mesh.group("sphere").unwrap().nodes();
    let stretched = |p: &[f64]| [1.1 * p[0], 0.95 * p[1], 0.95 * p[2]];
    let mut table = String::from("id,x,y,z\n");
    for &i in &sphere {
        let q = stretched(mesh.point(i));
        table += &format!("{i},{},{},{}\n", q[0], q[1], q[2]);
    }
    let positions = dir.path().join("ellipsoid.csv");
    std::fs::write(&positions, table).unwrap();
    let out = dir.path().join("stretched");
    let motion = [
        "--moving",
        "sphere",
        "--positions",
        positions.to_str().unwrap(),
        "--steps",
        "2",
    ];
    let o = deform_to(&case, &out, &motion);
    assert!(o.status.success(), "{}", stderr(&o));
    let moved = verbss::io::read(&out).unwrap();
    for &i in &sphere {
        let (want, got) = (stretched(mesh.point(i)), moved.point(i));
        assert!((0..3).all(|d| (want[d] - got[d]).abs() < 1e-12), "node {i}");
    }
    write_system(&out);
    assert_eq!(check_mesh_failures(&out, &[]), Vec::<String>::new());
    // The polyhedra written to .vtu and read back; SU2 cannot hold them.
    let vtu = dir.path().join("sphere.vtu");
    let o = verbss(&["convert", case.to_str().unwrap(), vtu.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let back = verbss::io::read(&vtu).unwrap();
    assert_eq!(back.cells, mesh.cells);
    assert_eq!(back.coords, mesh.coords);
    let su2 = dir.path().join("sphere.su2");
    let o = verbss(&["convert", case.to_str().unwrap(), su2.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let first = mesh.cells.first_general().unwrap() + 1;
    assert_eq!(
        stderr(&o),
        format!(
            "error: {}: the SU2 format cannot hold element {first}, a polyhedron (write .vtu, \
             or an OpenFOAM case; a mesh read from a .cgns file also writes back as .cgns)\n",
            su2.display()
        )
    );
    assert!(!su2.exists());
}

/// docs/openfoam.md's loop from a tutorial to a flow-solver run on the
/// moved mesh: airFoil2D's airfoil pitched 2° in 2 steps into its own case
/// (time directory 2 of `deltaT 1`), the fields copied there, and
/// simpleFoam started from that time reads the moved mesh. checkMesh finds
/// on it only what it finds on the tutorial's own mesh (its faces are not
/// in upper triangular order).
#[test]
fn airfoil_2d_pitched_then_simple_foam_runs_on_the_moved_mesh() {
    let name = "incompressible/simpleFoam/airFoil2D";
    let tools = ["simpleFoam", "foamDictionary", "checkMesh"];
    if !have_tutorial(name) || !have_utilities(&tools) {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("airFoil2D");
    copy_tutorial(name, &case);
    let o = deform_to(
        &case,
        &case,
        &[
            "--moving", "walls", "--rotate", "2", "--center", "0,0", "--steps", "2",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let moved = case.join("2");
    assert!(moved.join("polyMesh/points").is_file());
    assert!(!case.join("1").exists());
    start_from(&case, "2", "10");
    let log = foam("simpleFoam", &case, &[]);
    assert!(log.contains("Create mesh for time = 2\n"), "{log}");
    assert!(
        log.contains("\nTime = 10\n") && log.contains("\nEnd\n"),
        "{log}"
    );
    assert_eq!(
        check_mesh_failures(&case, &["-time", "2"]),
        check_mesh_failures(&case, &["-time", "0"])
    );
    assert_eq!(
        check_mesh_failures(&case, &["-time", "0"]),
        [" ***Faces not in upper triangular order."]
    );
}
