//! Finds MPI and METIS and, when both are here, compiles `src/shim.c`
//! against them and sets `cfg(with_mpi)`; otherwise the crate builds without
//! its MPI parts and says so once (`cargo::warning`).
//!
//! MPI: the first of the pkg-config packages `mpi-c`, `ompi-c`, `mpich`,
//! else the flags of the compiler wrapper `$MPICC` (default `mpicc`,
//! `-showme` of Open MPI or `-show` of MPICH). METIS: `$METIS_DIR/include`
//! and `$METIS_DIR/lib` when set, else pkg-config's `metis`, else the
//! compiler's default paths. Both are confirmed by compiling and linking a
//! probe program. The reason for a build without them is passed on as
//! `VERBSS_MPI_MISSING` (empty when they were found).

use std::env;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Include folders, library folders and libraries.
#[derive(Default)]
struct Flags {
    include: Vec<PathBuf>,
    search: Vec<PathBuf>,
    libs: Vec<String>,
}

impl Flags {
    /// Picks `-I`, `-L` and `-l` out of a command line.
    fn parse(line: &str) -> Flags {
        let mut flags = Flags::default();
        for word in line.split_whitespace() {
            if let Some(dir) = word.strip_prefix("-I") {
                flags.include.push(dir.into());
            } else if let Some(dir) = word.strip_prefix("-L") {
                flags.search.push(dir.into());
            } else if let Some(lib) = word.strip_prefix("-l") {
                flags.libs.push(lib.into());
            }
        }
        flags
    }

    /// Adds `other`'s flags after these.
    fn extend(&mut self, other: Flags) {
        self.include.extend(other.include);
        self.search.extend(other.search);
        self.libs.extend(other.libs);
    }
}

/// The standard output of `program args…` when it runs and succeeds.
fn output(program: &str, args: &[&str]) -> Option<String> {
    let out = Command::new(program).args(args).output().ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).into_owned())
}

/// The flags pkg-config gives for `package`, if it knows it.
fn pkg_config(package: &str) -> Option<Flags> {
    let program = env::var("PKG_CONFIG").unwrap_or_else(|_| "pkg-config".into());
    output(&program, &["--cflags", "--libs", package]).map(|line| Flags::parse(&line))
}

/// MPI's flags, or why there are none.
fn mpi() -> Result<Flags, String> {
    for package in ["mpi-c", "ompi-c", "mpich"] {
        if let Some(flags) = pkg_config(package) {
            return Ok(flags);
        }
    }
    let mpicc = env::var("MPICC").unwrap_or_else(|_| "mpicc".into());
    output(&mpicc, &["-showme"])
        .or_else(|| output(&mpicc, &["-show"]))
        .map(|line| Flags::parse(&line))
        .ok_or_else(|| {
            format!(
                "no MPI: pkg-config knows none of mpi-c, ompi-c, mpich and `{mpicc}` does not run"
            )
        })
}

/// METIS's flags (the compiler's default paths when nothing says otherwise).
fn metis() -> Flags {
    if let Some(dir) = env::var_os("METIS_DIR") {
        let dir = PathBuf::from(dir);
        return Flags {
            include: vec![dir.join("include")],
            search: vec![dir.join("lib")],
            libs: vec!["metis".into()],
        };
    }
    pkg_config("metis").unwrap_or_else(|| Flags {
        libs: vec!["metis".into()],
        ..Flags::default()
    })
}

/// Compiles and links a program calling both libraries; on failure, the
/// first error of the compiler or the linker.
fn probe(flags: &Flags, out: &Path) -> Result<(), String> {
    let source = out.join("probe.c");
    std::fs::write(
        &source,
        "#include <metis.h>\n#include <mpi.h>\n\
         int main(void) { idx_t o[METIS_NOPTIONS]; METIS_SetDefaultOptions(o); return MPI_Init(0, 0); }\n",
    )
    .map_err(|e| format!("cannot write {}: {e}", source.display()))?;
    let compiler = cc::Build::new()
        .try_get_compiler()
        .map_err(|e| format!("no C compiler: {e}"))?;
    let mut command = compiler.to_command();
    command.arg(&source).arg("-o").arg(out.join("probe"));
    command.args(flags.include.iter().map(|d| format!("-I{}", d.display())));
    command.args(flags.search.iter().map(|d| format!("-L{}", d.display())));
    command.args(flags.libs.iter().map(|l| format!("-l{l}")));
    let result = command
        .output()
        .map_err(|e| format!("cannot run the C compiler: {e}"))?;
    if result.status.success() {
        return Ok(());
    }
    let stderr = String::from_utf8_lossy(&result.stderr);
    let first = stderr
        .lines()
        .find(|l| {
            ["error:", "cannot find", "undefined reference"]
                .iter()
                .any(|k| l.contains(k))
        })
        .unwrap_or("the probe program does not link");
    // A compiler's error without the probe's path: `fatal error: metis.h: …`.
    let at = first
        .find("fatal error:")
        .or_else(|| first.find("error:"))
        .unwrap_or(0);
    Err(first[at..].trim().to_string())
}

fn main() {
    println!("cargo::rustc-check-cfg=cfg(with_mpi)");
    println!("cargo::rerun-if-changed=build.rs");
    println!("cargo::rerun-if-changed=src/shim.c");
    for var in [
        "PATH",
        "MPICC",
        "METIS_DIR",
        "PKG_CONFIG",
        "PKG_CONFIG_PATH",
        "PKG_CONFIG_LIBDIR",
    ] {
        println!("cargo::rerun-if-env-changed={var}");
    }
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    let found = mpi().and_then(|mut flags| {
        flags.extend(metis());
        probe(&flags, &out).map(|()| flags)
    });
    match found {
        Ok(flags) => {
            cc::Build::new()
                .file("src/shim.c")
                .includes(&flags.include)
                .warnings(true)
                .extra_warnings(true)
                .compile("verbss_mpi_shim");
            for dir in &flags.search {
                println!("cargo::rustc-link-search=native={}", dir.display());
            }
            for lib in &flags.libs {
                println!("cargo::rustc-link-lib={lib}");
            }
            println!("cargo::rustc-cfg=with_mpi");
            println!("cargo::rustc-env=VERBSS_MPI_MISSING=");
        }
        Err(why) => {
            println!(
                "cargo::warning=verbss-mpi is built without its MPI parts ({why}); \
                 install Open MPI and METIS (Debian: libopenmpi-dev openmpi-bin libmetis-dev), \
                 then `cargo clean -p verbss-mpi` and build again"
            );
            println!("cargo::rustc-env=VERBSS_MPI_MISSING={why}");
        }
    }
}
