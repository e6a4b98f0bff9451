//! The C program of docs/bindings.md (`square.c`) built with the static
//! command the page gives, word for word but for the library's path, and
//! run: it prints the steps the page shows (issue 43, 18: the command lacked
//! `-lcgns` and failed with `undefined reference to cg_close`).

use std::path::PathBuf;
use std::process::Command;

const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");

/// The page's first code block of `language` after the line holding `after`.
fn block(page: &str, after: &str, language: &str) -> String {
    let from = page.find(after).expect("the anchor is on the page");
    let fence = format!("```{language}\n");
    let start = from + page[from..].find(&fence).expect("a code block") + fence.len();
    let end = start + page[start..].find("```").expect("the block ends");
    page[start..end].to_string()
}

#[test]
fn the_static_link_command_of_the_bindings_page_builds_square_c() {
    let page = std::fs::read_to_string(format!("{ROOT}/docs/bindings.md")).unwrap();
    let commands = block(&page, "## C, C++ and Fortran", "sh");
    let command = commands
        .lines()
        .find(|l| l.starts_with("cc ") && l.contains("libverbss_capi.a"))
        .expect("a static link command");
    let exe = std::env::current_exe().unwrap();
    let deps: PathBuf = exe.parent().unwrap().to_path_buf();
    let library = deps.join("libverbss_capi.a");
    assert!(library.exists(), "no {}", library.display());
    let dir = tempfile::tempdir().unwrap();
    let source = block(&page, "A complete program (`square.c`", "c");
    std::fs::write(dir.path().join("my_solver.c"), source).unwrap();
    // A build without the CGNS library links without it, as the page says.
    let cgns = if verbss::io::cgns::available().is_ok() {
        " -lcgns"
    } else {
        ""
    };
    let command = command
        .replace(" -lcgns", cgns)
        .replace("target/release/libverbss_capi.a", library.to_str().unwrap())
        .replace("-Iinclude", &format!("-I{ROOT}/include"));
    let built = Command::new("sh")
        .arg("-c")
        .arg(&command)
        .current_dir(dir.path())
        .output()
        .unwrap();
    assert!(
        built.status.success(),
        "{command}:\n{}",
        String::from_utf8_lossy(&built.stderr)
    );
    let run = Command::new(dir.path().join("my_solver")).output().unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let printed = String::from_utf8_lossy(&run.stdout).into_owned();
    let shown = block(
        &page,
        "It prints the refused setting's message, then",
        "text",
    );
    for line in shown.lines().filter(|l| l.starts_with("step ")) {
        assert!(printed.contains(line), "{line:?} not in:\n{printed}");
    }
}
