//! The paper's quality histogram and the summary `verbss quality` prints.

use serde::Serialize;

/// The paper's bin edges: bins `[0, 0.02)`, `[0.02, 0.1)`, `[0.1, 0.4)`,
/// `[0.4, 0.7)` and `[0.7, 1.0]`.
pub const BIN_EDGES: [f64; 6] = [0.0, 0.02, 0.1, 0.4, 0.7, 1.0];

/// The bin of quality `q`: the `k` with `lo_k ≤ q < hi_k`; the last bin also
/// holds `q = 1` (and anything above), the first anything below 0.
pub fn bin_index(q: f64) -> usize {
    BIN_EDGES[1..BIN_EDGES.len() - 1]
        .iter()
        .filter(|&&edge| edge <= q)
        .count()
}

/// One histogram bin: the elements with `lo ≤ q < hi` (`≤ hi` for the last).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[non_exhaustive]
pub struct Bin {
    /// Lower edge (included).
    pub lo: f64,
    /// Upper edge (excluded, except 1.0 for the last bin).
    pub hi: f64,
    /// Number of elements in the bin.
    pub count: usize,
}

/// Minimum, mean and histogram of per-element qualities.
///
/// Serialises as `{"min":…,"mean":…,"bins":[{"lo":0.0,"hi":0.02,"count":…},…]}`;
/// with no element, `min` and `mean` are NaN (`null` in JSON).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[non_exhaustive]
pub struct Summary {
    /// The smallest quality.
    pub min: f64,
    /// The arithmetic mean `Σ q / n` (summed in element order).
    pub mean: f64,
    /// The paper's five bins, in order.
    pub bins: Vec<Bin>,
}

impl Summary {
    /// The summary of qualities `q` (one per element).
    pub fn new(q: &[f64]) -> Summary {
        let mut bins: Vec<Bin> = BIN_EDGES
            .windows(2)
            .map(|w| Bin {
                lo: w[0],
                hi: w[1],
                count: 0,
            })
            .collect();
        for &x in q {
            bins[bin_index(x)].count += 1;
        }
        let (min, mean) = if q.is_empty() {
            (f64::NAN, f64::NAN)
        } else {
            (
                q.iter().copied().fold(f64::INFINITY, f64::min),
                q.iter().sum::<f64>() / q.len() as f64,
            )
        };
        Summary { min, mean, bins }
    }
}

/// A mesh's quality report: `{"quality":{…},"inverted":…}`.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[non_exhaustive]
pub struct Report {
    /// Minimum, mean and histogram of the element qualities.
    pub quality: Summary,
    /// Number of inverted elements.
    pub inverted: usize,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bin_edges_belong_to_the_bin_above_and_one_to_the_last() {
        let q = [0.0, 0.019, 0.02, 0.0999, 0.1, 0.4, 0.69, 0.7, 0.99, 1.0];
        let s = Summary::new(&q);
        let counts: Vec<usize> = s.bins.iter().map(|b| b.count).collect();
        assert_eq!(counts, [2, 2, 1, 2, 3]);
        assert_eq!(s.min, 0.0);
        assert!((s.mean - q.iter().sum::<f64>() / 10.0).abs() < 1e-15);
    }

    #[test]
    fn serialises_as_the_cli_prints_it() {
        let r = Report {
            quality: Summary::new(&[0.5, 1.0]),
            inverted: 0,
        };
        assert_eq!(
            serde_json::to_string(&r).unwrap(),
            r#"{"quality":{"min":0.5,"mean":0.75,"bins":[{"lo":0.0,"hi":0.02,"count":0},{"lo":0.02,"hi":0.1,"count":0},{"lo":0.1,"hi":0.4,"count":0},{"lo":0.4,"hi":0.7,"count":1},{"lo":0.7,"hi":1.0,"count":1}]},"inverted":0}"#
        );
    }

    #[test]
    fn empty_summary_has_no_min_or_mean() {
        let s = Summary::new(&[]);
        assert!(s.min.is_nan() && s.mean.is_nan());
        assert!(s.bins.iter().all(|b| b.count == 0));
        assert!(serde_json::to_string(&s)
            .unwrap()
            .starts_with(r#"{"min":null,"mean":null,"#));
    }
}
