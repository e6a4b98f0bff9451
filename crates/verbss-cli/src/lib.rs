//! The `verbss` command line as a library: the argument types of each
//! command, the job runner, progress and the picture recorder. The `verbss`
//! binary (`src/main.rs`) parses and dispatches; `verbss-mpi` runs the same
//! `deform` jobs with its distributed stepper.
//!
//! Exit codes: 0 success, 2 bad input (file, argument, setting), 3 a step
//! inverted an element, 4 a step no solver could solve to a trusted result.

#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod case_times;
pub mod convert;
pub mod deform;
pub mod demo;
pub mod input;
pub mod msh;
pub mod overwrite;
pub mod progress;
pub mod quality;
pub mod render;
pub mod run;
pub mod settings;
pub mod zone;
