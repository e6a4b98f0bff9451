//! The paper's numbers, case by case, as printed in its text and Tables 1–9
//! (T.J. Lin, Z.Q. Guan, J.H. Chang, S.H. Lo, "Vertex-Ball Spring Smoothing:
//! an efficient method for unstructured dynamic hybrid meshes").

use serde::Serialize;

/// A method's largest motion in the paper; `at_least` when the paper
/// stopped there without an inversion.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Limit {
    /// The method.
    pub method: &'static str,
    /// The amplitude.
    pub value: f64,
    /// Whether the method got at least this far (no inversion reported).
    pub at_least: bool,
}

/// One column of a quality table: a method's counts at an amplitude.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Bins {
    /// The table.
    pub table: u8,
    /// The amplitude (units or degrees).
    pub amplitude: f64,
    /// The method.
    pub method: &'static str,
    /// Counts in the bins 0–0.02, 0.02–0.1, 0.1–0.4, 0.4–0.7, 0.7–1.
    pub counts: [usize; 5],
}

/// The paper's numbers of one case.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Numbers {
    /// The mesh's node count.
    pub nodes: usize,
    /// Its element count.
    pub cells: Option<usize>,
    /// Largest motions before the first inversion.
    pub limits: &'static [Limit],
    /// Quality tables (1, 4, 5).
    pub bins: &'static [Bins],
    /// CPU seconds for one step per method (Tables 2, 7 and the text).
    pub seconds_per_step: &'static [(&'static str, f64)],
    /// VerBSS sweeps per step (the text).
    pub verbss_iterations: Option<f64>,
    /// VerBSS's split (Tables 3, 6): forming, solving, updating, total seconds.
    pub split: Option<[f64; 4]>,
    /// Solve seconds per step against the processor count (Tables 8, 9):
    /// (processors, seconds, speed-up).
    pub threads: &'static [(usize, f64, f64)],
}

const NONE: Numbers = Numbers {
    nodes: 0,
    cells: None,
    limits: &[],
    bins: &[],
    seconds_per_step: &[],
    verbss_iterations: None,
    split: None,
    threads: &[],
};

/// The paper's numbers for the case `name`.
pub fn numbers(name: &str) -> Numbers {
    match name {
        "rectangle-298" => Numbers {
            nodes: 298,
            cells: Some(496),
            limits: &[
                Limit {
                    method: "spring",
                    value: 2.6,
                    at_least: false,
                },
                Limit {
                    method: "ball-vertex",
                    value: 5.0,
                    at_least: true,
                },
                Limit {
                    method: "verbss",
                    value: 5.0,
                    at_least: true,
                },
            ],
            bins: &[
                Bins {
                    table: 1,
                    amplitude: 4.0,
                    method: "ball-vertex",
                    counts: [6, 35, 81, 126, 248],
                },
                Bins {
                    table: 1,
                    amplitude: 4.0,
                    method: "verbss",
                    counts: [6, 35, 81, 126, 248],
                },
            ],
            seconds_per_step: &[("ball-vertex", 0.020), ("verbss", 0.0005)],
            ..NONE
        },
        "rectangle-1035" => Numbers {
            nodes: 1035,
            seconds_per_step: &[("ball-vertex", 0.349), ("verbss", 0.004)],
            ..NONE
        },
        "rectangle-3055" => Numbers {
            nodes: 3055,
            seconds_per_step: &[("ball-vertex", 3.174), ("verbss", 0.021)],
            ..NONE
        },
        "rectangle-8081" => Numbers {
            nodes: 8081,
            seconds_per_step: &[("ball-vertex", 20.532), ("verbss", 0.165)],
            ..NONE
        },
        "rectangle-21376" => Numbers {
            nodes: 21376,
            seconds_per_step: &[("verbss", 0.685)],
            ..NONE
        },
        "naca0012" => Numbers {
            nodes: 4485,
            cells: Some(8664),
            limits: &[
                Limit {
                    method: "spring",
                    value: 18.0,
                    at_least: false,
                },
                Limit {
                    method: "verbss",
                    value: 96.0,
                    at_least: true,
                },
            ],
            bins: &[
                Bins {
                    table: 4,
                    amplitude: 15.0,
                    method: "spring",
                    counts: [2, 3, 28, 158, 8473],
                },
                Bins {
                    table: 4,
                    amplitude: 15.0,
                    method: "ball-vertex",
                    counts: [0, 0, 6, 120, 8538],
                },
                Bins {
                    table: 4,
                    amplitude: 15.0,
                    method: "verbss",
                    counts: [0, 0, 6, 120, 8538],
                },
                Bins {
                    table: 5,
                    amplitude: 30.0,
                    method: "ball-vertex",
                    counts: [0, 1, 12, 206, 8445],
                },
                Bins {
                    table: 5,
                    amplitude: 30.0,
                    method: "verbss",
                    counts: [0, 1, 12, 206, 8445],
                },
            ],
            seconds_per_step: &[("spring", 9.11), ("ball-vertex", 9.328), ("verbss", 0.11)],
            verbss_iterations: Some(65.0),
            split: Some([0.031, 0.076, 0.003, 0.110]),
            ..NONE
        },
        "three-element" => Numbers {
            nodes: 11372,
            cells: Some(22177),
            verbss_iterations: Some(80.0),
            split: Some([0.094, 0.196, 0.018, 0.308]),
            ..NONE
        },
        "sphere-cube" => Numbers {
            nodes: 2058,
            cells: Some(9496),
            limits: &[
                Limit {
                    method: "spring",
                    value: 10.0,
                    at_least: false,
                },
                Limit {
                    method: "laplacian",
                    value: 10.0,
                    at_least: false,
                },
                Limit {
                    method: "ball-vertex",
                    value: 16.0,
                    at_least: true,
                },
                Limit {
                    method: "verbss",
                    value: 16.0,
                    at_least: true,
                },
            ],
            seconds_per_step: &[
                ("spring", 1.683),
                ("ball-vertex", 1.954),
                ("laplacian", 0.621),
                ("verbss", 0.067),
            ],
            verbss_iterations: Some(60.0),
            ..NONE
        },
        "two-fish" => Numbers {
            nodes: 20840,
            cells: Some(108322),
            seconds_per_step: &[("verbss", 0.205)],
            threads: &[(1, 0.205, 1.000), (2, 0.112, 1.830), (4, 0.076, 2.697)],
            ..NONE
        },
        "bending-wing" => Numbers {
            nodes: 106755,
            cells: Some(610252),
            seconds_per_step: &[("verbss", 1.198)],
            threads: &[(1, 1.198, 1.000), (2, 0.743, 1.612), (4, 0.463, 2.587)],
            ..NONE
        },
        _ => NONE,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_quality_column_adds_up_to_the_papers_element_count() {
        for name in ["rectangle-298", "naca0012"] {
            let n = numbers(name);
            for b in n.bins {
                assert_eq!(b.counts.iter().sum::<usize>(), n.cells.unwrap(), "{b:?}");
            }
        }
    }

    #[test]
    fn the_speed_ups_are_the_papers_time_ratios() {
        for name in ["two-fish", "bending-wing"] {
            let rows = numbers(name).threads;
            for &(_, s, up) in rows {
                assert!((rows[0].1 / s - up).abs() < 0.01, "{name}: {s} {up}");
            }
        }
    }

    #[test]
    fn the_split_adds_up_to_the_total() {
        for name in ["naca0012", "three-element"] {
            let [a, b, c, total] = numbers(name).split.unwrap();
            assert!((a + b + c - total).abs() < 1e-9, "{name}");
        }
    }
}
