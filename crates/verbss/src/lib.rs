//! # verbss — Vertex-Ball Spring Smoothing for unstructured hybrid meshes
//!
//! When a boundary moves, verbss moves the interior nodes of a 2D/3D hybrid mesh
//! (triangles, quads, tetrahedra, hexahedra, prisms, pyramids) so that no
//! element inverts, by the VerBSS method of Lin, Guan, Chang & Lo
//! ("Vertex-Ball Spring Smoothing: an efficient method for unstructured dynamic
//! hybrid meshes").
//!
//! The pipeline, one module per concept:
//! [`io`] reads and writes files → [`mesh::Mesh`] → [`topology`] →
//! [`springs`] assembles the node-block system → [`solve`] → [`quality`] checks.

#![warn(missing_docs)]

pub mod error;
pub mod geometry;
pub mod io;
pub mod mesh;
pub mod quality;
pub mod springs;
pub mod topology;

pub use error::{Error, Result};
pub use mesh::{CellKind, Cells, Group, Mesh};
pub mod solve;
pub mod generate;
pub mod case;
pub mod deform;
pub mod motion;
pub mod report;
pub mod render;
pub mod html_report;
