//! With the cargo feature `cgns` (on by default), finds the CGNS library and,
//! when it is here, links it and sets `cfg(with_cgns)` (plus
//! `cfg(cgns_size64)` when its `cgsize_t` is 64 bits wide); otherwise the
//! crate builds without CGNS and says so once (`cargo::warning`).
//!
//! The library: `$CGNS_DIR/include` and `$CGNS_DIR/lib` when set, else
//! pkg-config's `cgns`, else the compiler's default paths (Debian's
//! `libcgns-dev`). It is confirmed by compiling and linking a probe program.
//! The reason for a build without it is passed on as `VERBSS_CGNS_MISSING`
//! (empty when it was found).

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

    use verbss_build::{pkg_config, probe, Flags};

    /// Finds, confirms and links the library, or says why not.
    pub fn find() {
        for var in [
            "CGNS_DIR",
            "PKG_CONFIG",
            "PKG_CONFIG_PATH",
            "PKG_CONFIG_LIBDIR",
        ] {
            println!("cargo::rerun-if-env-changed={var}");
        }
        let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
        let flags = match env::var_os("CGNS_DIR") {
            Some(dir) => Flags::under(&PathBuf::from(dir), "cgns"),
            None => pkg_config("cgns").unwrap_or_else(|| Flags::lib("cgns")),
        };
        let links = "#include <cgnslib.h>\nint main(void) { return cg_get_error() == 0; }\n";
        match probe(&flags, &out, "cgns_probe", links, false) {
            Ok(()) => {
                flags.link();
                let wide = "#include <cgnslib.h>\n\
                            _Static_assert(sizeof(cgsize_t) == 8, \"32-bit cgsize_t\");\n";
                if probe(&flags, &out, "cgns_size", wide, true).is_ok() {
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
