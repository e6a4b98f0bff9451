//! One file per element kind: its node numbering and reference tables.

pub mod general;
pub mod hexahedron;
pub mod line;
pub mod pyramid;
pub mod quad;
pub mod tetra;
pub mod triangle;
pub mod vertex;
pub mod wedge;
