//! # verbss — Vertex-Ball Spring Smoothing for unstructured hybrid meshes
//!
//! When a boundary moves, verbss moves the interior nodes of a 2D/3D hybrid mesh
//! (triangles, quads, tetrahedra, hexahedra, prisms, pyramids, polygons and
//! polyhedra) so that no element inverts, by the VerBSS method of Lin, Guan, Chang & Lo
//! ("Vertex-Ball Spring Smoothing: an efficient method for unstructured dynamic
//! hybrid meshes"): edge springs plus ball-vertex springs, solved node by node
//! with small LDLᵀ block solves and over-relaxation.
//!
//! The pipeline, one module per concept (ARCHITECTURE.md follows one step
//! through them):
//!
//! | module | what it holds |
//! |---|---|
//! | [`io`] | the formats: Gmsh MSH 2.2/4.1, SU2, VTU/PVD, CGNS, OpenFOAM polyMesh, positions files: file in, [`Mesh`] out, moved mesh back |
//! | [`mesh`] | the [`Mesh`] (flat coordinates, cells, a polyhedron's faces, named groups) and per-kind tables |
//! | [`topology`] | node→cell, edges, boundary facets and nodes, colouring, BFS layers |
//! | [`geometry`] | small fixed-size kernels: determinants, nearest points, LDLᵀ |
//! | [`quality`] | ρ = C r/R, scaled Jacobians, the validity of a cell (checkMesh's cell tests), the paper's histogram |
//! | [`springs`] | assembles the node-block system `K_ii u_i = Σ_j B_ij u_j` |
//! | [`solve`] | the [`solve::Engine`]: VerBSS block SOR, scalar SOR, sparse LU, Laplacian; the multigrid; the escalation |
//! | [`motion`] | boundary motions: translation, rotation, pitch–plunge, undulation, bending, positions |
//! | [`settings`] | the one table of settings and the presets |
//! | [`near_wall`] | the near-wall treatments: the blended rigid motion, the rigid layer, wall-distance stiffening, sub-steps |
//! | [`deform`] | the stepper: motion → system → solve → update → check, on a whole mesh or a rank's part |
//! | [`collective`] | sums, maxima and ghost values over the processes sharing a mesh |
//! | [`threads`] | the one pool of worker threads a run's parallel work shares |
//! | [`case`], [`report`] | the TOML case file and `report.json` |
//! | [`generate`] | built-in meshes (the demo's NACA0012 O-grid) |
//!
//! Pictures of meshes coloured by quality and the self-contained HTML run
//! report are in the `verbss-render` crate, so this library draws nothing and
//! depends on no picture crate. The maths is stated in `docs/method.md`.
//!
//! # Once per time step, from a flow solver
//!
//! ```
//! use verbss::prelude::*;
//!
//! let mesh = naca0012(&AirfoilGrid::default())?;
//! let pitch = Attachment {
//!     groups: vec!["airfoil".into()],
//!     motion: Motion::Rotation {
//!         center: [0.25, 0.0, 0.0],
//!         axis: [0.0, 0.0, 1.0],
//!         angle: 10f64.to_radians(),
//!     },
//! };
//! let mut deformer = Deformer::new(&mesh, &[pitch], Settings::new(4))?;
//! for n in 1..=4 {
//!     let step = deformer.step(n)?; // an inverted element is an Err
//!     assert_eq!(step.inverted, 0);
//! }
//! let moved = deformer.mesh(); // same numbering, new coordinates
//! assert_eq!(moved.node_count(), mesh.node_count());
//! # Ok::<(), verbss::Error>(())
//! ```
//!
//! [`prelude`] holds what this example uses. Lower down, [`solve::Engine`]
//! solves one step for given prescribed displacements.

#![warn(missing_docs)]
#![deny(unsafe_code)]

pub mod case;
pub mod collective;
pub mod deform;
pub mod error;
pub mod generate;
pub mod geometry;
pub mod io;
pub mod mesh;
pub mod motion;
mod names;
pub mod near_wall;
pub mod prelude;
pub mod quality;
pub mod report;
pub mod settings;
pub mod solve;
pub mod springs;
pub mod threads;
pub mod topology;

pub use error::{Error, Result};
pub use mesh::{CellKind, Cells, CompactCells, Group, Mesh};

/// The README's library example, run as a doctest.
#[doc = include_str!("../../../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
