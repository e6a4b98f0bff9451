//! With the cargo feature `cgns` (on by default), finds the CGNS library and,
//! when it is here, links it and sets `cfg(with_cgns)` (plus
//! `cfg(cgns_size64)` when its `cgsize_t` is 64 bits wide); otherwise the
//! crate builds without CGNS and says so once (`cargo::warning`).
//!
//! The library: `$CGNS_DIR/include` and `$CGNS_DIR/lib` when set, else the
//! compiler's default paths (Debian's `libcgns-dev`). Its header is
//! confirmed by compiling a probe program that calls it. The reason for a
//! build without it is passed on as `VERBSS_CGNS_MISSING` (empty when it
//! was found).

fn main() {
    println!("cargo::rustc-check-cfg=cfg(with_cgns)");
    println!("cargo::rustc-check-cfg=cfg(cgns_size64)");
    println!("cargo::rerun-if-changed=build.rs");
    #[cfg(feature = "cgns")]
    cgns::find();
    #[cfg(not(feature = "cgns"))]
    println!("cargo::rustc-env=VERBSS_CGNS_MISSING=the cargo feature `cgns` is off");
}

#[cfg(feature = "cgns")]
mod cgns {
    use std::env;
    use std::path::PathBuf;

    /// Compiles the C program `source` against the CGNS header in
    /// `include` (none: the compiler's paths), quietly; the compiler's
    /// first error when it does not compile.
    fn compiles(include: Option<&PathBuf>, name: &str, source: &str) -> Result<(), String> {
        let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
        let file = out.join(format!("{name}.c"));
        std::fs::write(&file, source)
            .map_err(|e| format!("cannot write {}: {e}", file.display()))?;
        let compiler = cc::Build::new()
            .cargo_metadata(false)
            .try_get_compiler()
            .map_err(|e| format!("no C compiler: {e}"))?;
        let mut command = compiler.to_command();
        command
            .arg("-c")
            .arg(&file)
            .arg("-o")
            .arg(out.join(format!("{name}.o")));
        if let Some(dir) = include {
            command.arg(format!("-I{}", dir.display()));
        }
        let result = command
            .output()
            .map_err(|e| format!("cannot run the C compiler: {e}"))?;
        if result.status.success() {
            return Ok(());
        }
        let stderr = String::from_utf8_lossy(&result.stderr);
        let first = stderr
            .lines()
            .find(|l| l.contains("error"))
            .unwrap_or("the probe program does not compile");
        let at = first.find("error").unwrap_or(0);
        Err(first[at..].trim().to_string())
    }

    /// Finds, confirms and links the library, or says why not.
    pub fn find() {
        println!("cargo::rerun-if-env-changed=CGNS_DIR");
        let dir = env::var_os("CGNS_DIR").map(PathBuf::from);
        let include = dir.as_ref().map(|d| d.join("include"));
        let calls = "#include <cgnslib.h>\nint probe(void) { return cg_get_error() == 0; }\n";
        match compiles(include.as_ref(), "verbss_cgns_probe", calls) {
            Ok(()) => {
                if let Some(dir) = &dir {
                    println!(
                        "cargo::rustc-link-search=native={}",
                        dir.join("lib").display()
                    );
                }
                println!("cargo::rustc-link-lib=cgns");
                let wide = "#include <cgnslib.h>\n\
                            _Static_assert(sizeof(cgsize_t) == 8, \"32-bit cgsize_t\");\n";
                if compiles(include.as_ref(), "verbss_cgns_size", wide).is_ok() {
                    println!("cargo::rustc-cfg=cgns_size64");
                }
                println!("cargo::rustc-cfg=with_cgns");
                println!("cargo::rustc-env=VERBSS_CGNS_MISSING=");
            }
            Err(why) => {
                println!(
                    "cargo::warning=verbss is built without CGNS ({why}); install the CGNS \
                     library (Debian: libcgns-dev), then `cargo clean -p verbss` and build again"
                );
                println!("cargo::rustc-env=VERBSS_CGNS_MISSING={why}");
            }
        }
    }
}
