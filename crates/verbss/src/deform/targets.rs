//! Where the prescribed nodes are at a step: the moving nodes where their
//! bodies' motions put them, the rigid-layer nodes with their bodies.
//!
//! A layer node follows its body's motion evaluated at the node itself
//! where the motion is a field (exactly rigid for a rigid body), and the
//! displacement of its nearest node of the body where the body moves by
//! given positions (carried along the wall normal). That nearest node may
//! be another process's: then every step gathers the displacements of the
//! nodes some layer node follows ([`Anchors`]).

use std::collections::HashMap;

use rayon::prelude::*;

use super::roles::Plan;
use super::Deformer;
use crate::collective::{agree, Collective};
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use crate::motion::Clock;
use crate::near_wall::Follows;
use crate::solve::{NodeRole, SpringSolver};

/// The body nodes that layer nodes follow by their displacement, when some
/// process holds a layer node whose nearest body node it does not hold:
/// their tags, over every process, in increasing order.
pub(super) struct Anchors {
    shared: Option<Vec<u64>>,
}

impl Anchors {
    /// The anchors of the `layer` nodes of the local `mesh` planned by
    /// `plan` (collective).
    pub(super) fn new(
        mesh: &Mesh,
        plan: &Plan,
        layer: &[(usize, Follows, NodeRole)],
        on: &dyn Collective,
    ) -> Anchors {
        let needed: Vec<u64> = layer
            .iter()
            .filter_map(|(_, body, _)| body.map(|(_, tag)| tag))
            .collect();
        let held: std::collections::HashSet<u64> = plan
            .moving
            .iter()
            .map(|&(i, _)| mesh.node_tags[i])
            .collect();
        let mut missing = [f64::from(u8::from(
            needed.iter().any(|t| !held.contains(t)),
        ))];
        on.max(&mut missing);
        if missing[0] == 0.0 {
            return Anchors { shared: None };
        }
        let wanted: Vec<f64> = needed.iter().map(|&t| t as f64).collect();
        let mut all: Vec<u64> = on.gather(&wanted).into_iter().map(|t| t as u64).collect();
        all.sort_unstable();
        all.dedup();
        Anchors { shared: Some(all) }
    }
}

impl<S: SpringSolver, C: Collective> Deformer<S, C> {
    /// Where the prescribed nodes (moving and rigid-layer) are at step `n`
    /// (collective).
    pub fn targets(&self, n: usize) -> Result<Vec<(usize, Vec<f64>)>> {
        agree(&self.on, self.local_targets(n))
    }

    /// [`Deformer::targets`] of this process.
    fn local_targets(&self, n: usize) -> Result<Vec<(usize, Vec<f64>)>> {
        let clock = Clock {
            step: n,
            steps: self.settings.steps,
            dt: self.settings.dt,
        };
        let dim = self.mesh.dim;
        let frames = self
            .motions
            .iter()
            .map(|m| m.frame(clock, self.size.0, dim))
            .collect::<Result<Vec<_>>>()?;
        // Each node on its own, on the workers (the fields they read, not
        // the deformer, which may not be shared between threads); the first
        // failing node's error, in order.
        let (mesh, global, motions, bodies) =
            (&*self.mesh, &self.global, &self.motions, &self.bodies);
        let (normals, current) = (&self.normals, &self.current.coords);
        let (moving, layer, workers) = (&self.moving, &self.layer, &self.workers);
        // The global number of local node `i`: a positions file's node id.
        let global_of = |i: usize| global.get(i).map_or(i, |&g| g as usize);
        let moved: Vec<Result<(usize, Vec<f64>)>> = workers.install(|| {
            moving
                .par_iter()
                .map(|&(node, b)| {
                    let mut p = mesh.point(node).to_vec();
                    for &m in &bodies[b] {
                        motions[m].apply(global_of(node), &mut p, clock, &frames[m])?;
                    }
                    within_bounds(mesh, n, node, p)
                })
                .collect()
        });
        let mut targets = moved.into_iter().collect::<Result<Vec<_>>>()?;
        let is_field = |b: usize| bodies[b].iter().all(|&m| motions[m].is_field());
        let displaced = (0..bodies.len())
            .any(|b| !is_field(b))
            .then(|| self.anchor_displacements(&targets));
        let layer: Vec<Result<(usize, Vec<f64>)>> = workers.install(|| {
            layer
                .par_iter()
                .map(|&(node, body, role)| {
                    let mut p = mesh.point(node).to_vec();
                    match body {
                        Some((b, _)) if is_field(b) => {
                            for &m in &bodies[b] {
                                motions[m].apply(global_of(node), &mut p, clock, &frames[m])?;
                            }
                        }
                        Some((_, tag)) => {
                            if let Some(d) = displaced.as_ref().and_then(|map| map.get(&tag)) {
                                for (x, dx) in p.iter_mut().zip(d) {
                                    *x += dx;
                                }
                            }
                        }
                        None => {}
                    }
                    role.keep_on(normals, &mut p, &current[dim * node..dim * (node + 1)]);
                    within_bounds(mesh, n, node, p)
                })
                .collect()
        });
        for target in layer {
            targets.push(target?);
        }
        Ok(targets)
    }

    /// The displacement at this step of every moving node a layer node
    /// follows, by tag: this process's, and where [`Anchors`] says so every
    /// process's owned ones (collective).
    fn anchor_displacements(&self, targets: &[(usize, Vec<f64>)]) -> HashMap<u64, Vec<f64>> {
        let dim = self.mesh.dim;
        let displacement = |(node, p): &(usize, Vec<f64>)| -> Vec<f64> {
            let x = self.mesh.point(*node);
            p.iter().zip(x).map(|(a, b)| a - b).collect()
        };
        let moving = &targets[..self.moving.len()];
        let mut map: HashMap<u64, Vec<f64>> = moving
            .iter()
            .map(|t| (self.mesh.node_tags[t.0], displacement(t)))
            .collect();
        if let Some(shared) = &self.anchors.shared {
            let mine: Vec<f64> = moving
                .iter()
                .filter(|(node, _)| self.on.owns(*node))
                .filter(|(node, _)| shared.binary_search(&self.mesh.node_tags[*node]).is_ok())
                .flat_map(|t| {
                    let mut row = vec![self.mesh.node_tags[t.0] as f64];
                    row.extend(displacement(t));
                    row
                })
                .collect();
            for row in self.on.gather(&mine).chunks_exact(1 + dim) {
                map.insert(row[0] as u64, row[1..].to_vec());
            }
        }
        map
    }
}

/// The target `p` of `node` of `mesh` at step `n`, refused unless every
/// coordinate is finite and within ±1e100 (beyond it the springs'
/// products overflow): a motion whose numbers are too large or too
/// small (an infinite angle, a speed of 1e308, a wavelength of 1e-320,
/// a displacement of 1e308 given to a binding) never reaches a solve,
/// a message or a file as NaN.
fn within_bounds(mesh: &Mesh, n: usize, node: usize, p: Vec<f64>) -> Result<(usize, Vec<f64>)> {
    if p.iter().all(|x| x.abs() <= crate::motion::MAX_COORDINATE) {
        return Ok((node, p));
    }
    Err(Error::InvalidSetting(format!(
        "step {n}: the motion moves node {} to {}, not a finite position within ±1e100 \
         (check the motion's numbers: angles, speeds, wavelengths, displacements)",
        mesh.node_tags[node],
        crate::error::format_point(&p)
    )))
}
