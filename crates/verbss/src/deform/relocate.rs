//! Quality-driven relocation of the nodes of the worst cells
//! (docs/method.md, "Relocation of the worst cells' nodes").
//!
//! The springs spread a boundary's motion smoothly; where a small body
//! moves far compared with its size (a wing tip carried 0.8 span-units
//! up and turned 39°), the cells at the edge of its rigid layer take a
//! shear that the next step, built on them, keeps: step by step they
//! flatten. After the springs, every free or sliding node that is a corner
//! of a cell that kept less than [`BELOW`] of its input quality `q⁰_c` is
//! moved to raise the least ratio of its cells,
//!
//! `r_i(x) = min_{c ∋ i} q_c(x) / q⁰_c`,
//!
//! by a compass search (the `2·dim` axis directions and the direction to
//! its neighbours' centroid, the step halved when none gains, from a fifth
//! of its mean distance to them), a sliding node kept on its plane or line. A move
//! is kept only where it raises `r_i`. A cell keeps its input shape as far
//! as it can — a boundary-layer cell is not made isotropic.
//!
//! Nodes move in up to 3 passes (each finds the poor cells again) of up
//! to 8 rounds, each an independent set: a candidate moves when
//! its priority (a hash of its number in the file, the same on every
//! process and in any node order) is below that of every other
//! candidate of its cells, so no two nodes of a round share a cell. A
//! round's moves change disjoint cells: the mesh's least ratio never
//! falls, and the result is the same on any number of threads or processes.

use rayon::prelude::*;

use crate::collective::Collective;
use crate::mesh::Mesh;
use crate::quality;
use crate::solve::NodeRole;
use crate::threads::Workers;
use crate::topology::{self, Csr};

/// A cell below this fraction of its input quality has its nodes relocated.
pub const BELOW: f64 = 0.5;

/// Passes per (sub-)step: each finds the poor cells again and moves their
/// nodes in rounds.
const PASSES: usize = 3;

/// Rounds of independent sets per pass.
const ROUNDS: usize = 8;

/// Compass-search iterations per node.
const ITERATIONS: usize = 20;

/// The relocation's fixed data: each node's cells and each cell's input quality.
pub(super) struct Relocation {
    node_cells: Csr,
    input_quality: Vec<f64>,
}

impl Relocation {
    /// For `mesh` (a process's local cells) whose cells have the qualities
    /// `input_quality`.
    pub(super) fn new(mesh: &Mesh, input_quality: Vec<f64>) -> Relocation {
        Relocation {
            node_cells: topology::node_cells(&mesh.cells, mesh.node_count()),
            input_quality,
        }
    }

    /// Relocates the nodes of the cells of `coords` below [`BELOW`] of their
    /// input quality (see the module documentation); `ids` the nodes'
    /// numbers in the file (empty: their indices), `roles` and `normals` the
    /// deformer's, over the processes `on` (collective), the cells and
    /// nodes on `workers`. Returns how many nodes moved on every process
    /// together.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn apply(
        &self,
        mesh: &Mesh,
        coords: &mut [f64],
        orientation: &[i8],
        roles: &[NodeRole],
        normals: &[[f64; 3]],
        ids: &[u64],
        on: &dyn Collective,
        workers: &Workers,
    ) -> usize {
        let priority: Vec<u64> = (0..roles.len())
            .map(|i| mix(ids.get(i).copied().unwrap_or(i as u64)))
            .collect();
        let mut moved = 0;
        for _ in 0..PASSES {
            let mut candidate = self.candidates(mesh, coords, orientation, roles, on, workers);
            let mut left = [candidate.iter().sum::<f64>()];
            on.max(&mut left);
            if left[0] == 0.0 {
                break;
            }
            for _ in 0..ROUNDS {
                let chosen = self.independent(mesh, &candidate, &priority, on);
                let frozen: &[f64] = coords;
                let places: Vec<Option<Vec<f64>>> = workers.install(|| {
                    chosen
                        .par_iter()
                        .map(|&i| self.best_place(mesh, frozen, orientation, roles[i], normals, i))
                        .collect()
                });
                for (&i, place) in chosen.iter().zip(places) {
                    candidate[i] = 0.0;
                    if let Some(p) = place {
                        coords[mesh.dim * i..mesh.dim * (i + 1)].copy_from_slice(&p);
                        moved += 1;
                    }
                }
                on.refresh(coords, mesh.dim);
                on.refresh(&mut candidate, 1);
                let mut left = [candidate.iter().sum::<f64>()];
                on.max(&mut left);
                if left[0] == 0.0 {
                    break;
                }
            }
        }
        let mut moved = [moved as f64];
        on.sum(&mut moved);
        moved[0] as usize
    }

    /// 1 for every free or sliding node of a cell of `coords` below
    /// [`BELOW`] of its input quality, 0 for the others, every process's
    /// own nodes' flags on its ghosts (collective).
    fn candidates(
        &self,
        mesh: &Mesh,
        coords: &[f64],
        orientation: &[i8],
        roles: &[NodeRole],
        on: &dyn Collective,
        workers: &Workers,
    ) -> Vec<f64> {
        let q = workers.install(|| quality::qualities(mesh, coords, orientation));
        let poor: Vec<bool> = q
            .iter()
            .zip(&self.input_quality)
            .map(|(&q, &q0)| q < BELOW * q0)
            .collect();
        let mut candidate: Vec<f64> = (0..roles.len())
            .map(|i| {
                let movable = roles[i] != NodeRole::Fixed && on.owns(i);
                let near_poor = self.node_cells.entries(i).any(|c| poor[c]);
                f64::from(u8::from(movable && near_poor))
            })
            .collect();
        on.refresh(&mut candidate, 1);
        candidate
    }

    /// The own candidates whose priority is below that of every other
    /// candidate of their cells: no two of them share a cell.
    fn independent(
        &self,
        mesh: &Mesh,
        candidate: &[f64],
        priority: &[u64],
        on: &dyn Collective,
    ) -> Vec<usize> {
        (0..candidate.len())
            .filter(|&i| candidate[i] == 1.0 && on.owns(i))
            .filter(|&i| {
                self.node_cells.entries(i).all(|c| {
                    mesh.cells
                        .cell(c)
                        .iter()
                        .all(|&j| j == i || candidate[j] == 0.0 || priority[j] > priority[i])
                })
            })
            .collect()
    }

    /// Where node `i` raises the least quality ratio of its cells most
    /// (see the module documentation), or `None` where it is best where it is.
    fn best_place(
        &self,
        mesh: &Mesh,
        coords: &[f64],
        orientation: &[i8],
        role: NodeRole,
        normals: &[[f64; 3]],
        i: usize,
    ) -> Option<Vec<f64>> {
        let dim = mesh.dim;
        let ball = Ball::of(mesh, &self.node_cells, coords, i);
        let ratio = |x: &[f64]| ball.least_ratio(mesh, x, orientation, &self.input_quality);
        let start = coords[dim * i..dim * (i + 1)].to_vec();
        let mut x = start.clone();
        let mut best = ratio(&x);
        let mut step = 0.2 * ball.mean_distance(&x);
        let mut directions: Vec<Vec<f64>> = (0..2 * dim)
            .map(|k| {
                let mut e = vec![0.0; dim];
                e[k / 2] = if k % 2 == 0 { 1.0 } else { -1.0 };
                e
            })
            .collect();
        directions.push(ball.to_centroid(&x));
        let first = best;
        for _ in 0..ITERATIONS {
            let gain = directions.iter().find_map(|e| {
                let mut y: Vec<f64> = x.iter().zip(e).map(|(a, b)| a + step * b).collect();
                role.keep_on(normals, &mut y, &start);
                let r = ratio(&y);
                (r > best).then_some((y, r))
            });
            match gain {
                Some((y, r)) => {
                    (x, best) = (y, r);
                    directions[2 * dim] = ball.to_centroid(&x);
                }
                None => step *= 0.5,
            }
        }
        (best > first).then_some(x)
    }
}

/// The cells around one node, with their nodes' coordinates copied: the
/// node itself first.
struct Ball {
    dim: usize,
    /// `dim` numbers per node, the moving node's first.
    coords: Vec<f64>,
    /// Each cell: its index in the mesh and its nodes in `coords`.
    cells: Vec<(usize, Vec<usize>)>,
}

impl Ball {
    fn of(mesh: &Mesh, node_cells: &Csr, coords: &[f64], i: usize) -> Ball {
        let dim = mesh.dim;
        let mut nodes = vec![i];
        let cells = node_cells
            .entries(i)
            .map(|c| {
                let local = mesh.cells.cell(c).iter().map(|&j| {
                    nodes.iter().position(|&k| k == j).unwrap_or_else(|| {
                        nodes.push(j);
                        nodes.len() - 1
                    })
                });
                (c, local.collect())
            })
            .collect();
        let coords = nodes
            .iter()
            .flat_map(|&j| coords[dim * j..dim * (j + 1)].iter().copied())
            .collect();
        Ball { dim, coords, cells }
    }

    /// The least `q_c / q⁰_c` over the ball's cells with the node at `x`.
    fn least_ratio(&self, mesh: &Mesh, x: &[f64], orientation: &[i8], input: &[f64]) -> f64 {
        let mut coords = self.coords.clone();
        coords[..self.dim].copy_from_slice(x);
        self.cells
            .iter()
            .map(|(c, nodes)| {
                let q = quality::quality_in(mesh, *c, nodes, &coords, orientation[*c]);
                q / input[*c].max(f64::MIN_POSITIVE)
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// The mean distance from `x` to the ball's other nodes.
    fn mean_distance(&self, x: &[f64]) -> f64 {
        let others = self.coords[self.dim..].chunks(self.dim);
        let count = others.len().max(1) as f64;
        others.map(|p| distance(p, x)).sum::<f64>() / count
    }

    /// The unit direction from `x` to the centroid of the ball's other
    /// nodes (zero when `x` is there).
    fn to_centroid(&self, x: &[f64]) -> Vec<f64> {
        let others = self.coords[self.dim..].chunks(self.dim);
        let count = others.len().max(1) as f64;
        let mut e: Vec<f64> = (0..self.dim)
            .map(|d| others.clone().map(|p| p[d]).sum::<f64>() / count - x[d])
            .collect();
        let length = e.iter().map(|v| v * v).sum::<f64>().sqrt();
        if length > 0.0 {
            e.iter_mut().for_each(|v| *v /= length);
        }
        e
    }
}

fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| (p - q).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// SplitMix64's finaliser: a node's priority from its number in the file,
/// the same on every process.
fn mix(id: u64) -> u64 {
    let mut z = id.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collective::Whole;
    use crate::mesh::samples::{jittered_grid, square_of_triangles};

    /// The mesh's cells' least ratio to their input qualities.
    fn least_ratio(mesh: &Mesh, coords: &[f64], orientation: &[i8], input: &[f64]) -> f64 {
        let q = quality::qualities(mesh, coords, orientation);
        q.iter()
            .zip(input)
            .map(|(a, b)| a / b)
            .fold(f64::INFINITY, f64::min)
    }

    /// [`Relocation::apply`] on one process with `threads` workers, no
    /// sliding node, the nodes numbered by their indices.
    fn relocated(
        relocation: &Relocation,
        mesh: &Mesh,
        coords: &mut [f64],
        orientation: &[i8],
        roles: &[NodeRole],
        threads: usize,
    ) -> usize {
        let workers = Workers::new(threads).unwrap();
        relocation.apply(mesh, coords, orientation, roles, &[], &[], &Whole, &workers)
    }

    /// Free interior nodes, fixed boundary nodes.
    fn roles(mesh: &Mesh) -> Vec<NodeRole> {
        topology::boundary_nodes(mesh)
            .into_iter()
            .map(|b| if b { NodeRole::Fixed } else { NodeRole::Free })
            .collect()
    }

    /// An interior node pushed most of the way to its neighbour flattens
    /// its cells; relocation raises their least ratio above `BELOW`, moves
    /// no prescribed node and no node more than [`PASSES`] rings of
    /// neighbours away from the pushed one.
    #[test]
    fn a_node_pushed_against_its_neighbour_is_moved_back_and_nothing_far_moves() {
        let mesh = square_of_triangles(12);
        let orientation = quality::orientation(&mesh);
        let input = quality::qualities(&mesh, &mesh.coords, &orientation);
        let relocation = Relocation::new(&mesh, input.clone());
        let roles = roles(&mesh);
        let pushed = 6 * 13 + 6;
        let mut coords = mesh.coords.clone();
        coords[2 * pushed] += 0.8 / 12.0;
        let before = least_ratio(&mesh, &coords, &orientation, &input);
        assert!(before < BELOW, "{before}");
        let pushed_coords = coords.clone();
        let moved = relocated(&relocation, &mesh, &mut coords, &orientation, &roles, 1);
        let after = least_ratio(&mesh, &coords, &orientation, &input);
        assert!(
            moved >= 1 && after > BELOW,
            "{moved} nodes moved: {before} -> {after}"
        );
        let rings = topology::bfs_layers(&topology::node_graph(&mesh.cells, 169), &[pushed]);
        for i in 0..mesh.node_count() {
            if roles[i] == NodeRole::Fixed || rings[i] as usize > PASSES {
                assert_eq!(
                    coords[2 * i..2 * i + 2],
                    pushed_coords[2 * i..2 * i + 2],
                    "node {i}"
                );
            }
        }
    }

    /// On a jittered tetrahedral grid with many poor cells, every round's
    /// moves are independent: the least ratio never falls, and the result
    /// is the same on one thread and on three.
    #[test]
    fn relocation_never_lowers_the_least_ratio_and_does_not_depend_on_the_threads() {
        let mut seed = 7u64;
        let mut jitter = move || {
            seed = mix(seed);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let mesh = jittered_grid(3, 7, 2, || 0.0).unwrap();
        let orientation = quality::orientation(&mesh);
        let input = quality::qualities(&mesh, &mesh.coords, &orientation);
        let relocation = Relocation::new(&mesh, input.clone());
        let roles = roles(&mesh);
        let mut coords = mesh.coords.clone();
        for (i, role) in roles.iter().enumerate() {
            if *role == NodeRole::Free {
                for d in 0..3 {
                    coords[3 * i + d] += 0.08 * jitter();
                }
            }
        }
        let before = least_ratio(&mesh, &coords, &orientation, &input);
        let on = |threads: usize| {
            let mut c = coords.clone();
            relocated(&relocation, &mesh, &mut c, &orientation, &roles, threads);
            c
        };
        let one = on(1);
        assert_eq!(one, on(3));
        let after = least_ratio(&mesh, &one, &orientation, &input);
        assert!(before < BELOW && after > before, "{before} -> {after}");
    }
}
