//! What the build script of `verbss-mpi` uses to find MPI, METIS and
//! PT-Scotch: a C library's flags, from pkg-config or a command line,
//! confirmed by compiling a probe program against them.

use std::env;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Include folders, library folders and libraries.
#[derive(Default, Clone)]
pub struct Flags {
    /// `-I` folders.
    pub include: Vec<PathBuf>,
    /// `-L` folders.
    pub search: Vec<PathBuf>,
    /// `-l` libraries.
    pub libs: Vec<String>,
}

impl Flags {
    /// Picks `-I`, `-L` and `-l` out of a command line.
    pub fn parse(line: &str) -> Flags {
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

    /// The flags of `$dir/include`, `$dir/lib` and `-l lib`.
    pub fn under(dir: &Path, lib: &str) -> Flags {
        Flags {
            include: vec![dir.join("include")],
            search: vec![dir.join("lib")],
            libs: vec![lib.into()],
        }
    }

    /// Just `-l lib`: the compiler's default paths.
    pub fn lib(lib: &str) -> Flags {
        Flags {
            libs: vec![lib.into()],
            ..Flags::default()
        }
    }

    /// Adds `other`'s flags after these.
    pub fn extend(&mut self, other: Flags) {
        self.include.extend(other.include);
        self.search.extend(other.search);
        self.libs.extend(other.libs);
    }

    /// Tells cargo to link the libraries.
    pub fn link(&self) {
        for dir in &self.search {
            println!("cargo::rustc-link-search=native={}", dir.display());
        }
        for lib in &self.libs {
            println!("cargo::rustc-link-lib={lib}");
        }
    }
}

/// The standard output of `program args…` when it runs and succeeds.
pub fn output(program: &str, args: &[&str]) -> Option<String> {
    let out = Command::new(program).args(args).output().ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).into_owned())
}

/// The flags pkg-config (`$PKG_CONFIG`) gives for `package`, if it knows it.
pub fn pkg_config(package: &str) -> Option<Flags> {
    let program = env::var("PKG_CONFIG").unwrap_or_else(|_| "pkg-config".into());
    output(&program, &["--cflags", "--libs", package]).map(|line| Flags::parse(&line))
}

/// Compiles the C program `source` as `out/NAME.c` against `flags`, and
/// links it unless `compile_only`; on failure, the first error of the
/// compiler or the linker.
pub fn probe(
    flags: &Flags,
    out: &Path,
    name: &str,
    source: &str,
    compile_only: bool,
) -> Result<(), String> {
    let file = out.join(format!("{name}.c"));
    std::fs::write(&file, source).map_err(|e| format!("cannot write {}: {e}", file.display()))?;
    let compiler = cc::Build::new()
        .try_get_compiler()
        .map_err(|e| format!("no C compiler: {e}"))?;
    let mut command = compiler.to_command();
    command.arg(&file).arg("-o").arg(out.join(name));
    if compile_only {
        command.arg("-c");
    }
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
