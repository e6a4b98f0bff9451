//! What a program that moves a mesh needs, in one `use verbss::prelude::*;`:
//! the mesh, reading and writing it, the motions of its groups, the deformer
//! and its settings, the error, and the built-in airfoil mesh.
//!
//! [`crate::Result`] is left out: it would hide the standard two-parameter
//! `Result` of a glob import.

pub use crate::deform::{Deformer, StepReport};
pub use crate::error::Error;
pub use crate::generate::{naca0012, AirfoilGrid};
pub use crate::io::{read, write, WriteOptions};
pub use crate::mesh::{CellKind, Cells, Group, Mesh};
pub use crate::motion::{Attachment, Motion};
pub use crate::settings::Settings;
