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
//!
//! PT-Scotch, for the distributed read of SU2 files, is looked for only
//! with MPI: `$PTSCOTCH_DIR/include` and `$PTSCOTCH_DIR/lib` when set, else
//! Debian's `/usr/include/scotch` and the compiler's default paths, with the
//! libraries `ptscotch`, `scotch` and `ptscotcherr`, confirmed by a probe.
//! When found it compiles `src/scotch.c` and sets `cfg(with_ptscotch)`;
//! otherwise `VERBSS_PTSCOTCH_MISSING` says why.

use std::env;
use std::path::PathBuf;

use verbss_build::{output, pkg_config, probe, Flags};

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
    match env::var_os("METIS_DIR") {
        Some(dir) => Flags::under(&PathBuf::from(dir), "metis"),
        None => pkg_config("metis").unwrap_or_else(|| Flags::lib("metis")),
    }
}

/// PT-Scotch's flags (see the module documentation).
fn ptscotch() -> Flags {
    let mut flags = match env::var_os("PTSCOTCH_DIR") {
        Some(dir) => Flags::under(&PathBuf::from(dir), "ptscotch"),
        None => Flags {
            include: vec!["/usr/include/scotch".into()],
            ..Flags::lib("ptscotch")
        },
    };
    flags.libs.extend(["scotch".into(), "ptscotcherr".into()]);
    flags
}

/// PT-Scotch's flags when a probe against them and MPI's links, or why not.
fn find_ptscotch(mpi: &Flags, out: &std::path::Path) -> Result<Flags, String> {
    let flags = ptscotch();
    let mut all = flags.clone();
    all.extend(mpi.clone());
    let source = "#include <stdio.h>\n#include <mpi.h>\n#include <ptscotch.h>\n\
         int main(void) { SCOTCH_Context c; SCOTCH_Dgraph g; SCOTCH_contextInit(&c); \
         SCOTCH_dgraphInit(&g, MPI_COMM_WORLD); return 0; }\n";
    probe(&all, out, "probe_ptscotch", source, false).map(|()| flags)
}

fn main() {
    println!("cargo::rustc-check-cfg=cfg(with_mpi)");
    println!("cargo::rustc-check-cfg=cfg(with_ptscotch)");
    println!("cargo::rerun-if-changed=src/scotch.c");
    println!("cargo::rerun-if-changed=build.rs");
    println!("cargo::rerun-if-changed=src/shim.c");
    for var in [
        "PATH",
        "MPICC",
        "METIS_DIR",
        "PTSCOTCH_DIR",
        "PKG_CONFIG",
        "PKG_CONFIG_PATH",
        "PKG_CONFIG_LIBDIR",
    ] {
        println!("cargo::rerun-if-env-changed={var}");
    }
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    let found = mpi().and_then(|mut flags| {
        flags.extend(metis());
        let source = "#include <metis.h>\n#include <mpi.h>\n\
             int main(void) { idx_t o[METIS_NOPTIONS]; METIS_SetDefaultOptions(o); return MPI_Init(0, 0); }\n";
        probe(&flags, &out, "probe", source, false).map(|()| flags)
    });
    match found {
        Ok(flags) => {
            cc::Build::new()
                .file("src/shim.c")
                .includes(&flags.include)
                .warnings(true)
                .extra_warnings(true)
                .compile("verbss_mpi_shim");
            match find_ptscotch(&flags, &out) {
                Ok(scotch) => {
                    cc::Build::new()
                        .file("src/scotch.c")
                        .includes(&scotch.include)
                        .includes(&flags.include)
                        .warnings(true)
                        .extra_warnings(true)
                        .compile("verbss_mpi_scotch");
                    scotch.link();
                    println!("cargo::rustc-cfg=with_ptscotch");
                    println!("cargo::metadata=with_ptscotch=1");
                    println!("cargo::rustc-env=VERBSS_PTSCOTCH_MISSING=");
                }
                Err(why) => println!("cargo::rustc-env=VERBSS_PTSCOTCH_MISSING={why}"),
            }
            flags.link();
            println!("cargo::rustc-cfg=with_mpi");
            println!("cargo::metadata=with_mpi=1");
            println!("cargo::rustc-env=VERBSS_MPI_MISSING=");
        }
        Err(why) => {
            println!(
                "cargo::warning=verbss-mpi is built without its MPI parts ({why}); \
                 install Open MPI and METIS (Debian: libopenmpi-dev openmpi-bin libmetis-dev), \
                 then `cargo clean -p verbss-mpi` and build again"
            );
            println!("cargo::rustc-env=VERBSS_MPI_MISSING={why}");
            println!("cargo::rustc-env=VERBSS_PTSCOTCH_MISSING=no MPI");
        }
    }
}
