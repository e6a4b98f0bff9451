//! The quality of a step over all ranks, each cell counted on one rank: the
//! numbers of the single-process step report (`min_quality`, `inverted`,
//! `bins`, `mean_quality`; docs/method.md for the quality measure) from
//! each rank's own cells and four all-reduces; and a failed step's worst
//! inverted cell, named as one process names it.

use verbss::deform::StepReport;
use verbss::quality::{inversions, qualities_and_inversions, Failure, Summary};
use verbss::{Error, Mesh};

use crate::Comm;

/// The quality of the cells of every rank's `mesh` at its `coords`,
/// against the orientations `orientation` (collective): `min_quality`
/// (`min_r min_c q_c`), `inverted` and the paper's five `bins` (sums over
/// the ranks) and `mean_quality` (`Σ_r Σ_c q_c / Σ_r n_r`: the
/// single-process mean up to the order of the sum). The other fields are
/// the defaults. With no cell on any rank, the minimum and the mean are
/// NaN, as [`Summary::new`] gives them.
pub fn step_quality(comm: &Comm, mesh: &Mesh, coords: &[f64], orientation: &[i8]) -> StepReport {
    let (quality, inversions) = qualities_and_inversions(mesh, coords, orientation);
    let summary = Summary::new(&quality);
    let mut counts: Vec<u64> = summary.bins.iter().map(|b| b.count as u64).collect();
    counts.push(inversions.len() as u64);
    let counts = comm.sums(&counts);
    let min = comm.min(quality.iter().copied().fold(f64::INFINITY, f64::min));
    let sum = comm.sum(quality.iter().sum::<f64>());
    let mut bins = [0; 5];
    for (bin, &count) in bins.iter_mut().zip(&counts) {
        *bin = count as usize;
    }
    let cells: usize = bins.iter().sum();
    let (min_quality, mean_quality) = if cells == 0 {
        (f64::NAN, f64::NAN)
    } else {
        (min, sum / cells as f64)
    };
    let mut report = StepReport::default();
    report.min_quality = min_quality;
    report.mean_quality = mean_quality;
    report.inverted = counts[bins.len()] as usize;
    report.bins = bins;
    report
}

/// The error one process gives for step `step` at `coords` where a cell of
/// any rank's `mesh` is inverted (collective), `None` where none is: the
/// inverted cell of the lowest signed volume of a worst corner (the lowest
/// element tag among equals), its tag and centroid, and the inverted cells
/// of all ranks counted.
pub fn inverted_error(
    comm: &Comm,
    mesh: &Mesh,
    coords: &[f64],
    orientation: &[i8],
    step: usize,
) -> Option<Error> {
    let inverted = inversions(mesh, coords, orientation);
    let mut worst = vec![f64::INFINITY; 3 + mesh.dim];
    let mut tags = [0, inverted.len() as u64];
    if let Some(w) = inverted.iter().min_by(|a, b| a.volume.total_cmp(&b.volume)) {
        worst[0] = w.volume;
        worst[1..=mesh.dim].copy_from_slice(&w.centroid);
        worst[mesh.dim + 1..].copy_from_slice(&w.failure.to_numbers());
        tags[0] = mesh.cell_tags[w.cell];
    }
    let worst = comm.all_gather(&worst);
    let tags = comm.all_gather(&tags);
    let count: u64 = tags.iter().map(|t| t[1]).sum();
    let r = (0..tags.len())
        .filter(|&r| tags[r][1] > 0)
        .min_by(|&a, &b| {
            worst[a][0]
                .total_cmp(&worst[b][0])
                .then(tags[a][0].cmp(&tags[b][0]))
        })?;
    Some(Error::Inverted {
        step,
        count: count as usize,
        element: tags[r][0],
        centroid: worst[r][1..=mesh.dim].to_vec(),
        volume: worst[r][0],
        failure: Failure::from_numbers([worst[r][mesh.dim + 1], worst[r][mesh.dim + 2]]),
    })
}
