use std::collections::HashMap;
use std::path::Path;

use super::*;
use crate::mesh::samples::hex_wedge_pyramid_tet;
use crate::mesh::{Coupling, Interface, Transform};
use crate::quality::orientation;

/// The five polyMesh files of a 3D `mesh` as text: faces from the kinds'
/// outward facets (each started at a different corner), internal faces
/// first, then one patch per group (its facets) and `other` for the rest,
/// `empty` as the type of the patches named in `empty`.
fn poly_files(mesh: &Mesh, empty: &[&str]) -> Vec<(&'static str, String)> {
    let key = |f: &[usize]| {
        let mut k = f.to_vec();
        k.sort_unstable();
        k
    };
    let mut seen: HashMap<Vec<usize>, usize> = HashMap::new();
    let mut faces: Vec<(Vec<usize>, usize, Option<usize>)> = Vec::new();
    for (c, (kind, nodes)) in mesh.cells.iter().enumerate() {
        for facet in kind.table().facets {
            let f: Vec<usize> = facet.iter().map(|&l| nodes[l]).collect();
            match seen.get(&key(&f)) {
                Some(&i) => faces[i].2 = Some(c),
                None => {
                    seen.insert(key(&f), faces.len());
                    faces.push((f, c, None));
                }
            }
        }
    }
    let patch_of = |f: &[usize]| {
        mesh.groups
            .iter()
            .position(|g| g.facets.iter().any(|(_, n)| key(n) == key(f)))
            .unwrap_or(mesh.groups.len())
    };
    faces.sort_by_key(|(f, _, n)| (n.is_none(), n.is_none().then(|| patch_of(f))));
    let names: Vec<&str> = mesh
        .groups
        .iter()
        .map(|g| g.name.as_str())
        .chain(["other"])
        .collect();
    let head = |class: &str, object: &str| {
        format!(
            "/* made by a test */\nFoamFile\n{{\n    version 2.0;\n    format ascii;\n    \
             class {class};\n    location \"constant/polyMesh\";\n    object {object};\n}}\n\
             // * * * //\n\n"
        )
    };
    let mut points = head("vectorField", "points") + &format!("{}\n(\n", mesh.node_count());
    for i in 0..mesh.node_count() {
        let p = mesh.point(i);
        points += &format!("({} {} {})\n", p[0], p[1], p[2]);
    }
    let mut text = head("faceList", "faces") + &format!("{}\n(\n", faces.len());
    for (i, (f, _, _)) in faces.iter().enumerate() {
        let r = i % f.len();
        let rotated: Vec<String> = f[r..].iter().chain(&f[..r]).map(usize::to_string).collect();
        text += &format!("{}({})\n", f.len(), rotated.join(" "));
    }
    let owners: Vec<String> = faces.iter().map(|f| f.1.to_string()).collect();
    let neighbours: Vec<String> = faces
        .iter()
        .filter_map(|f| f.2.map(|n| n.to_string()))
        .collect();
    let n_internal = neighbours.len();
    let mut boundary = head("polyBoundaryMesh", "boundary") + &format!("{}\n(\n", names.len());
    let mut start = n_internal;
    for (k, name) in names.iter().enumerate() {
        let n = faces[n_internal..]
            .iter()
            .filter(|(f, _, _)| patch_of(f) == k)
            .count();
        let kind = if empty.contains(name) {
            "empty"
        } else {
            "wall"
        };
        boundary += &format!(
            "    {name}\n    {{\n        type {kind};\n        inGroups 1({kind});\n        \
             nFaces {n};\n        startFace {start};\n    }}\n"
        );
        start += n;
    }
    vec![
        ("points", points + ")\n"),
        ("faces", text + ")\n"),
        (
            "owner",
            head("labelList", "owner")
                + &format!("{}\n(\n{}\n)\n", owners.len(), owners.join("\n")),
        ),
        (
            "neighbour",
            head("labelList", "neighbour") + &format!("{n_internal}({})\n", neighbours.join(" ")),
        ),
        ("boundary", boundary + ")\n"),
    ]
}

/// Writes `files` into `dir/constant/polyMesh`.
pub(super) fn write_files(dir: &Path, files: &[(&str, String)]) {
    let poly = dir.join("constant/polyMesh");
    std::fs::create_dir_all(&poly).unwrap();
    for (name, text) in files {
        std::fs::write(poly.join(name), text).unwrap();
    }
}

/// The cells as (kind, sorted nodes).
fn cell_sets(mesh: &Mesh) -> Vec<(CellKind, Vec<usize>)> {
    mesh.cells
        .iter()
        .map(|(k, n)| {
            let mut n = n.to_vec();
            n.sort_unstable();
            (k, n)
        })
        .collect()
}

/// Reads `files` with `edit` applied to file `name`: the error message.
fn error_with(name: &str, edit: impl Fn(&str) -> String) -> String {
    let mut files = poly_files(&hex_wedge_pyramid_tet(), &[]);
    for f in &mut files {
        if f.0 == name {
            f.1 = edit(&f.1);
        }
    }
    let dir = tempfile::tempdir().unwrap();
    write_files(dir.path(), &files);
    match read(dir.path()) {
        Ok(_) => "read without an error".into(),
        Err(e) => e.to_string(),
    }
}

#[test]
fn the_four_kinds_are_read_positively_oriented_with_their_patches() {
    let sample = hex_wedge_pyramid_tet();
    let dir = tempfile::tempdir().unwrap();
    write_files(dir.path(), &poly_files(&sample, &[]));
    let mesh = read(dir.path()).unwrap();
    assert_eq!(mesh.dim, 3);
    assert_eq!(mesh.coords, sample.coords);
    assert_eq!(cell_sets(&mesh), cell_sets(&sample));
    assert_eq!(orientation(&mesh), vec![1; 4]);
    assert_eq!(mesh.group_names(), ["floor", "roof", "other"]);
    for (read, want) in mesh.groups.iter().zip(&sample.groups) {
        assert_eq!(read.facets.kinds, want.facets.kinds);
        let mut a = read.nodes();
        let mut b = want.nodes();
        a.sort_unstable();
        b.sort_unstable();
        assert_eq!(a, b);
    }
    // The polyMesh directory itself reads the same.
    let again = read(&dir.path().join("constant/polyMesh")).unwrap();
    assert_eq!(again.cells, mesh.cells);
}

#[test]
fn compact_and_countless_lists_and_comments_read_the_same() {
    let sample = hex_wedge_pyramid_tet();
    let mut files = poly_files(&sample, &[]);
    let plain = {
        let dir = tempfile::tempdir().unwrap();
        write_files(dir.path(), &files);
        read(dir.path()).unwrap()
    };
    for (name, text) in &mut files {
        if *name == "points" {
            // A list without its count, with comments inside.
            let at = text.find("\n(\n").unwrap();
            let count_line = text[..at].rfind('\n').unwrap();
            *text = format!(
                "{}\n// no count\n(\n/* first point */{}",
                &text[..count_line],
                &text[at + 3..]
            );
        }
    }
    let dir = tempfile::tempdir().unwrap();
    write_files(dir.path(), &files);
    assert_eq!(read(dir.path()).unwrap().coords, plain.coords);
    // One cell: owner written as a compact list `N{0}`.
    let one = Mesh::new(
        3,
        sample.coords[..24].to_vec(),
        {
            let mut c = Cells::new();
            c.push(CellKind::Hexahedron, &[0, 1, 2, 3, 4, 5, 6, 7]);
            c
        },
        vec![],
    )
    .unwrap();
    let mut files = poly_files(&one, &[]);
    for (name, text) in &mut files {
        if *name == "owner" {
            let at = text.find("6\n(").unwrap();
            *text = format!("{}6{{0}}\n", &text[..at]);
        }
    }
    let dir = tempfile::tempdir().unwrap();
    write_files(dir.path(), &files);
    let mesh = read(dir.path()).unwrap();
    assert_eq!(mesh.cells.kinds, [CellKind::Hexahedron]);
    assert_eq!(orientation(&mesh), [1]);
}

/// Two unit squares side by side, 0.1 thick: a 2D case with `left` (x = 0),
/// `other` (the rest of the outline) and `sides` (front and back, `empty`).
pub(super) fn two_squares() -> (Mesh, Vec<(&'static str, String)>) {
    let mut coords = Vec::new();
    for z in [0.0, 0.1] {
        for (x, y) in [(0., 0.), (1., 0.), (2., 0.), (0., 1.), (1., 1.), (2., 1.)] {
            coords.extend([x, y, z]);
        }
    }
    let mut cells = Cells::new();
    cells.push(CellKind::Hexahedron, &[0, 1, 4, 3, 6, 7, 10, 9]);
    cells.push(CellKind::Hexahedron, &[1, 2, 5, 4, 7, 8, 11, 10]);
    let mut left = Cells::new();
    left.push(CellKind::Quad, &[0, 6, 9, 3]);
    let mut sides = Cells::new();
    sides.push(CellKind::Quad, &[0, 3, 4, 1]);
    sides.push(CellKind::Quad, &[1, 4, 5, 2]);
    sides.push(CellKind::Quad, &[6, 7, 10, 9]);
    sides.push(CellKind::Quad, &[7, 8, 11, 10]);
    let groups = vec![
        Group {
            name: "left".into(),
            tag: None,
            facets: left,
        },
        Group {
            name: "sides".into(),
            tag: None,
            facets: sides,
        },
    ];
    let mesh = Mesh::new(3, coords, cells, groups).unwrap();
    let files = poly_files(&mesh, &["sides"]);
    (mesh, files)
}

#[test]
fn a_2d_case_is_read_as_its_back_plane_and_written_on_both() {
    let (_, files) = two_squares();
    let dir = tempfile::tempdir().unwrap();
    write_files(dir.path(), &files);
    let mut mesh = read(dir.path()).unwrap();
    assert_eq!(mesh.dim, 2);
    assert_eq!(mesh.node_count(), 6);
    assert_eq!(mesh.cells.kinds, [CellKind::Quad, CellKind::Quad]);
    assert_eq!(orientation(&mesh), [1, 1]);
    assert_eq!(mesh.group_names(), ["left", "other"]);
    assert_eq!(mesh.group("left").unwrap().facets.kinds, [CellKind::Line]);
    assert_eq!(mesh.group("other").unwrap().facets.len(), 5);
    // Node 4 is (1, 1): move it; its front point (label 10) follows.
    assert_eq!(mesh.point(4), [1.0, 1.0]);
    mesh.coords[8] = 1.25;
    write(dir.path(), &mesh, Some("0.5")).unwrap();
    let moved = std::fs::read_to_string(dir.path().join("0.5/polyMesh/points")).unwrap();
    assert!(moved.contains("(1.25 1.0 0.0)\n"), "{moved}");
    assert!(moved.contains("(1.25 1.0 0.1)\n"), "{moved}");
    let case = dir.path().join("0.5/polyMesh");
    for (name, text) in &files {
        if *name != "points" {
            std::fs::write(case.join(name), text).unwrap();
        }
    }
    let back = read(&case).unwrap();
    assert_eq!(back.coords, mesh.coords);
}

#[test]
fn a_3d_mesh_writes_back_the_same_points_and_topology() {
    let sample = hex_wedge_pyramid_tet();
    let dir = tempfile::tempdir().unwrap();
    write_files(dir.path(), &poly_files(&sample, &[]));
    let mesh = read(dir.path()).unwrap();
    let out = dir.path().join("copy");
    write(&out, &mesh, None).unwrap();
    let again = read(&out).unwrap();
    assert_eq!(again.coords, mesh.coords);
    assert_eq!(again.cells, mesh.cells);
    for name in ["faces", "owner", "neighbour", "boundary"] {
        let file = |d: &Path| std::fs::read(d.join("constant/polyMesh").join(name)).unwrap();
        assert_eq!(file(dir.path()), file(&out));
    }
    // The case it came from, without a time: its own points, replaced.
    write(dir.path(), &mesh, None).unwrap();
    assert_eq!(read(dir.path()).unwrap().coords, mesh.coords);
    // A mesh of another source has no faces to keep.
    let e = write(&dir.path().join("x"), &sample, None).unwrap_err();
    assert!(
        e.to_string().contains("only from a mesh read from one"),
        "{e}"
    );
}

#[test]
fn a_general_polyhedron_is_read_with_its_faces() {
    // A unit cube whose bottom is two triangles: 7 faces.
    let cube = &hex_wedge_pyramid_tet().coords[..24];
    let points: Vec<String> = cube
        .chunks(3)
        .map(|p| format!("({} {} {})", p[0], p[1], p[2]))
        .collect();
    let faces = "7(3(0 3 2) 3(0 2 1) 4(4 5 6 7) 4(0 1 5 4) 4(1 2 6 5) 4(2 3 7 6) 4(3 0 4 7))";
    let files = vec![
        ("points", format!("8({})", points.join(" "))),
        ("faces", faces.to_string()),
        ("owner", "7{0}".to_string()),
        ("neighbour", "0()".to_string()),
        (
            "boundary",
            "1(all { type wall; nFaces 7; startFace 0; })".to_string(),
        ),
    ];
    let dir = tempfile::tempdir().unwrap();
    write_files(dir.path(), &files);
    let mesh = read(dir.path()).unwrap();
    assert_eq!(mesh.cells.kinds, [CellKind::Polyhedron]);
    assert_eq!(mesh.cells.cell(0), [0, 3, 2, 1, 4, 5, 6, 7]);
    let faces: Vec<Vec<usize>> = mesh
        .cells
        .faces
        .of(0)
        .unwrap()
        .iter()
        .map(<[usize]>::to_vec)
        .collect();
    assert_eq!(faces[0], [0, 1, 2]);
    assert_eq!(faces[1], [0, 2, 3]);
    assert_eq!(faces.len(), 7);
    // The unit cube: valid, of quality 1 (the cube's decomposition).
    let summary = crate::quality::summary_json(&mesh);
    assert_eq!(summary["inverted"], 0);
    assert!(
        (summary["quality"]["min"].as_f64().unwrap() - 1.0).abs() < 1e-12,
        "{summary}"
    );
    // One face missing: the cell is open, named with the file and the side.
    let mut open = files.clone();
    open[1].1 = "6(3(0 3 2) 3(0 2 1) 4(4 5 6 7) 4(0 1 5 4) 4(1 2 6 5) 4(2 3 7 6))".into();
    open[2].1 = "6{0}".into();
    open[4].1 = "1(all { type wall; nFaces 6; startFace 0; })".into();
    write_files(dir.path(), &open);
    let e = read(dir.path()).unwrap_err().to_string();
    assert!(
        e.ends_with("owner:1: invalid mesh: cell 0 (polyhedron) is not closed: its side 0-3 belongs to one face only"),
        "{e}"
    );
    // The same cube with its bottom whole reads.
    let mut files = files;
    files[1].1 = "6(4(0 3 2 1) 4(4 5 6 7) 4(0 1 5 4) 4(1 2 6 5) 4(2 3 7 6) 4(3 0 4 7))".into();
    files[2].1 = "6{0}".into();
    files[4].1 = "1(all { type wall; nFaces 6; startFace 0; })".into();
    write_files(dir.path(), &files);
    assert_eq!(
        read(dir.path()).unwrap().cells.kinds,
        [CellKind::Hexahedron]
    );
    // The same faces as a faceCompactList: the offsets, then the points.
    files[1].1 = "FoamFile { format ascii; class faceCompactList; }\n7(0 4 8 12 16 20 24)\n\
                  24(0 3 2 1 4 5 6 7 0 1 5 4 1 2 6 5 2 3 7 6 3 0 4 7)"
        .into();
    write_files(dir.path(), &files);
    let compact = read(dir.path()).unwrap();
    assert_eq!(compact.cells.kinds, [CellKind::Hexahedron]);
    assert_eq!(orientation(&compact), [1]);
    files[1].1 = files[1].1.replace("7(0 4 8", "7(0 2 8");
    write_files(dir.path(), &files);
    let e = read(dir.path()).unwrap_err().to_string();
    assert!(
        e.contains("faces:2: the face offsets do not start at 0, grow by 3"),
        "{e}"
    );
}

/// A change to a file's text.
type Edit = Box<dyn Fn(&str) -> String>;

#[test]
fn malformed_files_name_the_file_line_and_what_was_expected() {
    let cases: Vec<(&str, Edit, &str)> = vec![
        (
            "points",
            Box::new(|t| {
                t.replace(
                    "format ascii",
                    "format binary; arch \"MSB;label=32;scalar=64\"",
                )
            }),
            "points:5: big-endian (MSB) binary files are not supported",
        ),
        (
            "points",
            Box::new(|t| t.replace("format ascii", "format binary")),
            "the file ends inside the binary list of 12 points",
        ),
        (
            "points",
            Box::new(|t| t.replace("(1 0 0)", "(1 zero 0)")),
            "points:15: expected y (a finite number), found 'zero'",
        ),
        (
            "points",
            Box::new(|t| t.replace("12\n(", "13\n(")),
            "the list holds 12 points, not the 13 announced",
        ),
        (
            "points",
            Box::new(|t| t.replace("12\n(", "1000000000000000000\n(")),
            "the list holds 12 points, not the 1000000000000000000 announced",
        ),
        (
            "faces",
            Box::new(|t| t.replacen("4(4 5 6 7)", "4(4 5 6 99)", 1)),
            "faces:14: point label 99 out of range (expected 0 to 11)",
        ),
        (
            "faces",
            Box::new(|t| t.replace("/* made by a test */", "/* never closed")),
            "faces:1: unclosed /* comment",
        ),
        (
            "owner",
            Box::new(|t| t.replacen("\n0\n", "\n999\n", 1)),
            "cell label 999 out of range",
        ),
        (
            "owner",
            Box::new(|t| t[..t.find("17\n").unwrap()].to_string() + "99999999999{0}\n"),
            "owner:12: 99999999999{…} is more cell labels than the 17 this mesh can have",
        ),
        (
            "boundary",
            Box::new(|t| t.replacen("nFaces", "nFacez", 1)),
            "patch 'floor' has no nFaces",
        ),
        (
            "boundary",
            Box::new(|t| t.replacen("startFace 3", "startFace 0", 1)),
            "patch 'floor' starts at face 0",
        ),
        (
            "neighbour",
            Box::new(|t| t.replace("3(", "2(")),
            "more cell labels than the 2 announced",
        ),
    ];
    for (file, edit, want) in cases {
        let e = error_with(file, edit);
        assert!(e.contains(want), "{file}: {e}\nexpected: {want}");
    }
}

#[test]
fn a_missing_or_compressed_file_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let e = read(dir.path()).unwrap_err().to_string();
    assert!(e.contains("not an OpenFOAM case"), "{e}");
    let files = poly_files(&hex_wedge_pyramid_tet(), &[]);
    write_files(dir.path(), &files);
    let poly = dir.path().join("constant/polyMesh");
    std::fs::rename(poly.join("owner"), poly.join("owner.gz")).unwrap();
    let e = read(dir.path()).unwrap_err().to_string();
    assert!(e.contains("owner: only owner.gz is there"), "{e}");
}

/// The sample's boundary with `floor` and `roof` given `floor` and `roof`
/// as their types and further entries.
fn coupled_case(floor: &str, roof: &str) -> Result<Mesh> {
    let mut files = poly_files(&hex_wedge_pyramid_tet(), &[]);
    let boundary = &mut files.iter_mut().find(|f| f.0 == "boundary").unwrap().1;
    for (name, entries) in [("floor", floor), ("roof", roof)] {
        let at = format!("    {name}\n    {{\n        type wall;");
        *boundary = boundary.replace(&at, &format!("    {name}\n    {{\n        {entries}"));
    }
    let dir = tempfile::tempdir().unwrap();
    write_files(dir.path(), &files);
    read(dir.path())
}

#[test]
fn coupled_patches_are_the_mesh_interfaces() {
    let sliding = coupled_case(
        "type cyclicAMI; neighbourPatch roof; matchTolerance 0.0001;",
        "type cyclicAMI; neighbourPatch floor;",
    )
    .unwrap();
    let sides = [vec!["floor".to_string()], vec!["roof".to_string()]];
    assert_eq!(
        sliding.origin.interfaces,
        [Interface {
            sides: sides.clone(),
            coupling: Coupling::Sliding
        }]
    );
    // A cyclic pair's translation from its centroids, or the file's turned
    // round to take the first patch onto the second.
    let centroid = |g: &str| -> [f64; 3] {
        let nodes = sliding.group(g).unwrap().nodes();
        std::array::from_fn(|d| {
            nodes.iter().map(|&i| sliding.point(i)[d]).sum::<f64>() / nodes.len() as f64
        })
    };
    let (f, r) = (centroid("floor"), centroid("roof"));
    let shift: [f64; 3] = std::array::from_fn(|d| r[d] - f[d]);
    let backwards = format!(
        "type cyclic; neighbourPatch roof; transform translational; separationVector ({} {} {});",
        -shift[0], -shift[1], -shift[2]
    );
    for floor in ["type cyclic; neighbourPatch roof;", &backwards] {
        let periodic = coupled_case(floor, "type cyclic; neighbourPatch floor;").unwrap();
        assert_eq!(
            periodic.origin.interfaces,
            [Interface {
                sides: sides.clone(),
                coupling: Coupling::Periodic(Transform::Translation(shift))
            }]
        );
    }
    // A mapped patch sampling another region's patch is no interface here.
    let mapped = coupled_case(
        "type mappedWall; sampleMode nearestPatchFace; sampleRegion solid; samplePatch elsewhere;",
        "type wall;",
    )
    .unwrap();
    assert_eq!(mapped.origin.interfaces, []);
    let e = coupled_case("type cyclicAMI; neighbourPatch nowhere;", "type wall;")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("boundary:")
            && e.contains("the neighbour patch 'nowhere' is not a patch of this boundary"),
        "{e}"
    );
}
