//! The distributed VerBSS sweep.
//!
//! Every rank holds the rows `K_ii u_i = Σ_j B_ij u_j` of its own unknown
//! nodes (assembled from its [`Part`], identical to the single-process rows)
//! and sweeps them colour by colour:
//!
//! ```text
//! for each colour c:
//!     for each owned unknown i of colour c:  u_i ← ω K_ii⁻¹ (c_i + Σ_j B_ij u_j) + (1 − ω) u_i
//!     send the new u_i to the ranks holding them as ghosts; receive the ghosts of colour c
//! ```
//!
//! Nodes of one colour never share a cell, so within a colour the order does
//! not matter, and with the same colours as the single-process engine every
//! rank computes the same numbers as it does: the iterates are those of one
//! process, bit for bit. Only the eq.-8 value (the mean absolute change of
//! a sweep, paper eq. 8) is a sum over ranks (an all-reduce), whose rounding
//! can differ in the last bits from the single-process sum.
//!
//! Sliding nodes are solved in their frame as in [`verbss::solve`]:
//! `Tᵀ K_ii T a = Tᵀ (Σ_j B_ij u_j − K_ii f)`, `f` the given part.

use std::time::Instant;

use verbss::geometry::{ldlt_factor, morton_keys, packed_len, point};
use verbss::solve::verify::{block_estimate, check, heights};
use verbss::solve::{
    coupled, relax, unit_directions, Accel, Frames, Method, NodeRole, SolveInfo, SolveParams,
    Stage, ERROR_FRACTION,
};
use verbss::springs::{self, CellTags, Connectivity, NodeBlocks, Springs};
use verbss::topology;
use verbss::{CompactCells, Error, Result};

use crate::halo::{swap, Halo};
use crate::part::Part;
use crate::Comm;

mod gmres;

/// A rank's solver: its [`Part`], the roles of its nodes, the ghost
/// exchange lists and, once built, its rows of the spring system.
pub struct Sweeper<'c> {
    comm: &'c Comm,
    part: Part,
    conn: Connectivity,
    roles: Vec<NodeRole>,
    /// Unit plane normals (normalised as [`verbss::solve::Engine::new`] does).
    normals: Vec<[f64; 3]>,
    halo: Halo,
    built: Option<Built>,
}

/// Per neighbouring rank, a list of positions.
type Lists = Vec<Vec<u32>>;

/// The rows of one reference configuration and colouring.
struct Built {
    coords: Vec<f64>,
    colours: Vec<u32>,
    method: Method,
    /// Position → local node: owned unknowns colour by colour, then ghost unknowns.
    order: Vec<usize>,
    /// Owned colour `c` holds positions `colour_starts[c]..colour_starts[c + 1]`.
    colour_starts: Vec<usize>,
    /// Per colour and neighbour: positions sent and received after the colour.
    exchanges: Vec<(Lists, Lists)>,
    /// The frames of the sliding owned positions.
    frames: Frames,
    blocks: NodeBlocks,
    /// The unprojected `K_ii` per sliding node ([`Frames::project_diagonal`]).
    unprojected: Vec<f64>,
    /// Unknown components of all ranks.
    dofs: u64,
    /// Each owned position's local size `h_p`, the smallest height of its
    /// cells ([`heights`]).
    heights: Vec<f64>,
}

/// How [`Sweeper::sweeps`] ended.
enum Swept {
    /// Converged, and trusted under escalation.
    Accepted,
    /// The sweep limit came first.
    Exhausted,
    /// The eq.-8 value grew a million-fold over the first sweep's (or is
    /// not finite).
    Diverged { value: f64, first: f64 },
}

impl<'c> Sweeper<'c> {
    /// Prepares rank `part.rank` of `comm`: `roles` per local node (the same
    /// on every rank that holds the node), `normals` for
    /// [`NodeRole::Slide`] (the first `D` numbers used, normalised). Finds the
    /// ghost exchange lists (collective).
    pub fn new(
        comm: &'c Comm,
        part: Part,
        roles: Vec<NodeRole>,
        normals: &[[f64; 3]],
    ) -> Result<Sweeper<'c>> {
        let dim = part.dim;
        if roles.len() != part.node_count() {
            return Err(Error::InvalidSetting(format!(
                "{} node roles for {} local nodes",
                roles.len(),
                part.node_count()
            )));
        }
        let unit = unit_directions(dim, &roles, normals, |i| part.node_tags[i])?;
        let n = part.node_count();
        let node_cells = topology::node_cells(&part.cells, n);
        let (graph, edge_graph) = Connectivity::graphs(&part.cells, &node_cells, None);
        let conn = Connectivity {
            dim,
            graph,
            edge_graph,
            node_cells,
            cells: CompactCells::ordered(&part.cells, 0..part.cells.len()),
            node_tags: part.node_tags.clone(),
            cell_tags: CellTags::ordered(&part.cell_tags, 0..part.cells.len()),
            stiffness: Vec::new(),
            locality: morton_keys(dim, &part.coords),
        };
        let halo = Halo::new(comm, &part.global, &part.owner);
        Ok(Sweeper {
            comm,
            part,
            conn,
            roles,
            normals: unit,
            halo,
            built: None,
        })
    }

    /// The rank's part.
    pub fn part(&self) -> &Part {
        &self.part
    }

    /// The role of each local node.
    pub fn roles(&self) -> &[NodeRole] {
        &self.roles
    }

    /// Sets per-local-node spring stiffness factors (as
    /// [`verbss::solve::Engine::set_stiffness`]; empty: all 1); the rows are
    /// rebuilt at the next solve.
    pub fn set_stiffness(&mut self, factors: Vec<f64>) {
        self.conn.stiffness = factors;
        self.built = None;
    }

    /// The ghost exchange lists.
    pub fn halo(&self) -> &Halo {
        &self.halo
    }

    /// Copies the owners' values of every ghost (`width` numbers per local
    /// node) into `data` (collective).
    pub fn exchange(&self, data: &mut [f64], width: usize) {
        self.halo.exchange(self.comm, data, width);
    }

    /// One solve on local reference coordinates `coords` (`D` per local
    /// node) with `colours` (per local node: the colour of an unknown node,
    /// the same on every rank holding it; anything for a prescribed one).
    /// `displacement` (`D` per local node) holds the prescribed values and
    /// the initial guess of the owned nodes on entry (ghosts are taken from
    /// their owners), the solution of all local nodes on return. Collective;
    /// the springs are rebuilt only when `coords`, `colours` or the method
    /// changed. Settings as [`verbss::solve::Engine::solve`]; only the sweeps of
    /// [`Method::Verbss`] and [`Method::Spring`] without acceleration are
    /// distributed.
    pub fn solve(
        &mut self,
        coords: &[f64],
        colours: &[u32],
        displacement: &mut [f64],
        params: &SolveParams,
    ) -> Result<SolveInfo> {
        self.solve_with(coords, colours, displacement, params, false)
    }

    /// [`Sweeper::solve`] to round-off, from the guess in `displacement`:
    /// GMRES preconditioned by the sweep until the residual is [`verbss::solve::ROUND_OFF`]
    /// of the largest prescribed displacement, at most
    /// `EXACT_ITERATIONS` (1,600) (the iterative stage of
    /// [`verbss::solve::Engine::solve_exact`]).
    /// What a converged step that inverts a cell is solved with again
    /// before the inversion is judged: an inversion is never the solver's
    /// fault. `converged` says whether it got there (collective).
    pub fn solve_exact(
        &mut self,
        coords: &[f64],
        colours: &[u32],
        displacement: &mut [f64],
        params: &SolveParams,
    ) -> Result<SolveInfo> {
        self.solve_with(coords, colours, displacement, params, true)
    }

    /// [`Sweeper::solve`], or [`Sweeper::solve_exact`] when `exact`.
    fn solve_with(
        &mut self,
        coords: &[f64],
        colours: &[u32],
        displacement: &mut [f64],
        params: &SolveParams,
        exact: bool,
    ) -> Result<SolveInfo> {
        let start = Instant::now();
        self.check(coords, colours, displacement, params)?;
        let reuse = self.built.as_ref().is_some_and(|b| {
            b.method == params.method && b.coords == coords && b.colours == colours
        });
        let rebuilt = if reuse {
            Ok(())
        } else {
            self.built = None;
            match self.part.dim {
                2 => self.build::<2>(coords, colours, params.method),
                _ => self.build::<3>(coords, colours, params.method),
            }
            .map(|b| self.built = Some(b))
        };
        // A rank whose rows failed must not leave the others waiting.
        let failed = self.any(rebuilt.is_err());
        rebuilt?;
        if failed {
            return Err(Error::InvalidMesh(
                "another rank could not assemble its rows (see its message)".into(),
            ));
        }
        let form_seconds = start.elapsed().as_secs_f64();
        let solving = Instant::now();
        self.halo.exchange(self.comm, displacement, self.part.dim);
        let mut info = match self.part.dim {
            2 => self.run::<2>(displacement, params, exact),
            _ => self.run::<3>(displacement, params, exact),
        }?;
        info.form_seconds = form_seconds;
        info.solve_seconds = solving.elapsed().as_secs_f64();
        info.seconds = start.elapsed().as_secs_f64();
        info.rebuilt = !reuse;
        Ok(info)
    }

    /// Whether `flag` is set on any rank (collective).
    fn any(&self, flag: bool) -> bool {
        self.comm.max(u8::from(flag)) != 0
    }

    /// Validates the arrays and settings of [`Sweeper::solve`].
    fn check(
        &self,
        coords: &[f64],
        colours: &[u32],
        displacement: &[f64],
        params: &SolveParams,
    ) -> Result<()> {
        let dim = self.part.dim;
        let n = self.part.node_count();
        if coords.len() != dim * n || displacement.len() != dim * n || colours.len() != n {
            return Err(Error::InvalidSetting(format!(
                "{} coordinates, {} displacements and {} colours for {n} local nodes in {dim}D",
                coords.len(),
                displacement.len(),
                colours.len()
            )));
        }
        Self::supports(params)?;
        params.validate()
    }

    /// Whether the distributed sweeps can solve with `params`: the sweeps of
    /// the methods verbss and spring (the robust preset's is verbss), with
    /// accel none or auto (the robust preset's: the multigrid it would hand
    /// a slow step to is not distributed, so on ranks it means the sweeps).
    pub fn supports(params: &SolveParams) -> Result<()> {
        if !matches!(params.method, Method::Verbss | Method::Spring) || params.accel == Accel::Amg {
            return Err(Error::InvalidSetting(format!(
                "verbss-mpi distributes the solve of its sweeper, which runs --method robust, \
                 verbss or spring with --accel none or auto (got method {}, accel {})",
                params.method, params.accel
            )));
        }
        Ok(())
    }

    /// Numbers the unknowns, assembles and factors the owned rows and lists
    /// the exchanges of each colour.
    fn build<const D: usize>(
        &self,
        coords: &[f64],
        colours: &[u32],
        method: Method,
    ) -> Result<Built> {
        let part = &self.part;
        let n = part.node_count();
        let unknown = |i: usize| self.roles[i] != NodeRole::Fixed;
        let mut order: Vec<usize> = (0..n).filter(|&i| part.owns(i) && unknown(i)).collect();
        order.sort_by_key(|&i| (colours[i], part.global[i]));
        let owned = order.len();
        order.extend((0..n).filter(|&i| !part.owns(i) && unknown(i)));
        let local_colours = order.iter().map(|&i| colours[i] + 1).max().unwrap_or(0);
        let count = self.comm.max(local_colours) as usize;
        let mut colour_starts = vec![0usize; count + 1];
        for &i in &order[..owned] {
            colour_starts[colours[i] as usize + 1] += 1;
        }
        for c in 0..count {
            colour_starts[c + 1] += colour_starts[c];
        }
        let mut position = vec![u32::MAX; n];
        for (p, &i) in order.iter().enumerate() {
            position[i] = p as u32;
        }
        let mut exchanges = vec![(Vec::new(), Vec::new()); count];
        for (send, recv) in &mut exchanges {
            *send = vec![Vec::new(); self.halo.ranks.len()];
            *recv = vec![Vec::new(); self.halo.ranks.len()];
        }
        for k in 0..self.halo.ranks.len() {
            for &i in &self.halo.send[k] {
                if unknown(i as usize) {
                    exchanges[colours[i as usize] as usize].0[k].push(position[i as usize]);
                }
            }
            for &i in &self.halo.recv[k] {
                if unknown(i as usize) {
                    exchanges[colours[i as usize] as usize].1[k].push(position[i as usize]);
                }
            }
        }
        let frames = Frames::new::<D>(order[..owned].iter().map(|&i| self.roles[i]), &self.normals);
        let dofs = frames.unknowns::<D>() as u64;
        let total = self.comm.sum(dofs);
        let kind = if method == Method::Spring {
            Springs::Edge
        } else {
            Springs::BallVertex
        };
        let mut blocks = springs::assemble(&self.conn, coords, &order[..owned], &position, kind)?;
        let heights = heights::<D>(&self.conn, coords, &order[..owned]);
        let unprojected = frames.project_diagonal::<D>(&mut blocks.diag);
        self.factor_diag::<D>(&mut blocks, &order)?;
        Ok(Built {
            coords: coords.to_vec(),
            colours: colours.to_vec(),
            method,
            order,
            colour_starts,
            exchanges,
            frames,
            blocks,
            unprojected,
            dofs: total,
            heights,
        })
    }

    /// Factors every (projected) diagonal block as LDLᵀ.
    fn factor_diag<const D: usize>(&self, blocks: &mut NodeBlocks, order: &[usize]) -> Result<()> {
        let s = packed_len(D);
        for (p, diag) in blocks.diag.chunks_exact_mut(s).enumerate() {
            let a = diag.to_vec();
            if !ldlt_factor::<D>(&a, diag) {
                return Err(Error::InvalidMesh(format!(
                    "node {}: its springs do not hold it in every direction \
                     (singular stiffness block)",
                    self.part.node_tags[order[p]]
                )));
            }
        }
        Ok(())
    }

    /// Right-hand side, sweeps until the eq.-8 test, solution back into
    /// `displacement`.
    fn run<const D: usize>(
        &self,
        displacement: &mut [f64],
        params: &SolveParams,
        exact: bool,
    ) -> Result<SolveInfo> {
        let b = self.built.as_ref().expect("built before the run");
        let owned = b.frames.len();
        let mut scale = 0.0f64;
        for &i in b.order[..owned].iter().chain(self.fixed_owned().iter()) {
            let given = self.roles[i].prescribed::<D>(&self.normals, &point::<D>(displacement, i));
            scale = scale.max(given.iter().map(|v| v * v).sum::<f64>().sqrt());
        }
        let global_scale = self.comm.max(scale);
        let threshold = params.threshold(global_scale, exact);
        let mut work = vec![0.0; D * b.order.len()];
        for (p, &i) in b.order.iter().enumerate() {
            work[D * p..D * (p + 1)].copy_from_slice(&displacement[D * i..D * (i + 1)]);
        }
        let constant = self.constants::<D>(b, displacement);
        let mut info = SolveInfo::default();
        if b.dofs == 0 {
            info.converged = true;
            return Ok(info);
        }
        if exact {
            info.stages.push(Stage::Gmres);
            let outcome = self.gmres::<D>(b, &constant, &mut work, threshold, true);
            info.iterations = outcome.iterations;
            info.residual = outcome.estimate;
            if outcome.converged && !outcome.diverged {
                self.verify::<D>(b, &constant, &work, &mut info);
                info.converged = info.error_ratio <= ERROR_FRACTION;
            }
            self.scatter::<D>(b, &work, displacement);
            return Ok(info);
        }
        // Under escalation a stage that diverges or runs out of sweeps is
        // followed by GMRES preconditioned by the sweep (Stage::Gmres), then
        // by sweeps with ω = 1 (Stage::SafeSweeps): each from the initial
        // guess after a divergence, from the last iterate otherwise.
        let initial = work.clone();
        info.stages.push(Stage::Sweeps);
        let swept = self.sweeps::<D>(
            b,
            &constant,
            &mut work,
            params.omega,
            threshold,
            params,
            &mut info,
        );
        match swept {
            Swept::Accepted => info.converged = true,
            Swept::Exhausted => {}
            Swept::Diverged { value, first } => {
                if !params.escalate {
                    return Err(Error::InvalidSetting(format!(
                        "the sweeps diverged (eq.-8 value {value:.3e} at sweep {}, \
                         {first:.3e} at the first); omega {} is too large for this mesh",
                        info.iterations, params.omega
                    )));
                }
                info.diverged = true;
                work.copy_from_slice(&initial);
            }
        }
        if !info.converged && params.escalate {
            info.stages.push(Stage::Gmres);
            let outcome = self.gmres::<D>(b, &constant, &mut work, threshold, false);
            info.iterations += outcome.iterations;
            info.residual = outcome.estimate;
            if outcome.diverged {
                info.diverged = true;
                work.copy_from_slice(&initial);
            } else if outcome.converged {
                self.verify::<D>(b, &constant, &work, &mut info);
                info.converged = info.error_ratio <= ERROR_FRACTION;
            }
        }
        if !info.converged && params.escalate {
            info.stages.push(Stage::SafeSweeps);
            match self.sweeps::<D>(b, &constant, &mut work, 1.0, threshold, params, &mut info) {
                Swept::Accepted => info.converged = true,
                Swept::Exhausted => {}
                Swept::Diverged { .. } => {
                    info.diverged = true;
                    work.copy_from_slice(&initial);
                }
            }
        }
        if !info.converged {
            // What the failed solve left, for the message that names it.
            self.verify::<D>(b, &constant, &work, &mut info);
        }
        self.scatter::<D>(b, &work, displacement);
        Ok(info)
    }

    /// The positions' values `work` back into the local nodes' `displacement`.
    fn scatter<const D: usize>(&self, b: &Built, work: &[f64], displacement: &mut [f64]) {
        for (p, &i) in b.order.iter().enumerate() {
            displacement[D * i..D * (i + 1)].copy_from_slice(&work[D * p..D * (p + 1)]);
        }
    }

    /// Sweeps of `work` with `omega` until the eq.-8 value falls below
    /// `threshold` and, under escalation, every node's estimated error is
    /// within [`ERROR_FRACTION`] of its cell height (the eq.-8 stop is not
    /// the error, docs/method.md, "Accepting a step": the threshold is cut
    /// tenfold until it is), at most `params.max_iterations` sweeps
    /// (collective: every rank decides alike on all-reduced values).
    #[allow(clippy::too_many_arguments)]
    fn sweeps<const D: usize>(
        &self,
        b: &Built,
        constant: &[f64],
        work: &mut [f64],
        omega: f64,
        mut threshold: f64,
        params: &SolveParams,
        info: &mut SolveInfo,
    ) -> Swept {
        let mut first = None;
        for _ in 0..params.max_iterations {
            let mut local = 0.0;
            for c in 0..b.colour_starts.len() - 1 {
                for p in b.colour_starts[c]..b.colour_starts[c + 1] {
                    let (value, change) = self.update::<D>(b, constant, omega, p, work);
                    work[D * p..D * (p + 1)].copy_from_slice(&value);
                    local += change;
                }
                let (send, recv) = &b.exchanges[c];
                swap(self.comm, &self.halo.ranks, send, recv, work, D);
            }
            let value = self.comm.sum(local) / b.dofs as f64;
            info.iterations += 1;
            info.residual = value;
            if params.record_history {
                info.history.push(value);
            }
            let first = *first.get_or_insert(value);
            if !value.is_finite() || value > 1e6 * first {
                return Swept::Diverged { value, first };
            }
            if value < threshold {
                if !params.escalate {
                    return Swept::Accepted;
                }
                self.verify::<D>(b, constant, work, info);
                if info.error_ratio <= ERROR_FRACTION {
                    return Swept::Accepted;
                }
                threshold /= 10.0;
            }
        }
        Swept::Exhausted
    }

    /// Fills `info`'s error ratio `max_p |e_p| / h_p` over every rank's owned
    /// unknowns (collective): the single process's [`check`] with its
    /// [`block_estimate`], the Jacobi step that puts position `p` where its
    /// springs hold it given its neighbours, over `h_p` its local size; the
    /// root-mean-square true residual over them; and the worst node, a
    /// local node on the lowest rank holding the largest ratio
    /// (`usize::MAX` on the others).
    fn verify<const D: usize>(
        &self,
        b: &Built,
        constant: &[f64],
        work: &[f64],
        info: &mut SolveInfo,
    ) {
        let local = check::<D, _>(work, &b.heights, |p, w| {
            let rhs = coupled::<D>(&b.blocks, constant, p, w);
            let factor = &b.blocks.diag[packed_len(D) * p..packed_len(D) * (p + 1)];
            block_estimate::<D>(factor, &rhs, &point::<D>(w, p), b.frames.get::<D>(p))
        });
        // The root-mean-square over every rank's unknowns.
        let m = b.heights.len() as f64;
        let sums = self
            .comm
            .sums(&[local.true_residual * local.true_residual * m, m]);
        info.true_residual = (sums[0] / sums[1].max(1.0)).sqrt();
        info.error_ratio = self.comm.max(local.error_ratio);
        let holder = if m > 0.0 && local.error_ratio == info.error_ratio {
            f64::from(self.comm.rank())
        } else {
            f64::INFINITY
        };
        let lowest = -self.comm.max(-holder);
        info.worst_node = if holder == lowest {
            b.order[local.worst]
        } else {
            usize::MAX
        };
    }

    /// The owned prescribed nodes.
    fn fixed_owned(&self) -> Vec<usize> {
        (0..self.part.node_count())
            .filter(|&i| self.part.owns(i) && self.roles[i] == NodeRole::Fixed)
            .collect()
    }

    /// `c_p = Σ_{j prescribed} B_pj u_j`, minus `K_pp f` for a sliding node
    /// with given part `f`.
    fn constants<const D: usize>(&self, b: &Built, displacement: &[f64]) -> Vec<f64> {
        let owned = b.frames.len();
        let mut constant = vec![0.0; D * owned];
        for p in 0..owned {
            let mut c = b.blocks.prescribed_pull::<D>(p, displacement);
            let u = point::<D>(displacement, b.order[p]);
            if let Some(kf) = b.frames.given_pull::<D>(&b.unprojected, p, &u) {
                for k in 0..D {
                    c[k] -= kf[k];
                }
            }
            constant[D * p..D * (p + 1)].copy_from_slice(&c);
        }
        constant
    }

    /// Position `p`'s relaxed block solution and the sum of the absolute
    /// changes of its unknown components (paper eq. 13).
    #[inline]
    fn update<const D: usize>(
        &self,
        b: &Built,
        constant: &[f64],
        omega: f64,
        p: usize,
        work: &[f64],
    ) -> ([f64; D], f64) {
        relax::<D>(
            &b.blocks.diag[packed_len(D) * p..],
            &coupled::<D>(&b.blocks, constant, p, work),
            &point::<D>(work, p),
            b.frames.get::<D>(p),
            omega,
        )
    }
}
