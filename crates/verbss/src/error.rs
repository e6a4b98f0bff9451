//! The library's error type: every failure names the file, the line (or byte
//! offset) and what was expected.

use std::path::PathBuf;

/// Everything that can go wrong in verbss.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The operating system refused to open, read or write a file.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        #[source]
        source: std::io::Error,
    },
    /// A text file does not hold what its format requires at a line.
    #[error("{}:{line}: {message}", path.display())]
    Parse {
        /// The file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// What was found and what was expected.
        message: String,
    },
    /// A binary file (or binary section) is malformed at a byte offset.
    #[error("{}: byte {offset}: {message}", path.display())]
    Binary {
        /// The file.
        path: PathBuf,
        /// 0-based byte offset from the start of the file.
        offset: u64,
        /// What was found and what was expected.
        message: String,
    },
    /// A CGNS file does not hold what verbss reads (the message names the
    /// zone, section or boundary condition), or the CGNS library failed.
    #[error("{}: {message}", path.display())]
    Cgns {
        /// The file.
        path: PathBuf,
        /// What was found and what was expected.
        message: String,
    },
    /// The output format cannot hold a cell or facet of the mesh (a polygon
    /// or polyhedron in SU2 or Gmsh).
    #[error(
        "{}: the {format} format cannot hold {what} (write .vtu, or an OpenFOAM case; a mesh \
         read from a .cgns file also writes back as .cgns)",
        path.display()
    )]
    Unrepresentable {
        /// The file.
        path: PathBuf,
        /// The format's name.
        format: &'static str,
        /// The element or facet, named (`element 17, a polyhedron`).
        what: String,
    },
    /// The file's extension does not name a format verbss knows.
    #[error("{}: unknown mesh format (expected .msh, .su2, .vtu, .cgns or an OpenFOAM case directory)", path.display())]
    UnknownFormat {
        /// The file.
        path: PathBuf,
    },
    /// A mesh that was read is not usable (a structural problem not tied to one line).
    #[error("invalid mesh: {0}")]
    InvalidMesh(String),
    /// A setting or an argument is out of range.
    #[error("invalid setting: {0}")]
    InvalidSetting(String),
    /// A displacement given to a binding (Python, C) is out of range.
    #[error("invalid displacement: {0}")]
    InvalidDisplacement(String),
    /// A file a command would write is refused before the solve: it is an
    /// input, another output, or no regular file.
    #[error("{flag} {}: {message}", path.display())]
    Output {
        /// The option (or case-file key) that names it.
        flag: String,
        /// The file.
        path: PathBuf,
        /// Why it is refused.
        message: String,
    },
    /// A named boundary group does not exist.
    #[error("unknown group '{name}' (the mesh has: {available})")]
    UnknownGroup {
        /// The name asked for.
        name: String,
        /// The groups that exist, comma separated.
        available: String,
    },
    /// A group was asked for but the mesh has no boundary groups at all.
    #[error(
        "unknown group '{name}': the mesh has no boundary groups. A Gmsh mesh gets them from \
         physical groups: add `Physical {entity}(\"{name}\") = {{1, 2}};` to the .geo file, or \
         call `gmsh.model.addPhysicalGroup({facet_dim}, [1, 2], name=\"{name}\")` in Python, \
         with the tags of the {entity_lower}s on that boundary, and mesh again",
        entity = if *.dim == 3 { "Surface" } else { "Curve" },
        entity_lower = if *.dim == 3 { "surface" } else { "curve" },
        facet_dim = .dim.saturating_sub(1)
    )]
    NoGroups {
        /// The name asked for.
        name: String,
        /// The mesh's spatial dimension (2 or 3).
        dim: usize,
    },
    /// What another process sharing the mesh failed with, as it said it
    /// ([`crate::collective::agree`]).
    #[error("{0}")]
    Reported(String),
    /// A picture or chart could not be drawn or encoded (by the
    /// `verbss-render` crate).
    #[error("cannot draw the picture: {0}")]
    Render(String),
    /// A step inverted elements (relative to the input mesh's orientation),
    /// or left one that the flow solver refuses
    /// ([`crate::quality::Failure`]).
    #[error(
        "step {step}: element {element} {failure} at {}, signed volume {volume:.3e} ({count} inverted element(s))",
        format_point(.centroid)
    )]
    Inverted {
        /// The step.
        step: usize,
        /// How many elements inverted.
        count: usize,
        /// The worst one's number in the file.
        element: u64,
        /// Its centroid.
        centroid: Vec<f64>,
        /// Its worst corner's signed area (2D) or volume (3D), relative to the
        /// input orientation (≤ 0), or the signed volume of the test it fails
        /// ([`crate::quality::Inversion::volume`]).
        volume: f64,
        /// The test it fails.
        failure: crate::quality::Failure,
    },
    /// No solver reached a solution that could be trusted.
    #[error(
        "step {step}: the solve did not converge (stages tried: {}; true residual {:.3e}; \
         node {} estimated error {:.3e} of its cell height{})",
        .what.stages, .what.true_residual, .what.node, .what.error_ratio,
        if .what.diverged { "; the sweeps diverged: omega too large for this mesh" } else { "" }
    )]
    NotConverged {
        /// The step.
        step: usize,
        /// The last solve's account.
        what: Box<Unconverged>,
    },
}

/// What [`Error::NotConverged`] reports of the last solve tried.
#[derive(Debug, Clone, PartialEq)]
pub struct Unconverged {
    /// The solvers tried, in order (`sweeps, multigrid, direct`).
    pub stages: String,
    /// Root-mean-square true residual of the last solve.
    pub true_residual: f64,
    /// The worst node's estimated error relative to its local cell height.
    pub error_ratio: f64,
    /// That node's number in the file.
    pub node: u64,
    /// Whether the configured sweeps diverged.
    pub diverged: bool,
}

/// A point as `(x, y[, z])` with six decimals, as messages print it; a
/// coordinate of 1e9 or more in magnitude in exponent form (`1.500000e300`).
pub fn format_point(p: &[f64]) -> String {
    let parts: Vec<String> = p
        .iter()
        .map(|x| {
            if x.abs() >= 1e9 {
                format!("{x:.6e}")
            } else {
                format!("{x:.6}")
            }
        })
        .collect();
    format!("({})", parts.join(", "))
}

/// A number as messages print it: its shortest exact form, with an
/// exponent where that is shorter than the digits (`1e308`, `2.5e-12`).
pub fn format_number(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-4..1e9).contains(&x.abs()) {
        x.to_string()
    } else {
        format!("{x:e}")
    }
}

/// Numbers as messages print them ([`format_number`]), comma separated.
pub fn format_numbers(xs: &[f64]) -> String {
    let shown: Vec<String> = xs.iter().map(|&x| format_number(x)).collect();
    shown.join(", ")
}

/// Result with the library's [`Error`].
pub type Result<T> = std::result::Result<T, Error>;

#[cfg(test)]
mod tests {
    #[test]
    fn huge_coordinates_print_short() {
        assert_eq!(
            super::format_point(&[1.5e300, -0.25]),
            "(1.500000e300, -0.250000)"
        );
    }
}
