//! The input mesh is never an output unless the user says so, no output
//! replaces an input or another output, and what an output cannot keep of
//! the input is said.

use std::path::Path;

use verbss::io::outputs::{self, Input, Output, MESH};
use verbss::io::su2::Anchor;
use verbss::io::{foam, Format};
use verbss::mesh::Mesh;

use crate::render::Recorder;
use crate::run::Job;

/// The files of the input mesh `path`: the file, or an OpenFOAM case's
/// polyMesh files and its `system/controlDict`.
pub fn mesh_inputs(path: &Path) -> Vec<Input> {
    if !matches!(Format::from_path(path), Ok(Format::Foam)) {
        return vec![Input {
            what: MESH,
            path: path.to_path_buf(),
        }];
    }
    let dir = foam::polymesh_dir(path);
    let mut files: Vec<Input> = foam::FILES
        .iter()
        .map(|f| Input {
            what: MESH,
            path: dir.join(f),
        })
        .collect();
    files.push(Input {
        what: "the case's controlDict",
        path: foam::case_dir(&dir).join("system").join("controlDict"),
    });
    files
}

/// Before the first solve: fails, naming the option and the file, when a
/// file `job` writes (its outputs in one process, its report, the
/// pictures of `recorder`, and `more`: an MPI run's pieces) is an input,
/// another output, or no regular file. `more` replaces the one-process
/// mesh files when given (an MPI run without the whole mesh).
pub fn check_outputs(job: &Job, recorder: &Recorder, more: Vec<Output>) -> verbss::Result<()> {
    let mut files = if more.is_empty() {
        whole_files(job)
    } else {
        more
    };
    let flag = |option: &str, key: &str| flag(job, option, key);
    if let Some(report) = &job.report {
        files.push(Output::new(flag("--report", "output.report"), report));
    }
    files.extend(recorder.outputs());
    outputs::check(&job.inputs, &files)?;
    refuse_existing_times(job)
}

/// Fails, unless `--overwrite`, when a time directory `job` writes into
/// the input OpenFOAM case already holds a polyMesh (another mesh's faces
/// would stay beside the new points; with `--overwrite` it is replaced
/// whole).
fn refuse_existing_times(job: &Job) -> verbss::Result<()> {
    let steps = job.settings.steps;
    for n in job.written_steps(steps) {
        let Some(time) = job.time_dir(n) else {
            return Ok(());
        };
        let poly = time.join("polyMesh");
        if job.overwrite || std::fs::symlink_metadata(&poly).is_err() {
            continue;
        }
        let name = time.file_name().unwrap_or_default().to_string_lossy();
        return Err(verbss::Error::Output {
            flag: (if n == steps { "-o" } else { "--every" }).into(),
            path: poly,
            message: format!(
                "the time directory {name} already holds a polyMesh (give --overwrite to \
                 replace it whole)"
            ),
        });
    }
    Ok(())
}

/// How a message names a setting of `job`: its case-file `key` when the
/// job came from a case file, else its command-line `option`.
fn flag(job: &Job, option: &str, key: &str) -> String {
    (if job.from_case { key } else { option }).to_string()
}

/// The files of a mesh written whole to `path` (named by `flag`), which may
/// be the input mesh when `overwrite`: the file, or an OpenFOAM case's
/// polyMesh files, each replacing a link at its path.
pub fn mesh_outputs(flag: &str, path: &Path, overwrite: bool) -> Vec<Output> {
    if !matches!(Format::from_path(path), Ok(Format::Foam)) {
        return vec![Output {
            overwrite: Some(overwrite),
            ..Output::new(flag, path)
        }];
    }
    let dir = match path.ends_with("polyMesh") {
        true => path.to_path_buf(),
        false => path.join("constant").join("polyMesh"),
    };
    foam::FILES
        .iter()
        .map(|f| Output {
            replaces_link: true,
            overwrite: Some(overwrite),
            ..Output::new(flag, dir.join(f))
        })
        .collect()
}

/// The files a one-process run of `job` writes: the final mesh (or the
/// OpenFOAM files or time directories it makes), the series and its
/// `.pvd`, and the failed state.
pub fn whole_files(job: &Job) -> Vec<Output> {
    let flag = |option: &str, key: &str| flag(job, option, key);
    let (final_flag, every) = (flag("-o", "output.dir"), flag("--every", "output.every"));
    let steps = job.settings.steps;
    let mut files = Vec::new();
    match job.time_dir(0) {
        Some(_) => files.extend(job.written_steps(steps).into_iter().map(|n| {
            let dir = job.time_dir(n).expect("an OpenFOAM output in the case");
            let flag = if n == steps { &final_flag } else { &every };
            Output {
                replaces_link: true,
                ..Output::new(flag, dir.join("polyMesh").join("points"))
            }
        })),
        None if job.final_mesh => {
            files.extend(mesh_outputs(&final_flag, &job.final_path(), job.overwrite));
        }
        None => {}
    }
    if job.series && job.foam_times.is_none() {
        let written = std::iter::once(0).chain(job.written_steps(steps));
        files.extend(written.map(|n| Output::new(&every, job.dir.join(job.series_file(n)))));
        files.push(Output::new(
            &every,
            job.dir.join(format!("{}.pvd", job.name)),
        ));
    }
    files.push(Output::new("the failed state", job.failed_path()));
    files
}

/// Says on standard error that `output`, not an SU2 file, leaves out the
/// other zones of a multi-zone SU2 input and the sections of the SU2 input
/// that verbss does not use (FFD boxes, periodic data), naming their first
/// three keywords.
pub fn note_lost_su2_blocks(mesh: &Mesh, output: &Path) {
    if mesh.origin.su2_skipped.is_empty() || matches!(Format::from_path(output), Ok(Format::Su2)) {
        return;
    }
    let (zones, sections): (Vec<_>, Vec<_>) = mesh
        .origin
        .su2_skipped
        .iter()
        .partition(|b| matches!(b.after, Anchor::ZonesBefore | Anchor::ZonesAfter));
    if !zones.is_empty() {
        eprintln!(
            "note: {} leaves out the other zones of the multi-zone SU2 input \
             (only an .su2 output keeps them)",
            output.display()
        );
    }
    let keywords = sections.iter().flat_map(|b| {
        b.text.lines().filter_map(|l| {
            Some(format!(
                "{}=",
                l.split('%').next()?.split_once('=')?.0.trim()
            ))
        })
    });
    let mut named: Vec<String> = Vec::new();
    for k in keywords {
        if named.len() == 3 {
            named.push("…".into());
            break;
        }
        if !named.contains(&k) {
            named.push(k);
        }
    }
    if named.is_empty() {
        return;
    }
    eprintln!(
        "note: {} leaves out the input's SU2 sections {} (only an .su2 output keeps them)",
        output.display(),
        named.join(", ")
    );
}
