//! Where a step is accepted or rejected: the check of a configuration
//! (every cell's quality and validity, [`crate::quality`]) summed over the
//! processes that share the mesh, the choice between the blended and the
//! plain start, and the error that names a rejected step's worst cell.
//!
//! A configuration is accepted when its solve converged and no cell of any
//! process is invalid (docs/method.md, "Accepting a step"). Each cell is
//! counted by one process ([`Collective::counts`]), so the summary is one
//! process's on any cut.

use crate::collective::Collective;
use crate::mesh::Mesh;
use crate::quality::{self, Failure, Inversion, Summary};
use crate::solve::SolveInfo;
use crate::threads::Workers;

/// A blended solve whose minimum quality falls below this fraction of the
/// reference configuration's is compared with the solve without the blend.
pub const QUALITY_DROP: f64 = 0.5;

/// A configuration's check: its own cells' qualities and invalid cells, and
/// the summary over every process.
#[derive(Debug, Clone, PartialEq)]
pub struct Check {
    /// The quality of each local cell.
    pub quality: Vec<f64>,
    /// The local cells that are invalid (inverted, or failing the flow
    /// solver's checks).
    pub invalid: Vec<Inversion>,
    /// The summary over every process's counted cells.
    pub summary: Totals,
}

/// The quality of a configuration over every process (each cell once).
#[derive(Debug, Clone, PartialEq)]
pub struct Totals {
    /// The smallest quality (NaN without cells).
    pub min_quality: f64,
    /// The mean quality (NaN without cells).
    pub mean_quality: f64,
    /// Cells in the paper's five quality bins.
    pub bins: [usize; 5],
    /// The number of invalid cells.
    pub invalid: usize,
    /// The invalid cell of the lowest signed volume (the lowest element
    /// tag among equals).
    pub worst: Option<Worst>,
}

/// The worst invalid cell of a configuration, over every process.
#[derive(Debug, Clone, PartialEq)]
pub struct Worst {
    /// Its element tag in the input.
    pub element: u64,
    /// The mean of its nodes.
    pub centroid: Vec<f64>,
    /// Its signed volume ([`Inversion::volume`]).
    pub volume: f64,
    /// The test it fails.
    pub failure: Failure,
}

/// Checks `mesh` at `coords` against the input orientations `orientation`
/// (collective), the cells on `workers`.
pub fn check(
    mesh: &Mesh,
    coords: &[f64],
    orientation: &[i8],
    on: &dyn Collective,
    workers: &Workers,
) -> Check {
    let (quality, invalid) =
        workers.install(|| quality::qualities_and_inversions(mesh, coords, orientation));
    let counted: Vec<bool> = (0..mesh.cells.len())
        .map(|c| on.counts(mesh.cells.cell(c)))
        .collect();
    let mine: Vec<f64> = quality
        .iter()
        .zip(&counted)
        .filter(|(_, &k)| k)
        .map(|(&q, _)| q)
        .collect();
    let local = Summary::new(&mine);
    let mut counts: Vec<f64> = local.bins.iter().map(|b| b.count as f64).collect();
    let own_invalid: Vec<&Inversion> = invalid.iter().filter(|i| counted[i.cell]).collect();
    counts.push(own_invalid.len() as f64);
    counts.push(mine.iter().sum());
    on.sum(&mut counts);
    let mut low = [-local.min];
    on.max(&mut low);
    let mut bins = [0; 5];
    for (b, &c) in bins.iter_mut().zip(&counts) {
        *b = c as usize;
    }
    let cells: usize = bins.iter().sum();
    let (min_quality, mean_quality) = if cells == 0 {
        (f64::NAN, f64::NAN)
    } else {
        (-low[0], counts[6] / cells as f64)
    };
    let worst = worst(mesh, &own_invalid, on);
    Check {
        quality,
        invalid,
        summary: Totals {
            min_quality,
            mean_quality,
            bins,
            invalid: counts[5] as usize,
            worst,
        },
    }
}

/// Whether a blended solve checked `check` is weak, to be compared with the
/// solve without the blend: an invalid cell, or a minimum quality below
/// [`QUALITY_DROP`] of the reference configuration's, `reference_quality`.
pub fn weak(check: &Check, reference_quality: f64) -> bool {
    check.summary.invalid > 0 || check.summary.min_quality < QUALITY_DROP * reference_quality
}

/// Whether the solve `a` (its account and its check) is better than `b`:
/// valid (converged, no invalid cell) where `b` is not, or of a higher
/// minimum quality.
pub fn better(a: (&SolveInfo, &Check), b: (&SolveInfo, &Check)) -> bool {
    let valid = |(info, check): (&SolveInfo, &Check)| info.converged && check.summary.invalid == 0;
    valid(a) && (!valid(b) || a.1.summary.min_quality > b.1.summary.min_quality)
}

/// The worst of every process's invalid cells `mine` (collective).
fn worst(mesh: &Mesh, mine: &[&Inversion], on: &dyn Collective) -> Option<Worst> {
    let dim = mesh.dim;
    // Per process: found, volume, tag, the failure's two numbers, centroid.
    let width = 5 + dim;
    let mut row = vec![0.0; width];
    if let Some(w) = mine.iter().min_by(|a, b| {
        a.volume
            .total_cmp(&b.volume)
            .then(mesh.cell_tags[a.cell].cmp(&mesh.cell_tags[b.cell]))
    }) {
        row[0] = 1.0;
        row[1] = w.volume;
        row[2] = mesh.cell_tags[w.cell] as f64;
        row[3..5].copy_from_slice(&w.failure.to_numbers());
        row[5..].copy_from_slice(&w.centroid);
    }
    let all = on.gather(&row);
    all.chunks_exact(width)
        .filter(|r| r[0] == 1.0)
        .min_by(|a, b| a[1].total_cmp(&b[1]).then(a[2].total_cmp(&b[2])))
        .map(|r| Worst {
            element: r[2] as u64,
            centroid: r[5..].to_vec(),
            volume: r[1],
            failure: Failure::from_numbers([r[3], r[4]]),
        })
}
