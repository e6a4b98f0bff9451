//! The paper's six cases (ten with the five rectangle sizes): where their
//! case files and mesh generators are, how far each limit search goes and
//! where the quality histograms are taken.
//!
//! Every case runs its case file (`cases/<name>.toml`) with each method. The
//! largest motion before the first inverted element (the "limit") is found
//! by stepping on with the same increment per step as the case file's
//! motion, from the last valid configuration (updated reference, paper
//! option 1), until an element inverts or the cap is reached: the limit is
//! the amplitude of the last valid step, so it is bracketed to one increment.

use std::path::{Path, PathBuf};

use verbss::motion::{Attachment, Motion};

/// How a case's limit is searched.
#[derive(Debug, Clone, PartialEq)]
pub enum LimitSearch {
    /// The case file's motion continued linearly past its `N` steps, up to
    /// step `cap` (amplitude `n × per_step` at step `n`).
    Continue {
        /// The last step tried.
        cap: usize,
    },
    /// A separate run: the group rotated about `center` by `per_step`
    /// degrees a step (counter-clockwise: nose up for an airfoil pointing to
    /// −x), up to step `cap` (the paper's §4.2 rotation to 96°).
    Rotation {
        /// The rotating group.
        group: &'static str,
        /// The centre of rotation.
        center: [f64; 2],
        /// The last step tried.
        cap: usize,
    },
}

/// A point of a run where the quality histogram is taken (Tables 1, 4, 5).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BinsAt {
    /// The step of the run (of the limit run for [`LimitSearch::Rotation`]).
    pub step: usize,
    /// Its amplitude, in the case's unit.
    pub amplitude: f64,
    /// Whether the step is in the limit run (else the case file's run).
    pub in_limit_run: bool,
}

/// One of the paper's cases.
#[derive(Debug, Clone, PartialEq)]
pub struct PaperCase {
    /// The case name (`cases/<name>.toml`).
    pub name: &'static str,
    /// The paper's section.
    pub section: &'static str,
    /// What moves, in words.
    pub motion: &'static str,
    /// The generating script in `cases/meshes/` and its arguments before the output path.
    pub generator: (&'static str, &'static [&'static str]),
    /// The limit's unit (`units`, `°`, `× the prescribed motion`).
    pub unit: &'static str,
    /// The amplitude per step of the limit search.
    pub per_step: f64,
    /// How the limit is searched.
    pub limit: LimitSearch,
    /// Where the histograms are taken.
    pub bins: &'static [BinsAt],
    /// Whether the case measures 1 against 2 threads (Tables 8, 9).
    pub threads: bool,
    /// What the pictures show.
    pub view: View,
    /// Whether to draw the pictures (not for the finer rectangles: the
    /// 298-node one shows the case).
    pub pictures: bool,
}

/// What the before/after pictures show.
#[derive(Debug, Clone, PartialEq)]
pub enum View {
    /// A 2D mesh, in this window (or all of it).
    Plane(Option<[f64; 4]>),
    /// The cut of a 3D mesh by the plane `x[axis] = at`, in this window.
    Cut {
        /// The axis held fixed.
        axis: usize,
        /// Its value.
        at: f64,
        /// The window in the plane's other two coordinates.
        window: Option<[f64; 4]>,
    },
    /// The surfaces of these groups, seen from (azimuth, elevation) in degrees.
    Surface {
        /// The groups drawn.
        groups: &'static [&'static str],
        /// Azimuth and elevation of the viewer.
        camera: (f64, f64),
    },
}

const fn rectangle(
    name: &'static str,
    nodes: &'static [&'static str],
    pictures: bool,
) -> PaperCase {
    PaperCase {
        name,
        section: "4.1",
        motion: "the 4 × 2 rectangle moves up 0.1 unit a step; 4.0 units in 40 steps",
        generator: ("rectangle.py", nodes),
        unit: "units",
        per_step: 0.1,
        limit: LimitSearch::Continue { cap: 69 },
        bins: &[BinsAt {
            step: 40,
            amplitude: 4.0,
            in_limit_run: false,
        }],
        threads: false,
        view: View::Plane(None),
        pictures,
    }
}

/// All cases, in the paper's order.
pub const CASES: &[PaperCase] = &[
    rectangle("rectangle-298", &["298"], true),
    rectangle("rectangle-1035", &["1035"], false),
    rectangle("rectangle-3055", &["3055"], false),
    rectangle("rectangle-8081", &["8081"], false),
    rectangle("rectangle-21376", &["21376"], false),
    PaperCase {
        name: "naca0012",
        section: "4.2",
        motion: "pitching θ₀ = 40° and plunging h₀ = 0.2 about the quarter chord, 160 steps; \
                 limit: rotation about the quarter chord, 1° a step",
        generator: ("naca0012.py", &[]),
        unit: "°",
        per_step: 1.0,
        limit: LimitSearch::Rotation {
            group: "airfoil",
            center: [0.25, 0.0],
            cap: 180,
        },
        bins: &[
            BinsAt {
                step: 15,
                amplitude: 15.0,
                in_limit_run: true,
            },
            BinsAt {
                step: 30,
                amplitude: 30.0,
                in_limit_run: true,
            },
        ],
        threads: false,
        view: View::Plane(Some([-0.6, 1.6, -0.7, 0.7])),
        pictures: true,
    },
    PaperCase {
        name: "three-element",
        section: "4.3",
        motion: "slat and flap turn and move toward the main element, 40 steps",
        generator: ("three_element.py", &[]),
        unit: "× the prescribed motion",
        per_step: 1.0 / 40.0,
        limit: LimitSearch::Continue { cap: 40 },
        bins: &[BinsAt {
            step: 40,
            amplitude: 1.0,
            in_limit_run: false,
        }],
        threads: false,
        view: View::Plane(Some([-0.25, 1.35, -0.4, 0.2])),
        pictures: true,
    },
    PaperCase {
        name: "sphere-cube",
        section: "5.1",
        motion: "the sphere moves 0.5 unit a step toward −x; 16 units in 32 steps",
        generator: ("sphere_cube.py", &[]),
        unit: "units",
        per_step: 0.5,
        limit: LimitSearch::Continue { cap: 39 },
        bins: &[BinsAt {
            step: 32,
            amplitude: 16.0,
            in_limit_run: false,
        }],
        threads: false,
        view: View::Cut {
            axis: 2,
            at: 0.0,
            window: None,
        },
        pictures: true,
    },
    PaperCase {
        name: "two-fish",
        section: "5.2",
        motion: "eq. 11 undulation in anti-phase, λ = 1, c = 1.5, 60 steps a cycle \
                 (grown in over 10 steps, then one cycle: 70 steps)",
        generator: ("two_fish.py", &[]),
        unit: "× the prescribed motion",
        per_step: 1.0 / 70.0,
        limit: LimitSearch::Continue { cap: 70 },
        bins: &[BinsAt {
            step: 70,
            amplitude: 1.0,
            in_limit_run: false,
        }],
        threads: true,
        view: View::Cut {
            axis: 2,
            at: 0.0,
            window: Some([-0.3, 1.4, -0.7, 0.7]),
        },
        pictures: true,
    },
    PaperCase {
        name: "bending-wing",
        section: "5.3",
        motion: "the wing bends up, tip deflection 0.4 span (tip section turned 38.7°), 40 steps",
        generator: ("bending_wing.py", &[]),
        unit: "× the prescribed motion",
        per_step: 1.0 / 40.0,
        limit: LimitSearch::Continue { cap: 40 },
        bins: &[BinsAt {
            step: 40,
            amplitude: 1.0,
            in_limit_run: false,
        }],
        threads: true,
        view: View::Surface {
            groups: &["wing", "body"],
            camera: (-150.0, 20.0),
        },
        pictures: true,
    },
];

impl PaperCase {
    /// The case with this name.
    pub fn find(name: &str) -> Option<&'static PaperCase> {
        CASES.iter().find(|c| c.name == name)
    }

    /// The case file under `root` (the `cases/` folder).
    pub fn file(&self, root: &Path) -> PathBuf {
        root.join(format!("{}.toml", self.name))
    }

    /// The limit run's motions for `Rotation` searches: the group turned by
    /// `per_step` degrees a step up to `cap` steps (every other boundary node
    /// fixed).
    pub fn rotation_attachments(&self) -> Option<(Vec<Attachment>, usize)> {
        let LimitSearch::Rotation { group, center, cap } = self.limit else {
            return None;
        };
        let motion = Motion::Rotation {
            center: [center[0], center[1], 0.0],
            axis: [0.0, 0.0, 1.0],
            angle: (self.per_step * cap as f64).to_radians(),
        };
        let attachment = Attachment {
            groups: vec![group.to_string()],
            motion,
        };
        Some((vec![attachment], cap))
    }
}
