//! Sets `cfg(with_mpi)` and `cfg(with_ptscotch)` as the `verbss-mpi` crate
//! found MPI and PT-Scotch (its build script tells them as
//! `DEP_VERBSS_MPI_WITH_MPI` and `DEP_VERBSS_MPI_WITH_PTSCOTCH`).

fn main() {
    println!("cargo::rustc-check-cfg=cfg(with_mpi)");
    println!("cargo::rustc-check-cfg=cfg(with_ptscotch)");
    for (var, cfg) in [
        ("DEP_VERBSS_MPI_WITH_MPI", "with_mpi"),
        ("DEP_VERBSS_MPI_WITH_PTSCOTCH", "with_ptscotch"),
    ] {
        println!("cargo::rerun-if-env-changed={var}");
        if std::env::var_os(var).is_some() {
            println!("cargo::rustc-cfg={cfg}");
        }
    }
}
