//! What the OpenFOAM tests share: running OpenFOAM's utilities, the
//! `system` files they read, copies of OpenFOAM's own tutorials and what
//! `checkMesh` reports.

use std::path::Path;
use std::process::Command;

use super::stderr;
use verbss_testkit::{needs, program};

/// The OpenFOAM installation the Debian package `openfoam` makes.
pub const FOAM_DIR: &str = "/usr/share/openfoam";

/// Whether `blockMesh` and `checkMesh` run.
pub fn have_openfoam() -> bool {
    needs(
        "OpenFOAM's blockMesh and checkMesh (Debian openfoam)",
        program(
            "sh",
            &[
                "-c",
                &format!(
                    "export WM_PROJECT_DIR=${{WM_PROJECT_DIR:-{FOAM_DIR}}}; \
                     blockMesh -help >/dev/null && checkMesh -help >/dev/null"
                ),
            ],
        ),
    )
}

/// Runs an OpenFOAM utility on `case` with `args`, in `case` (as a
/// tutorial's Allrun runs it: some dictionaries name paths relative to
/// it); its standard output.
pub fn foam(utility: &str, case: &Path, args: &[&str]) -> String {
    let out = foam_output(utility, case, args);
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "{utility} failed:\n{text}{}",
        stderr(&out)
    );
    text
}

/// Runs an OpenFOAM utility as [`foam`] does; all it did.
pub fn foam_output(utility: &str, case: &Path, args: &[&str]) -> std::process::Output {
    Command::new(utility)
        .arg("-case")
        .arg(case)
        .args(args)
        .current_dir(case)
        .env(
            "WM_PROJECT_DIR",
            std::env::var("WM_PROJECT_DIR").unwrap_or(FOAM_DIR.into()),
        )
        .output()
        .expect("run an OpenFOAM utility")
}

/// The `system` files `blockMesh` and `checkMesh` read (OpenFOAM writes
/// ASCII files).
pub fn write_system(case: &Path) {
    write_system_as(case, "ascii");
}

/// The `system` files, with `writeFormat` `format`.
pub fn write_system_as(case: &Path, format: &str) {
    let head = |object: &str| {
        format!("FoamFile {{ version 2.0; format ascii; class dictionary; object {object}; }}\n")
    };
    let system = case.join("system");
    std::fs::create_dir_all(&system).unwrap();
    let files = [
        (
            "controlDict",
            "application none; startFrom latestTime; startTime 0; stopAt endTime; \
             endTime 1; deltaT 1; writeControl timeStep; writeInterval 1; writeFormat FORMAT;\n",
        ),
        (
            "fvSchemes",
            "ddtSchemes {} gradSchemes {} divSchemes {} laplacianSchemes {} \
             interpolationSchemes {} snGradSchemes {}\n",
        ),
        ("fvSolution", ""),
    ];
    for (name, body) in files {
        let body = body.replace("FORMAT", format);
        std::fs::write(system.join(name), head(name) + &body).unwrap();
    }
}

/// The failed checks of checkMesh on `case` (with `args`), as its `***` lines.
pub fn check_mesh_failures(case: &Path, args: &[&str]) -> Vec<String> {
    let log = foam("checkMesh", case, args);
    failures(&log).into_iter().map(str::to_string).collect()
}

/// Whether `checkMesh` passes the mesh of `case` at its latest time.
pub fn assert_mesh_ok(case: &Path) {
    let log = foam("checkMesh", case, &["-latestTime"]);
    assert!(log.contains("Mesh OK."), "checkMesh:\n{log}");
}

/// Whether OpenFOAM's `utilities` run (each with `-help`), for a test that
/// needs them beyond blockMesh and checkMesh.
pub fn have_utilities(utilities: &[&str]) -> bool {
    let probe = utilities
        .iter()
        .map(|u| format!("{u} -help >/dev/null"))
        .collect::<Vec<_>>()
        .join(" && ");
    have_openfoam()
        && needs(
            &format!("OpenFOAM's {} (Debian openfoam)", utilities.join(", ")),
            program(
                "sh",
                &[
                    "-c",
                    &format!("export WM_PROJECT_DIR=${{WM_PROJECT_DIR:-{FOAM_DIR}}}; {probe}"),
                ],
            ),
        )
}

/// The directory of OpenFOAM's tutorials (Debian `openfoam-examples`).
pub const TUTORIALS: &str = "/usr/share/doc/openfoam-examples/examples";

/// Whether the tutorial `name` (a path under [`TUTORIALS`]) is installed.
pub fn have_tutorial(name: &str) -> bool {
    let dir = Path::new(TUTORIALS).join(name);
    needs(
        &format!("OpenFOAM's tutorial {name} (Debian openfoam-examples)"),
        if dir.is_dir() {
            Ok(())
        } else {
            Err(format!("{} is missing", dir.display()))
        },
    )
}

/// A copy of tutorial `name` in `to`, its gzipped files unpacked (Debian
/// compresses the larger ones).
pub fn copy_tutorial(name: &str, to: &Path) {
    let from = Path::new(TUTORIALS).join(name);
    let status = Command::new("cp")
        .arg("-r")
        .arg(&from)
        .arg(to)
        .status()
        .expect("run cp");
    assert!(status.success(), "cp -r {}", from.display());
    let status = Command::new("find")
        .arg(to)
        .args(["-name", "*.gz", "-exec", "gunzip", "{}", ";"])
        .status()
        .expect("run find");
    assert!(status.success(), "gunzip in {}", to.display());
}

/// The lines of a checkMesh log that report a failed check (`***`).
pub fn failures(log: &str) -> Vec<&str> {
    log.lines().filter(|l| l.contains("***")).collect()
}

/// The number after `key` on the first line of `log` that holds it.
pub fn count_after(log: &str, key: &str) -> Option<usize> {
    let at = log.find(key)? + key.len();
    log[at..]
        .split(|c: char| !c.is_ascii_digit())
        .find(|t| !t.is_empty())?
        .parse()
        .ok()
}

/// A square body (patch `wing`, side 1) in a square box (patch `farfield`,
/// side 3), 8 blocks of `n × n` cells and `layers` cells in z (0 to 0.2):
/// with `empty` patches `back` (z = 0) and `front` when `layers` is 1 (a 2D
/// case), else `wall` ones.
pub fn block_case(case: &Path, n: usize, layers: usize) {
    ring_case(case, n, layers, ["farfield"; 4], &[("farfield", "patch")]);
}

/// [`block_case`] with the box's sides (bottom, right, top, left) in the
/// patches `outer` names, each patch declared by `patches` as its name and
/// what follows `type` in its entry (`"cyclic; neighbourPatch hi"`).
pub fn ring_case(case: &Path, n: usize, layers: usize, outer: [&str; 4], patches: &[(&str, &str)]) {
    write_system(case);
    let x = [-1.5, -0.5, 0.5, 1.5];
    let v = |i: usize, j: usize, k: usize| k * 16 + j * 4 + i;
    let mut vertices = String::new();
    for k in 0..2 {
        for j in 0..4 {
            for i in 0..4 {
                vertices += &format!("({} {} {}) ", x[i], x[j], 0.2 * k as f64);
            }
        }
    }
    let quad = |a: usize, b: usize, c: usize, d: usize| format!("({a} {b} {c} {d}) ");
    let (mut blocks, mut wing, mut back, mut front) =
        (String::new(), String::new(), String::new(), String::new());
    for j in 0..3 {
        for i in 0..3 {
            if (i, j) == (1, 1) {
                continue;
            }
            let (a, b, c, d) = (
                v(i, j, 0),
                v(i + 1, j, 0),
                v(i + 1, j + 1, 0),
                v(i, j + 1, 0),
            );
            blocks += &format!(
                "hex ({a} {b} {c} {d} {} {} {} {}) ({n} {n} {layers}) simpleGrading (1 1 1)\n",
                a + 16,
                b + 16,
                c + 16,
                d + 16
            );
            back += &quad(a, d, c, b);
            front += &quad(a + 16, b + 16, c + 16, d + 16);
        }
    }
    let mut faces = vec![String::new(); patches.len()];
    for t in 0..3 {
        let edges = [
            (v(t, 0, 0), v(t + 1, 0, 0)),
            (v(3, t, 0), v(3, t + 1, 0)),
            (v(t, 3, 0), v(t + 1, 3, 0)),
            (v(0, t, 0), v(0, t + 1, 0)),
        ];
        for (side, (p, q)) in edges.into_iter().enumerate() {
            let k = patches
                .iter()
                .position(|(name, _)| *name == outer[side])
                .expect("each side's patch is declared");
            faces[k] += &quad(p, q, q + 16, p + 16);
        }
    }
    for (p, q) in [
        ((1, 1), (2, 1)),
        ((2, 1), (2, 2)),
        ((2, 2), (1, 2)),
        ((1, 2), (1, 1)),
    ] {
        let (p, q) = (v(p.0, p.1, 0), v(q.0, q.1, 0));
        wing += &quad(p, q, q + 16, p + 16);
    }
    let outer: String = patches
        .iter()
        .zip(&faces)
        .map(|((name, kind), faces)| format!("{name} {{ type {kind}; faces ( {faces}); }}\n"))
        .collect();
    let side_type = if layers == 1 { "empty" } else { "wall" };
    let dict = format!(
        "FoamFile {{ version 2.0; format ascii; class dictionary; object blockMeshDict; }}\n\
         convertToMeters 1;\nvertices ( {vertices});\nblocks (\n{blocks});\nboundary (\n\
         wing {{ type wall; faces ( {wing}); }}\n\
         {outer}\
         back {{ type {side_type}; faces ( {back}); }}\n\
         front {{ type {side_type}; faces ( {front}); }}\n);\n"
    );
    std::fs::write(case.join("system/blockMeshDict"), dict).unwrap();
    foam("blockMesh", case, &[]);
}

/// Makes `case` start from its time directory `time` (where verbss wrote a
/// moved mesh) and run to `end`: the fields of `0` copied there,
/// `startFrom latestTime` and `endTime` set by foamDictionary.
pub fn start_from(case: &Path, time: &str, end: &str) {
    let start = case.join(time);
    for field in std::fs::read_dir(case.join("0")).unwrap() {
        let field = field.unwrap().path();
        std::fs::copy(&field, start.join(field.file_name().unwrap())).unwrap();
    }
    let control = case.join("system/controlDict");
    let control = control.to_str().unwrap();
    foam(
        "foamDictionary",
        case,
        &["-entry", "startFrom", "-set", "latestTime", control],
    );
    foam(
        "foamDictionary",
        case,
        &["-entry", "endTime", "-set", end, control],
    );
}
