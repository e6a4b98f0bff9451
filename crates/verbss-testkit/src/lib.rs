//! # verbss-testkit — tests that need a package outside Rust
//!
//! A test that needs a system library or an external program (mpirun,
//! python3 with some modules, …) starts with
//!
//! ```text
//! if !needs("python3 with meshio (pip install meshio)", python(&["meshio"])) {
//!     return;
//! }
//! ```
//!
//! When the package is here the test runs. When it is not, the test prints
//! one line, `skipped: TEST needs PACKAGE (why)`, and passes — unless the
//! environment variable `VERBSS_REQUIRE_ALL` is `1` (CI sets it, having
//! installed everything), where the same line is the test's failure.
//!
//! The notice goes straight to the standard error stream, past the test
//! harness's capture, so that `cargo test` shows it.

use std::io::Write;
use std::process::Command;

/// Whether a test that needs `package` can run, from `probe`: `Ok` when the
/// package is here, `Err(why)` when not (see the crate documentation).
/// Panics with the notice when the package is missing and
/// `VERBSS_REQUIRE_ALL=1`, at the caller's line.
#[track_caller]
pub fn needs(package: &str, probe: Result<(), String>) -> bool {
    let thread = std::thread::current();
    let test = thread.name().unwrap_or("a test");
    match verdict(test, package, probe, required()) {
        Verdict::Run => true,
        Verdict::Skip(notice) => {
            // A failed write to stderr leaves nothing better to do.
            let _ = writeln!(std::io::stderr(), "{notice}");
            false
        }
        Verdict::Fail(message) => panic!("{message}"),
    }
}

/// What a test does about a package.
#[derive(Debug, PartialEq)]
enum Verdict {
    Run,
    /// Skips, with this notice.
    Skip(String),
    /// Fails, with this message.
    Fail(String),
}

fn verdict(test: &str, package: &str, probe: Result<(), String>, required: bool) -> Verdict {
    match probe {
        Ok(()) => Verdict::Run,
        Err(why) if required => Verdict::Fail(format!(
            "{test} needs {package} ({why}), and VERBSS_REQUIRE_ALL=1 allows no skipped test"
        )),
        Err(why) => Verdict::Skip(format!("skipped: {test} needs {package} ({why})")),
    }
}

/// Whether `VERBSS_REQUIRE_ALL=1` is set: every test must run.
pub fn required() -> bool {
    std::env::var("VERBSS_REQUIRE_ALL").is_ok_and(|v| v == "1")
}

/// Whether `program args…` runs and succeeds.
pub fn program(program: &str, args: &[&str]) -> Result<(), String> {
    match Command::new(program).args(args).output() {
        Ok(out) if out.status.success() => Ok(()),
        Ok(out) => Err(format!(
            "`{program}` failed: {}",
            last_line(&out.stderr).unwrap_or("no message")
        )),
        Err(e) => Err(format!("`{program}`: {e}")),
    }
}

/// Whether `python3` imports every module of `modules`.
pub fn python(modules: &[&str]) -> Result<(), String> {
    let import = format!("import {}", modules.join(", "));
    match Command::new("python3").args(["-c", &import]).output() {
        Ok(out) if out.status.success() => Ok(()),
        Ok(out) => Err(last_line(&out.stderr)
            .unwrap_or("python3 failed")
            .to_string()),
        Err(e) => Err(format!("python3: {e}")),
    }
}

/// The last non-empty line of `bytes` (a traceback's error), if any.
fn last_line(bytes: &[u8]) -> Option<&str> {
    std::str::from_utf8(bytes)
        .ok()?
        .lines()
        .rev()
        .map(str::trim)
        .find(|l| !l.is_empty())
}

/// Whether the MPI tests can run: the MPI crate was built with its MPI
/// parts (`missing`: why not, `verbss_mpi::missing()`) and `mpirun` runs;
/// otherwise the test skips with a notice ([`needs`]).
pub fn mpi_ready(missing: Option<&str>) -> bool {
    needs(
        "Open MPI and METIS when verbss-mpi is built (Debian: libopenmpi-dev libmetis-dev, \
         then cargo clean -p verbss-mpi)",
        missing.map_or(Ok(()), |why| Err(why.into())),
    ) && needs(
        "mpirun (Debian: openmpi-bin)",
        program("mpirun", &["--version"]),
    )
}

/// `mpirun --oversubscribe -np NP` (root allowed, as in containers), with
/// the session directory `session` of its own: two mpiruns started at once
/// race for the shared one under /tmp.
pub fn mpirun(np: usize, session: &std::path::Path) -> Command {
    let mut command = Command::new("mpirun");
    command
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        .env("OMPI_MCA_orte_tmpdir_base", session)
        .args(["--oversubscribe", "-np", &np.to_string()]);
    command
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_present_package_lets_the_test_run() {
        assert_eq!(verdict("t", "p", Ok(()), true), Verdict::Run);
        assert_eq!(verdict("t", "p", Ok(()), false), Verdict::Run);
        assert!(needs("nothing", Ok(())));
    }

    #[test]
    fn a_missing_package_skips_with_one_line_or_fails_when_required() {
        assert_eq!(
            verdict("t", "mpirun", Err("not found".into()), false),
            Verdict::Skip("skipped: t needs mpirun (not found)".into())
        );
        assert_eq!(
            verdict("t", "mpirun", Err("not found".into()), true),
            Verdict::Fail(
                "t needs mpirun (not found), and VERBSS_REQUIRE_ALL=1 allows no skipped test"
                    .into()
            )
        );
    }

    #[test]
    fn a_missing_program_says_why() {
        let why = program("verbss-testkit-no-such-program", &[]).unwrap_err();
        assert!(
            why.starts_with("`verbss-testkit-no-such-program`: "),
            "{why}"
        );
    }

    #[test]
    fn a_failing_program_gives_its_last_line() {
        let why = program("sh", &["-c", "echo first >&2; echo last >&2; exit 3"]).unwrap_err();
        assert_eq!(why, "`sh` failed: last");
    }
}
