//! A half-model with a symmetry plane, partitioned by Gmsh (the half
//! sphere in its box of `scripts/make_half_model_fixtures.py`, 3
//! partitions), moved on 1, 2 and 3 ranks where no rank holds the whole
//! mesh, its symmetry plane sliding (`--slide`): the moved pieces, the
//! report and the gathered mesh are those of one process to 1e-10 of the
//! motion, with the paper's method and with the default one.

use verbss::near_wall::Robust;
use verbss::settings::Reference;

mod common;
mod like_one_process;

use like_one_process::{asset, deforms_like_one_process_with, NearWall};

fn half_model(method: &str, robust: Robust, stages: &str) {
    if !common::mpi_ready() {
        return;
    }
    let mesh = asset("gmsh/half_sphere_part3_v41_ascii.msh");
    let near_wall = NearWall {
        method,
        robust,
        args: &["--slide", "symmetry"],
        slides: &["symmetry"],
        steps: 2,
        stages,
    };
    deforms_like_one_process_with(
        &mesh,
        "sphere",
        &["--translate", "0.1,0,0.05"],
        Reference::Updated,
        0.1,
        &[],
        &near_wall,
    );
}

#[test]
fn a_half_model_slides_on_its_symmetry_plane_as_on_one_process() {
    half_model("verbss", Robust::off(), "sweeps");
}

#[test]
fn the_default_method_moves_a_half_model_as_on_one_process() {
    half_model("robust", Robust::recommended(), "blended motion only");
}
