//! What the hostile-file tests share: fixture builders and a run of the
//! binary that reports its exit code, its messages and its peak memory.

// Each test binary compiles this module and uses a part of it.
#![allow(dead_code)]

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use base64::Engine;

/// Writes `text` as `name` in `dir`.
pub fn file(dir: &Path, name: &str, text: impl AsRef<[u8]>) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).expect("write the fixture");
    path
}

/// A unit square of two triangles in VTU, zlib-compressed binary arrays
/// allowed; `point_data`, `cell_data` and `field_data` go in their sections.
pub fn vtu(point_data: &str, cell_data: &str, field_data: &str) -> String {
    format!(
        r#"<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt32" compressor="vtkZLibDataCompressor">
<UnstructuredGrid>
<FieldData>{field_data}</FieldData>
<Piece NumberOfPoints="4" NumberOfCells="2">
<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">0 0 0 1 0 0 1 1 0 0 1 0</DataArray></Points>
<Cells>
<DataArray type="Int32" Name="connectivity" format="ascii">0 1 2 0 2 3</DataArray>
<DataArray type="Int32" Name="offsets" format="ascii">3 6</DataArray>
<DataArray type="UInt8" Name="types" format="ascii">5 5</DataArray>
</Cells>
<PointData>{point_data}</PointData>
<CellData>{cell_data}</CellData>
</Piece>
</UnstructuredGrid>
</VTKFile>
"#
    )
}

/// The points array of [`vtu`], to be replaced.
pub const VTU_POINTS: &str = r#"<DataArray type="Float64" NumberOfComponents="3" format="ascii">0 0 0 1 0 0 1 1 0 0 1 0</DataArray>"#;

/// A base64 zlib block: header words `words` (UInt32), then `data`.
pub fn block(words: &[u32], data: &[u8]) -> String {
    let mut bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
    bytes.extend(data);
    base64::engine::general_purpose::STANDARD.encode(bytes)
}

/// A binary Float64 array called `name` holding `block`.
pub fn binary(name: &str, components: &str, block: &str) -> String {
    format!(
        r#"<DataArray type="Float64" Name="{name}" NumberOfComponents="{components}" format="binary">{block}</DataArray>"#
    )
}

/// The zlib stream of `n` zero bytes.
pub fn zeros_zlib(n: usize) -> Vec<u8> {
    use std::io::Write;
    let mut z = Vec::new();
    let mut e = flate2::write::ZlibEncoder::new(&mut z, flate2::Compression::best());
    e.write_all(&vec![0u8; n]).unwrap();
    e.finish().unwrap();
    z
}

/// An MSH 4.1 unit square: its lines, `lines` of them, on a curve with
/// physical tags 1..=`tags`.
pub fn msh_with_tags(lines: usize, tags: usize) -> String {
    let tag_list: Vec<String> = (1..=tags).map(|t| t.to_string()).collect();
    let mut s = format!(
        "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n0 1 1 0\n1 0 0 0 1 0 0 {tags} {} 0\n\
         1 0 0 0 1 1 0 0 0\n$EndEntities\n$Nodes\n1 4 1 4\n2 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n\
         1 1 0\n0 1 0\n$EndNodes\n$Elements\n2 {} 1 {}\n1 1 1 {lines}\n",
        tag_list.join(" "),
        lines + 2,
        lines + 2
    );
    for e in 1..=lines {
        s += &format!("{e} 1 2\n");
    }
    s += &format!(
        "2 1 2 2\n{} 1 2 3\n{} 1 3 4\n$EndElements\n",
        lines + 1,
        lines + 2
    );
    s
}

/// The unit square in SU2 with `markers` markers of one line each.
pub fn su2_with_markers(markers: usize) -> String {
    let mut s = format!(
        "NDIME= 2\nNELEM= 2\n5 0 1 2\n5 0 2 3\nNPOIN= 4\n0 0\n1 0\n1 1\n0 1\nNMARK= {markers}\n"
    );
    for k in 0..markers {
        s += &format!("MARKER_TAG= m{k}\nMARKER_ELEMS= 1\n3 0 1\n");
    }
    s
}

/// How a run of the binary ended.
pub struct Run {
    /// The exit code (`None`: killed by a signal).
    pub code: Option<i32>,
    /// What it printed on standard error.
    pub stderr: String,
    /// Its peak resident memory in KiB (`getrusage` of this child alone).
    pub peak_kib: i64,
}

/// Runs `verbss ARGS` in a child killed after 30 s (a hang fails the test
/// instead of stalling the suite).
#[expect(
    clippy::zombie_processes,
    reason = "the child is reaped by wait4, which also gives its resource usage"
)]
pub fn run(args: &[&str]) -> Run {
    let mut child = Command::new(env!("CARGO_BIN_EXE_verbss"))
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run verbss");
    let mut err = child.stderr.take().expect("piped stderr");
    let reader = std::thread::spawn(move || {
        let mut text = String::new();
        err.read_to_string(&mut text).expect("read stderr");
        text
    });
    let pid = child.id() as libc::pid_t;
    let deadline = Instant::now() + Duration::from_secs(30);
    let (status, usage) = loop {
        let mut status = 0;
        // SAFETY: wait4 only writes the status and the struct it is given.
        let (done, usage) = unsafe {
            let mut usage: libc::rusage = std::mem::zeroed();
            (
                libc::wait4(pid, &mut status, libc::WNOHANG, &mut usage),
                usage,
            )
        };
        assert!(done >= 0, "wait4 failed");
        if done == pid {
            break (status, usage);
        }
        if Instant::now() > deadline {
            child.kill().expect("kill");
            panic!("verbss {args:?} still running after 30 s");
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    Run {
        code: libc::WIFEXITED(status).then(|| libc::WEXITSTATUS(status)),
        stderr: reader.join().expect("stderr reader"),
        peak_kib: usage.ru_maxrss,
    }
}

/// `verbss quality PATH` (see [`run`]).
pub fn quality(path: &Path) -> Run {
    run(&["quality", path.to_str().unwrap()])
}

/// `verbss quality` on `path` fails with exit 2 and a message naming the
/// file and holding `message`.
pub fn refused(path: &Path, message: &str) {
    let r = quality(path);
    assert_eq!(r.code, Some(2), "{}", r.stderr);
    assert!(
        r.stderr.contains(message),
        "expected {message:?} in: {}",
        r.stderr
    );
    assert!(r.stderr.contains(&*path.to_string_lossy()), "{}", r.stderr);
}

/// `verbss quality` on `path` reads it (exit 0).
pub fn read(path: &Path) {
    let r = quality(path);
    assert_eq!(r.code, Some(0), "{}: {}", path.display(), r.stderr);
}
