//! Boundary motions: where a boundary node is at step `n` of a run.
//!
//! A [`Motion`] maps a node's position in the input mesh `X` to its position
//! at step `n` of `N` ([`Clock`]). Motions are attached to boundary groups
//! ([`Attachment`]); several attachments naming the same group compose in
//! order (the second acts on the output of the first), so a pitching–plunging
//! wing that also bends is two attachments. The rules that decide which node
//! follows which motion live in [`crate::deform`].
//!
//! Monotone motions (translation, rotation, bending, positions from one file)
//! grow linearly with the run: their amount at step `n` is `n/N` of the
//! final amount.

use std::collections::HashMap;
use std::path::PathBuf;

use crate::error::{Error, Result};
use crate::geometry::{cross, dot, norm};
use crate::io::positions;

mod pattern;

use pattern::step_fields;
pub use pattern::step_path;

/// Step `step` of a run of `steps` steps, with physical time `step × dt`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Clock {
    /// The step, 0 for the input mesh.
    pub step: usize,
    /// The number of steps of the run, `N`.
    pub steps: usize,
    /// Time per step (used by [`Motion::Undulation`]).
    pub dt: f64,
}

impl Clock {
    /// `n / N`, the fraction of the run done.
    pub fn fraction(&self) -> f64 {
        self.step as f64 / self.steps.max(1) as f64
    }

    /// The time `t = n · dt`.
    pub fn time(&self) -> f64 {
        self.step as f64 * self.dt
    }
}

/// Where prescribed node positions come from ([`Motion::Positions`]).
#[derive(Debug, Clone, PartialEq)]
pub enum PositionSource {
    /// Final positions (node index → point), reached linearly:
    /// `x(n) = (1 − n/N) X + (n/N) P`, exactly `P` at the last step.
    Final(HashMap<usize, Vec<f64>>),
    /// One file per step ([`positions`] format: SU2 surface file or CSV, node
    /// IDs are 0-based node indices): `pattern` with `{step}` (or `{step:0W}`,
    /// zero-padded to W digits) replaced by the step number; the file of step
    /// `n` holds the positions at step `n`.
    PerStep(PathBuf),
    /// Positions for the step about to be taken, whatever its number:
    /// `x(n) = P` (node index → point). A coupled solver sets them before
    /// each step with [`crate::deform::Deformer::set_motion`].
    Given(HashMap<usize, Vec<f64>>),
}

/// A boundary motion. Points are `D` numbers (2 or 3); 3-vectors given for a
/// 2D mesh use their first two components.
#[derive(Debug, Clone, PartialEq)]
pub enum Motion {
    /// The nodes stay where they are.
    Fixed,
    /// The nodes slide within their plane (a symmetry plane): the normal
    /// component of their displacement is zero, the tangential ones are
    /// unknowns. `normal: None` takes the plane of the group's facets.
    Slide {
        /// The plane's normal, or `None` for the group's own plane.
        normal: Option<[f64; 3]>,
    },
    /// Rigid translation: `x(n) = X + (n/N) d`.
    Translation {
        /// The displacement `d` reached at the last step.
        displacement: [f64; 3],
    },
    /// Rigid rotation about `center` by `(n/N) α`, counter-clockwise about
    /// `axis` (right-hand rule; in 2D the axis is `z`):
    /// `x(n) = c + R(α n/N) (X − c)`.
    Rotation {
        /// The centre of rotation.
        center: [f64; 3],
        /// The rotation axis (3D; normalised on use).
        axis: [f64; 3],
        /// The final angle α in radians.
        angle: f64,
    },
    /// The paper's pitching–plunging (eq. 10): `θₙ = θ₀ sin(2πn/T)`,
    /// `hₙ = h₀ sin(2πn/T)`; `x(n) = c + R(θₙ) (X − c) + hₙ e`, a rotation
    /// about the pitch centre `c` (counter-clockwise positive: an airfoil
    /// pointing its nose to −x pitches nose-up for θ < 0), then a plunge
    /// along `e`.
    PitchPlunge {
        /// The pitch centre `c`.
        center: [f64; 3],
        /// The pitch axis (3D; normalised on use).
        axis: [f64; 3],
        /// The pitch amplitude θ₀ in radians.
        pitch: f64,
        /// The plunge `h₀ e`: amplitude times direction.
        plunge: [f64; 3],
        /// The period `T` in steps; `None` for the run's `N` (paper).
        period: Option<usize>,
    },
    /// Travelling-wave undulation of a body (paper eq. 11):
    /// `x(n) = X + y(ξ, t) e_y` with `y = A(ξ) cos(2π/λ (ξ − c t))`,
    /// `ξ = (X − head)·e_x` the distance from the head along the body axis
    /// `e_x`, `A(ξ) = Σₖ aₖ ξᵏ`, `t = n·dt`. With `ramp > 0` the wave grows in
    /// over the first `ramp` steps (factor `min(1, n/ramp)`), so that the
    /// first step does not jump from the straight body to the full wave.
    Undulation {
        /// The head position.
        head: [f64; 3],
        /// The body axis `e_x`, head to tail (normalised on use).
        axis: [f64; 3],
        /// The lateral direction `e_y` (normalised on use).
        lateral: [f64; 3],
        /// The envelope's polynomial coefficients `a₀, a₁, …`.
        amplitude: Vec<f64>,
        /// The wavelength λ.
        wavelength: f64,
        /// The phase speed c.
        speed: f64,
        /// Steps over which the wave grows in (0: none).
        ramp: usize,
    },
    /// Bending of a body clamped at `root` (a wing, paper §5.3). With `s` the
    /// span coordinate `(X − root)·e_s` (negative values count as 0), `b` the
    /// offset `(X − root)·e_b` along the bending direction and `δ = (n/N) δ_tip`,
    /// the deflection is `w(s) = δ (s/L)²` and each section turns with the
    /// bent axis by `φ(s) = atan(2 δ s / L²)`:
    /// `x(n) = X + (w + b(cos φ − 1)) e_b − b sin φ e_s`. A tip deflection of
    /// 0.4 L turns the tip section by atan(0.8) ≈ 38.7°. Points beyond the
    /// tip (`s > L`: a rounded tip cap, the cells outboard of it that a
    /// rigid layer moves with the wing) move rigidly with the tip section:
    /// with `r = s − L`, `x(n) = X + (w + b(cos φ − 1) + r sin φ) e_b +
    /// (r(cos φ − 1) − b sin φ) e_s` at `s = L`, not the parabola continued.
    Bending {
        /// A point of the clamped root section.
        root: [f64; 3],
        /// The span direction `e_s` (normalised on use).
        span_axis: [f64; 3],
        /// The bending direction `e_b` (made normal to `e_s` and normalised on use).
        direction: [f64; 3],
        /// The span `L`.
        span: f64,
        /// The tip deflection `δ_tip` reached at the last step.
        tip: f64,
    },
    /// Node positions prescribed from data (a structural solver's output).
    Positions(PositionSource),
}

/// A motion attached to boundary groups.
#[derive(Debug, Clone, PartialEq)]
pub struct Attachment {
    /// The groups that follow the motion.
    pub groups: Vec<String>,
    /// The motion.
    pub motion: Motion,
}

/// A motion's data for one step, loaded by [`Motion::frame`] (files of
/// [`PositionSource::PerStep`]).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Frame {
    /// Node index → position at this step.
    pub positions: HashMap<usize, Vec<f64>>,
}

/// The largest coordinate a position may have (a motion's points, a
/// positions file's, every step's targets): beyond it the springs'
/// products overflow.
pub(crate) const MAX_COORDINATE: f64 = 1e100;

/// Refuses a displacement that a binding gives (`u`, `dim` numbers per
/// node) unless every number is finite and within ±1e100: names the first
/// other number and, by `node(k)`, where its row `k` came from
/// (`Python Deformer.step displacement of node 17`).
pub fn check_displacement(u: &[f64], dim: usize, node: impl Fn(usize) -> String) -> Result<()> {
    match u
        .iter()
        .position(|x| x.is_nan() || x.abs() > MAX_COORDINATE)
    {
        None => Ok(()),
        Some(k) => Err(Error::InvalidDisplacement(format!(
            "{} is {} (expected finite numbers within ±1e100)",
            node(k / dim.max(1)),
            crate::error::format_number(u[k])
        ))),
    }
}

/// `v` of length 1. Scaled by its largest component first, so that a
/// direction of huge (or tiny) finite numbers is still one.
fn unit(v: &[f64; 3], what: &str) -> Result<[f64; 3]> {
    let largest = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if !(largest > 0.0 && largest.is_finite()) {
        return Err(Error::InvalidSetting(format!(
            "{what} must be a non-zero vector of finite numbers (got {})",
            crate::error::format_numbers(v)
        )));
    }
    let w = v.map(|x| x / largest);
    let l = norm(&w);
    Ok(w.map(|x| x / l))
}

/// Rotates `p − c` by `angle` about `axis` (Rodrigues; in 2D about z, or
/// −z when `axis` points that way) and adds `c` back.
pub(crate) fn rotate(p: &mut [f64], c: &[f64; 3], axis: &[f64; 3], angle: f64) {
    if p.len() == 2 {
        let (s, co) = (if axis[2] < 0.0 { -angle } else { angle }).sin_cos();
        let (x, y) = (p[0] - c[0], p[1] - c[1]);
        p[0] = c[0] + co * x - s * y;
        p[1] = c[1] + s * x + co * y;
        return;
    }
    let (s, co) = angle.sin_cos();
    let v = [p[0] - c[0], p[1] - c[1], p[2] - c[2]];
    let kxv = cross(axis, &v);
    let kv = dot(axis, &v);
    for d in 0..3 {
        p[d] = c[d] + v[d] * co + kxv[d] * s + axis[d] * kv * (1.0 - co);
    }
}

/// `(X − a)·e` over the first `p.len()` components.
fn along(p: &[f64], a: &[f64; 3], e: &[f64; 3]) -> f64 {
    p.iter().enumerate().map(|(d, x)| (x - a[d]) * e[d]).sum()
}

impl Motion {
    /// Whether the nodes of the motion's groups are prescribed (not free or sliding).
    pub fn moves(&self) -> bool {
        !matches!(self, Motion::Fixed | Motion::Slide { .. })
    }

    /// Checks the motion's settings (non-zero axes, positive lengths, a
    /// translation and a rotation center within ±1e100) for a mesh of
    /// dimension `dim`.
    pub fn validate(&self, dim: usize) -> Result<()> {
        let bad = |m: String| Err(Error::InvalidSetting(m));
        // Beyond ±1e100 the springs' products overflow to NaN.
        let (what, point) = match self {
            Motion::Translation { displacement } => ("the translation", Some(displacement)),
            Motion::Rotation { center, .. } | Motion::PitchPlunge { center, .. } => {
                ("the rotation center", Some(center))
            }
            _ => ("", None),
        };
        if let Some(p) = point.filter(|p| !p.iter().all(|x| x.abs() <= MAX_COORDINATE)) {
            return bad(format!(
                "{what} {} is beyond ±1e100 (the displacements would overflow)",
                crate::error::format_point(&p[..dim.min(3)])
            ));
        }
        match self {
            Motion::Rotation { axis, .. } | Motion::PitchPlunge { axis, .. } if dim == 3 => {
                unit(axis, "the rotation axis").map(|_| ())
            }
            Motion::PitchPlunge {
                period: Some(0), ..
            } => bad("the pitch-plunge period must be at least 1 step".into()),
            Motion::Undulation {
                axis,
                lateral,
                wavelength,
                ..
            } => {
                unit(axis, "the body axis")?;
                unit(lateral, "the lateral direction")?;
                if *wavelength > 0.0 {
                    Ok(())
                } else {
                    bad(format!(
                        "the wavelength must be positive (got {})",
                        crate::error::format_number(*wavelength)
                    ))
                }
            }
            Motion::Bending {
                span_axis,
                direction,
                span,
                ..
            } => {
                let es = unit(span_axis, "the span axis")?;
                let k = dot(direction, &es);
                let b = std::array::from_fn(|d| direction[d] - k * es[d]);
                unit(&b, "the bending direction (normal to the span axis)")?;
                if *span > 0.0 {
                    Ok(())
                } else {
                    bad(format!(
                        "the span must be positive (got {})",
                        crate::error::format_number(*span)
                    ))
                }
            }
            Motion::Slide { normal: Some(n) } => unit(n, "the slide normal").map(|_| ()),
            Motion::Positions(PositionSource::PerStep(pattern)) => {
                step_fields(&pattern.to_string_lossy()).map_or_else(bad, |_| Ok(()))
            }
            _ => Ok(()),
        }
    }

    /// Whether the motion can change the shape of what it moves (given
    /// positions, a bending, an undulation), unlike the rigid motions.
    pub fn deforms(&self) -> bool {
        matches!(
            self,
            Motion::Positions(_) | Motion::Bending { .. } | Motion::Undulation { .. }
        )
    }

    /// Whether the motion is a field defined at every point (all but
    /// [`Motion::Positions`], which prescribes given nodes only).
    pub fn is_field(&self) -> bool {
        !matches!(self, Motion::Positions(_))
    }

    /// Loads what the motion needs at `clock.step` (the step's positions
    /// file) for a mesh of `nodes` nodes in dimension `dim`.
    pub fn frame(&self, clock: Clock, nodes: usize, dim: usize) -> Result<Frame> {
        let Motion::Positions(PositionSource::PerStep(pattern)) = self else {
            return Ok(Frame::default());
        };
        if clock.step == 0 {
            return Ok(Frame::default());
        }
        let path = step_path(pattern, clock.step);
        let table = positions::read(&path, dim)?;
        table.check_against(nodes, &path)?;
        let positions = (0..table.len())
            .map(|k| (table.ids[k], table.point(k).to_vec()))
            .collect();
        Ok(Frame { positions })
    }

    /// Moves point `p` (node `node`, `D` numbers) to where the motion puts it
    /// at `clock`; `frame` is the motion's [`Motion::frame`] for that step.
    /// Returns an error when the motion prescribes no position for the node.
    pub fn apply(&self, node: usize, p: &mut [f64], clock: Clock, frame: &Frame) -> Result<()> {
        let dim = p.len();
        let f = clock.fraction();
        match self {
            Motion::Fixed | Motion::Slide { .. } => {}
            Motion::Translation { displacement } => {
                for d in 0..dim {
                    p[d] += f * displacement[d];
                }
            }
            Motion::Rotation {
                center,
                axis,
                angle,
            } => rotate(p, center, &unit_or_z(axis, dim), f * angle),
            Motion::PitchPlunge {
                center,
                axis,
                pitch,
                plunge,
                period,
            } => {
                let t = period.unwrap_or(clock.steps).max(1) as f64;
                let s = (2.0 * std::f64::consts::PI * clock.step as f64 / t).sin();
                rotate(p, center, &unit_or_z(axis, dim), pitch * s);
                for d in 0..dim {
                    p[d] += s * plunge[d];
                }
            }
            Motion::Undulation {
                head,
                axis,
                lateral,
                amplitude,
                wavelength,
                speed,
                ramp,
            } => {
                let ex = unit(axis, "the body axis")?;
                let ey = unit(lateral, "the lateral direction")?;
                let xi = along(p, head, &ex);
                let a = amplitude.iter().rev().fold(0.0, |acc, c| acc * xi + c);
                let phase = 2.0 * std::f64::consts::PI / wavelength * (xi - speed * clock.time());
                let grow = if *ramp == 0 {
                    1.0
                } else {
                    (clock.step as f64 / *ramp as f64).min(1.0)
                };
                let y = grow * a * phase.cos();
                for d in 0..dim {
                    p[d] += y * ey[d];
                }
            }
            Motion::Bending {
                root,
                span_axis,
                direction,
                span,
                tip,
            } => {
                let es = unit(span_axis, "the span axis")?;
                let k = dot(direction, &es);
                let eb = unit(
                    &std::array::from_fn(|d| direction[d] - k * es[d]),
                    "the bending direction",
                )?;
                let along_span = along(p, root, &es).max(0.0);
                let s = along_span.min(*span);
                let beyond = along_span - s;
                let b = along(p, root, &eb);
                let delta = f * tip;
                let w = delta * (s / span).powi(2);
                let phi = (2.0 * delta * s / (span * span)).atan();
                let (sin, cos) = phi.sin_cos();
                for d in 0..dim {
                    p[d] += (w + b * (cos - 1.0) + beyond * sin) * eb[d]
                        + (beyond * (cos - 1.0) - b * sin) * es[d];
                }
            }
            Motion::Positions(PositionSource::Final(table)) => {
                let target = table.get(&node).ok_or_else(|| missing(node))?;
                for d in 0..dim {
                    p[d] = (1.0 - f) * p[d] + f * target[d];
                }
            }
            Motion::Positions(PositionSource::Given(table)) => {
                let target = table.get(&node).ok_or_else(|| missing(node))?;
                p.copy_from_slice(&target[..dim]);
            }
            Motion::Positions(PositionSource::PerStep(_)) => {
                if clock.step > 0 {
                    let target = frame.positions.get(&node).ok_or_else(|| missing(node))?;
                    p.copy_from_slice(&target[..dim]);
                }
            }
        }
        Ok(())
    }
}

impl PositionSource {
    /// Final positions from one positions file (SU2 surface format or CSV,
    /// 0-based node indices), each checked against a mesh of `nodes` nodes.
    pub fn from_file(path: &std::path::Path, nodes: usize, dim: usize) -> Result<PositionSource> {
        let table = positions::read(path, dim)?;
        table.check_against(nodes, path)?;
        Ok(final_positions(&table))
    }

    /// [`PositionSource::from_file`] for the nodes of `groups` of `mesh`,
    /// numbered as `numbering` says (a whole mesh, or one process's part):
    /// a line naming a node on none of them is an error (of the process
    /// that owns the node).
    pub fn for_groups(
        path: &std::path::Path,
        mesh: &crate::mesh::Mesh,
        groups: &[String],
        numbering: &Numbering,
    ) -> Result<PositionSource> {
        let table = positions::read(path, mesh.dim)?;
        table.check_against(numbering.total.unwrap_or(mesh.node_count()), path)?;
        let mut on = vec![false; mesh.node_count()];
        for g in groups {
            for i in mesh.group(g)?.nodes() {
                on[i] = true;
            }
        }
        let local: HashMap<u64, usize> = numbering
            .global
            .iter()
            .enumerate()
            .filter(|&(i, _)| numbering.owned.get(i).copied().unwrap_or(true))
            .map(|(i, &g)| (g, i))
            .collect();
        let at = |id: usize| match numbering.global.is_empty() {
            true => Some(on.get(id).copied().unwrap_or(false)),
            false => local.get(&(id as u64)).map(|&i| on[i]),
        };
        table.check_on(at, &groups.join(", "), path)?;
        Ok(final_positions(&table))
    }
}

/// How the nodes a process holds are numbered in a positions file: the
/// global number of each local node (empty: its index), whether this
/// process owns it (empty: every one) and the whole mesh's node count
/// (`None`: the local count). [`Numbering::default`] is a whole mesh.
#[derive(Debug, Clone, Default)]
pub struct Numbering {
    /// The global number of each local node.
    pub global: Vec<u64>,
    /// Whether this process owns each local node.
    pub owned: Vec<bool>,
    /// The whole mesh's node count.
    pub total: Option<usize>,
}

/// The final positions of a read positions file.
fn final_positions(table: &positions::Positions) -> PositionSource {
    PositionSource::Final(
        (0..table.len())
            .map(|k| (table.ids[k], table.point(k).to_vec()))
            .collect(),
    )
}

fn missing(node: usize) -> Error {
    Error::InvalidSetting(format!(
        "the positions give no position for node index {node} of a moving group"
    ))
}

fn unit_or_z(axis: &[f64; 3], dim: usize) -> [f64; 3] {
    if dim == 2 {
        return [0.0, 0.0, if axis[2] < 0.0 { -1.0 } else { 1.0 }];
    }
    unit(axis, "the rotation axis").unwrap_or([0.0, 0.0, 1.0])
}

#[cfg(test)]
mod tests;
