//! `examples/c/deform.c` compiles against `include/verbss.h` and the shared
//! library cargo built, runs on the repository's meshes, and ends with the
//! coordinates the library computes for the same positions with the same
//! (default, robust) settings, bit for bit; given every setting of `verbss
//! deform` and sliding planes with and without normals, it ends where the
//! `verbss` command ends.

use std::path::{Path, PathBuf};
use std::process::Command;

use verbss::deform::Deformer;
use verbss::io::WriteOptions;
use verbss::motion::{Attachment, Motion, PositionSource};
use verbss::settings::Settings;
use verbss::{CellKind, Cells, Group, Mesh};

const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");

/// The relative tolerance of the runs.
const TOLERANCE: f64 = 1e-5;

/// The folder holding the `libverbss_capi.so` built with this test: the
/// test's own `deps/` folder (cargo copies only plain builds' libraries up to
/// the profile folder).
fn library_dir() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let dir = exe.parent().unwrap().to_path_buf();
    assert!(
        dir.join("libverbss_capi.so").exists(),
        "no libverbss_capi.so in {}",
        dir.display()
    );
    dir
}

/// Compiles the example into `dir` and returns the program's path.
fn compile(dir: &Path) -> PathBuf {
    let lib = library_dir();
    let program = dir.join("deform");
    let out = Command::new("cc")
        .args(["-std=c99", "-O2", "-Wall", "-Wextra", "-Werror"])
        .arg(format!("{ROOT}/examples/c/deform.c"))
        .arg(format!("-I{ROOT}/include"))
        .arg(format!("-L{}", lib.display()))
        .arg("-lverbss_capi")
        .arg(format!("-Wl,-rpath,{}", lib.display()))
        .arg("-o")
        .arg(&program)
        .output()
        .expect("cc runs");
    assert!(
        out.status.success(),
        "cc failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    program
}

/// A run of the compiled example, with the library of this build first on
/// the loader's path (cargo's own `LD_LIBRARY_PATH` also names the profile
/// folder, where a plain build may have left an older library).
fn example(program: &Path) -> Command {
    let mut command = Command::new(program);
    command.env("LD_LIBRARY_PATH", library_dir());
    command
}

/// What the library computes when MARKER's nodes are put at their input
/// positions plus `n/steps × shift` at step `n` (as the C example does), with
/// the C API's default settings (one worker thread per core) and TOLERANCE.
fn library_result(mesh: &str, marker: &str, steps: usize, shift: &[f64]) -> Vec<f64> {
    let mesh = verbss_mesh(mesh);
    let mut settings = Settings::robust(steps);
    settings.solve.tolerance = TOLERANCE;
    settings.solve.threads = 0;
    let marker_nodes = mesh.group(marker).unwrap().nodes();
    let at = |f: f64| {
        let table = marker_nodes
            .iter()
            .map(|&i| {
                let x = mesh.point(i);
                (i, (0..mesh.dim).map(|d| x[d] + f * shift[d]).collect())
            })
            .collect();
        Motion::Positions(PositionSource::Given(table))
    };
    let attachment = Attachment {
        groups: vec![marker.into()],
        motion: at(0.0),
    };
    let mut deformer = Deformer::new(&mesh, &[attachment], settings).unwrap();
    for n in 1..=steps {
        deformer.set_motion(0, at(n as f64 / steps as f64)).unwrap();
        deformer.step(n).unwrap();
    }
    deformer.current().coords.clone()
}

#[test]
fn c_example_matches_the_library_on_every_mesh() {
    let dir = tempfile::tempdir().unwrap();
    let program = compile(dir.path());
    let cases: [(&str, &str, &[f64]); 4] = [
        ("mesh_NACA0012_inv.su2", "airfoil", &[0.05, 0.1]),
        ("mesh_RAE2822_turb_ffd.su2", "AIRFOIL", &[0.02, -0.03]),
        ("mesh_brick_tets_ffd.su2", "x_p", &[0.2, 0.0, 0.05]),
        ("mesh_brick_hex_ffd.su2", "x_p", &[0.2, 0.0, 0.05]),
    ];
    for (mesh, marker, shift) in cases {
        let steps = 2;
        let out_path = dir.path().join("points.txt");
        let out = example(&program)
            .arg(format!("{ROOT}/assets/meshes/su2/{mesh}"))
            .arg(marker)
            .arg(steps.to_string())
            .arg(&out_path)
            .args(shift.iter().map(|x| x.to_string()))
            .arg(format!("tolerance={TOLERANCE}"))
            .output()
            .unwrap();
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success(),
            "{mesh}: {stdout}{}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert_eq!(stdout.lines().count(), steps, "{mesh}: {stdout}");
        assert!(stdout.starts_with("step 1: "), "{mesh}: {stdout}");
        let c_points = read_points(&out_path);
        let expected = library_result(mesh, marker, steps, shift);
        assert_eq!(c_points.len(), expected.len(), "{mesh}");
        let differ = c_points
            .iter()
            .zip(&expected)
            .filter(|(a, b)| a.to_bits() != b.to_bits())
            .count();
        assert_eq!(differ, 0, "{mesh}: coordinates that differ");
        assert_ne!(c_points, verbss_mesh(mesh).coords, "{mesh}: nothing moved");
    }
}

fn verbss_mesh(mesh: &str) -> verbss::Mesh {
    verbss::io::read(Path::new(&format!("{ROOT}/assets/meshes/su2/{mesh}"))).unwrap()
}

#[test]
fn c_example_reports_the_api_error_and_its_status() {
    let dir = tempfile::tempdir().unwrap();
    let program = compile(dir.path());
    // A translation that pushes the airfoil through the farfield inverts elements.
    let out = example(&program)
        .arg(format!("{ROOT}/assets/meshes/su2/mesh_NACA0012_inv.su2"))
        .args(["airfoil", "1"])
        .arg(dir.path().join("points.txt"))
        .args(["1000", "0"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(3));
    let mesh = verbss_mesh("mesh_NACA0012_inv.su2");
    let table = mesh
        .group("airfoil")
        .unwrap()
        .nodes()
        .into_iter()
        .map(|i| (i, vec![mesh.point(i)[0] + 1000.0, mesh.point(i)[1]]))
        .collect();
    let attachment = Attachment {
        groups: vec!["airfoil".into()],
        motion: Motion::Positions(PositionSource::Given(table)),
    };
    let message = Deformer::new(&mesh, &[attachment], Settings::robust(1))
        .unwrap()
        .step(1)
        .unwrap_err()
        .to_string();
    assert!(message.starts_with("step 1: element "), "{message}");
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        format!("verbss_deformer_step failed (status 3): {message}\n")
    );
}

/// The numbers of the C example's output, node after node.
fn read_points(path: &Path) -> Vec<f64> {
    std::fs::read_to_string(path)
        .unwrap()
        .split_whitespace()
        .map(|x| x.parse().unwrap())
        .collect()
}

/// The `verbss` command of this tree, built by cargo for this test's
/// profile into its target folder (nothing to do when it is up to date).
fn verbss_command() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let profile_dir = exe.parent().unwrap().parent().unwrap();
    let profile = match profile_dir.file_name().unwrap().to_str().unwrap() {
        "debug" => "dev",
        other => other,
    };
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let out = Command::new(cargo)
        .args(["build", "--quiet", "-p", "verbss-cli", "--bin", "verbss"])
        .args(["--profile", profile, "--manifest-path"])
        .arg(format!("{ROOT}/Cargo.toml"))
        .arg("--target-dir")
        .arg(profile_dir.parent().unwrap())
        .output()
        .expect("cargo runs");
    assert!(
        out.status.success(),
        "cargo build -p verbss-cli failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    profile_dir.join("verbss")
}

/// Writes the box [0, 2] × [0, 1] × [0, 1] of 8 × 4 × 4 hexahedra, its six
/// faces the groups `x_m`, `x_p`, `y_m`, `y_p`, `z_m`, `z_p`, to `path`.
fn write_box(path: &Path) {
    let n = [8, 4, 4];
    let id = |p: [usize; 3]| p[0] + (n[0] + 1) * (p[1] + (n[1] + 1) * p[2]);
    let mut coords = Vec::new();
    for k in 0..=n[2] {
        for j in 0..=n[1] {
            for i in 0..=n[0] {
                coords.extend([2.0 * i as f64 / n[0] as f64, j as f64 / n[1] as f64]);
                coords.push(k as f64 / n[2] as f64);
            }
        }
    }
    let mut cells = Cells::new();
    for k in 0..n[2] {
        for j in 0..n[1] {
            for i in 0..n[0] {
                let c = |di, dj, dk| id([i + di, j + dj, k + dk]);
                let bottom = [c(0, 0, 0), c(1, 0, 0), c(1, 1, 0), c(0, 1, 0)];
                let top = [c(0, 0, 1), c(1, 0, 1), c(1, 1, 1), c(0, 1, 1)];
                cells.push(CellKind::Hexahedron, &[bottom, top].concat());
            }
        }
    }
    // The face at index `at` of `axis`: quads over the two other axes.
    let face = |name: &str, axis: usize, at: usize| {
        let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
        let mut facets = Cells::new();
        for v in 0..n[b] {
            for u in 0..n[a] {
                let node = |du: usize, dv: usize| {
                    let mut p = [0; 3];
                    (p[axis], p[a], p[b]) = (at, u + du, v + dv);
                    id(p)
                };
                facets.push(
                    CellKind::Quad,
                    &[node(0, 0), node(1, 0), node(1, 1), node(0, 1)],
                );
            }
        }
        Group {
            name: name.into(),
            tag: None,
            facets,
        }
    };
    let groups = (0..3)
        .flat_map(|axis| {
            let x = ["x", "y", "z"][axis];
            [
                face(&format!("{x}_m"), axis, 0),
                face(&format!("{x}_p"), axis, n[axis]),
            ]
        })
        .collect();
    let mesh = Mesh::new(3, coords, cells, groups).unwrap();
    verbss::io::write(path, &mesh, &WriteOptions::default()).unwrap();
}

/// Runs the C example on `mesh`, moving `x_p` by (0.3, 0, 0.1) in 3 steps
/// with `settings` (NAME=VALUE), and returns the final coordinates.
fn c_run(program: &Path, mesh: &Path, settings: &[String]) -> Vec<f64> {
    let out_path = mesh.with_file_name("c_points.txt");
    let out = example(program)
        .arg(mesh)
        .args(["x_p", "3"])
        .arg(&out_path)
        .args(["0.3", "0", "0.1"])
        .args(settings)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    read_points(&out_path)
}

/// Runs the `verbss` command with `args` and returns the coordinates of the
/// mesh it wrote to `output`.
fn command_run(verbss: &Path, args: &[String], output: &Path) -> Vec<f64> {
    let out = Command::new(verbss).args(args).output().unwrap();
    assert!(
        out.status.success(),
        "verbss {}: {}",
        args.join(" "),
        String::from_utf8_lossy(&out.stderr)
    );
    verbss::io::read(output).unwrap().coords
}

#[test]
fn c_example_with_every_setting_ends_where_the_command_ends() {
    let dir = tempfile::tempdir().unwrap();
    let program = compile(dir.path());
    let verbss = verbss_command();
    let mesh = dir.path().join("box.su2");
    write_box(&mesh);
    let start = verbss::io::read(&mesh).unwrap().coords;
    let words = |list: &[&str]| list.iter().map(|s| s.to_string()).collect::<Vec<_>>();

    // Sliding in their own planes with the near-wall treatments, the
    // multigrid and the fixed reference: `verbss deform`.
    let settings = [
        ("method", "robust"),
        ("rigid_layer", "0.1"),
        ("stiffening", "2"),
        ("substeps", "3"),
        ("blend", "off"),
        ("predictor", "linear"),
        ("reference", "fixed"),
        ("accel", "amg"),
        ("omega", "1.5"),
        ("tolerance", "1e-7"),
        ("max_iterations", "500"),
        ("threads", "2"),
    ];
    let mut c_args: Vec<String> = settings.iter().map(|(n, v)| format!("{n}={v}")).collect();
    // The mesh's other groups, which the command knows from the file.
    c_args.extend(words(&[
        "slide=y_m",
        "slide=y_p",
        "fixed=x_m",
        "fixed=z_m",
        "fixed=z_p",
    ]));
    let c_points = c_run(&program, &mesh, &c_args);
    let output = dir.path().join("deformed.su2");
    let mut args = words(&[
        "deform",
        mesh.to_str().unwrap(),
        "-o",
        output.to_str().unwrap(),
    ]);
    // The C example gives the moving nodes' positions: the command is given
    // the same final positions (a body moved by given positions is not
    // stiffened, docs/method.md, "Amplification").
    let positions = dir.path().join("x_p.dat");
    let boxed = verbss::io::read(&mesh).unwrap();
    let lines: String = boxed
        .group("x_p")
        .unwrap()
        .nodes()
        .into_iter()
        .map(|i| {
            let p = boxed.point(i);
            format!("{i} {} {} {}\n", p[0] + 0.3, p[1], p[2] + 0.1)
        })
        .collect();
    std::fs::write(&positions, lines).unwrap();
    args.extend(words(&[
        "--moving",
        "x_p",
        "--positions",
        positions.to_str().unwrap(),
        "--steps",
        "3",
    ]));
    args.extend(words(&["--slide", "y_m,y_p", "--quiet"]));
    for (name, value) in settings {
        args.extend([format!("--{}", name.replace('_', "-")), value.to_string()]);
    }
    let expected = command_run(&verbss, &args, &output);
    assert_eq!(c_points.len(), expected.len());
    // The C example's positions X + (n/3) u and the command's
    // (1 − n/3) X + (n/3)(X + u): equal up to rounding.
    let differ = c_points
        .iter()
        .zip(&expected)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(differ < 1e-12, "largest difference {differ}");
    assert_ne!(c_points, start, "nothing moved");

    // Sliding in the planes of given normals (0.29° off the y_m plane, within
    // the half degree allowed), the paper's method with an
    // absolute tolerance: a case file's `kind = "slide"` with `normal`,
    // through `verbss run`.
    let case = dir.path().join("normals.toml");
    std::fs::write(
        &case,
        format!(
            "mesh = {:?}\nsteps = 3\n\n[solver]\nmethod = \"verbss\"\ntolerance = 1e-9\n\
             absolute_tolerance = true\n\n[[motion]]\nkind = \"translation\"\n\
             groups = [\"x_p\"]\ndisplacement = [0.3, 0.0, 0.1]\n\n[[motion]]\n\
             kind = \"slide\"\ngroups = [\"y_m\"]\nnormal = [0.0, 1.0, 0.005]\n\n\
             [[motion]]\nkind = \"slide\"\ngroups = [\"z_m\"]\nnormal = [0.0, 0.0, 2.0]\n\n\
             [output]\nseries = false\nreport = false\n",
            mesh.to_str().unwrap()
        ),
    )
    .unwrap();
    let c_args = words(&[
        "method=verbss",
        "tolerance=1e-9",
        "absolute_tolerance=on",
        "slide=y_m:0,1,0.005",
        "slide=z_m:0,0,2",
        "fixed=x_m",
        "fixed=y_p",
        "fixed=z_p",
    ]);
    let c_points = c_run(&program, &mesh, &c_args);
    let out_dir = dir.path().join("run");
    let args = words(&[
        "run",
        case.to_str().unwrap(),
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    let expected = command_run(&verbss, &args, &out_dir.join("box.su2"));
    assert_eq!(c_points, expected);
    // The nodes of y_m (y = 0) that x_p (x = 2) does not move slid in the
    // plane of normal (0, 1, 0.005).
    let y_m = (0..start.len() / 3).filter(|&i| start[3 * i + 1] == 0.0 && start[3 * i] != 2.0);
    let mut slid = 0;
    for i in y_m {
        let u: Vec<f64> = (0..3)
            .map(|d| c_points[3 * i + d] - start[3 * i + d])
            .collect();
        assert!((u[1] + 0.005 * u[2]).abs() < 1e-12, "node {i}: {u:?}");
        slid += usize::from(u[1] != 0.0);
    }
    assert!(slid > 0);
}
