//! Smoothed-aggregation algebraic multigrid for the node-block system, with
//! the VerBSS sweep as the finest level's smoother (docs/acceleration.md).
//!
//! Setup, from the finest level down (Vaněk, Mandel & Brezina 1996):
//!
//! 1. **Strength**: block `(i, j)` is strong when
//!    `‖A_ij‖_F ≥ θ √(‖A_ii‖_F ‖A_jj‖_F)` (either way round), `θ = 0.08` on the
//!    finest level, halved on each coarser one.
//! 2. **Aggregation** (standard, three passes): a node whose strong
//!    neighbours are all free starts an aggregate with them; a node left over
//!    joins a neighbouring aggregate; what is still left forms aggregates of
//!    its own.
//! 3. **Tentative prolongator** `T`: on each aggregate, the near-null space
//!    `B` (the rigid-body modes: translations and rotations of the node
//!    coordinates, projected on the tangent plane of sliding nodes) is split
//!    `B_agg = Q R` by Gram–Schmidt; `Q` gives `T`'s rows, `R` the coarse
//!    near-null space. A mode that an aggregate cannot carry (its column
//!    vanishes) is dropped: its coarse unknown is decoupled.
//! 4. **Smoothed prolongator** `P = (I − (4/3)/ρ · D⁻¹ A) T`, `D` the block
//!    diagonal, `ρ` the spectral radius of `D⁻¹ A` by power iteration.
//! 5. **Galerkin coarse matrix** `A_c = Pᵀ A P`.
//!
//! until a level has at most [`COARSEST_UNKNOWNS`] unknowns, which is solved
//! exactly (dense LU).
//!
//! One V-cycle for `A e = r`: on the finest level one forward VerBSS sweep
//! from `e = 0` with `constant = r` (exactly the paper's node update), the
//! residual restricted by `Pᵀ`, the coarse correction (recursively) prolonged
//! by `P`, one backward VerBSS sweep; on coarser levels the same with
//! multicolour block Gauss–Seidel. The cycle is a fixed linear operator, the
//! preconditioner of [`super::gmres`].

use rayon::prelude::*;

use super::bsr::{galerkin, invert, madd_kernel, mul_kernel, Bsr, DenseLu, Transposed};
use super::{chunked_sum, Layout};
use crate::error::{Error, Result};
use crate::geometry::{ldlt_mul, packed_len, packed_mul};
use crate::springs::NodeBlocks;
use crate::topology::{self, Csr};

/// The largest block: 6 rigid-body modes in 3D.
const MAX_BLOCK: usize = 6;
/// Levels with at most this many unknowns are solved exactly.
pub(crate) const COARSEST_UNKNOWNS: usize = 300;
/// At most this many levels.
const MAX_LEVELS: usize = 12;
/// Strength threshold θ of the finest level.
const THETA: f64 = 0.08;
/// Power iterations estimating ρ(D⁻¹A).
const POWER_STEPS: usize = 40;
/// A Gram–Schmidt column shorter than this fraction of its original length is dropped.
const DROP: f64 = 1e-10;

/// The multigrid hierarchy below the finest level.
pub(crate) struct Hierarchy {
    /// The fine unknowns' order (position → node) it was built for.
    pub(crate) order: Vec<usize>,
    /// `transfers[l]` maps level `l + 1` to level `l`.
    transfers: Vec<Transfer>,
    /// Levels `1..L−1` (smoothed).
    coarse: Vec<Coarse>,
    /// Level `L`, the coarsest (the fine level itself when it is small).
    coarsest: Coarsest,
    /// Per level `1..=L`: right-hand side, correction, residual, next values.
    scratch: Vec<[Vec<f64>; 4]>,
    /// Fine level: residual after pre-smoothing, prolonged correction.
    fine: [Vec<f64>; 2],
}

/// Prolongation `P` and restriction `R = Pᵀ` (a view of `P`'s blocks)
/// between two levels.
struct Transfer {
    p: Bsr,
    r: Transposed,
}

/// A coarse level: its matrix and its Gauss–Seidel data.
struct Coarse {
    a: Bsr,
    /// Inverse of each diagonal block (`b × b`).
    inverse: Vec<f64>,
    /// Block rows of each colour.
    colours: Vec<Vec<u32>>,
}

/// How the coarsest level is solved.
enum Coarsest {
    /// Exactly, when it has at most [`DENSE_LIMIT`] unknowns.
    Exact(DenseLu),
    /// Approximately, by [`COARSEST_SWEEPS`] symmetric Gauss–Seidel sweeps,
    /// when the coarsening stalled above that size.
    Sweeps(Coarse),
}

/// The largest coarsest level factored densely.
const DENSE_LIMIT: usize = 1000;
/// Gauss–Seidel sweeps (each way) of a coarsest level too large to factor.
const COARSEST_SWEEPS: usize = 10;

impl Hierarchy {
    /// Builds the hierarchy of the fine system (factored `blocks`, `layout`)
    /// with node coordinates `coords` (`D` per mesh node) for the rigid modes.
    pub(crate) fn new<const D: usize>(
        blocks: &NodeBlocks,
        layout: &Layout,
        coords: &[f64],
    ) -> Result<Hierarchy> {
        // The fine matrix is needed to form the first coarse level only
        // (the fine level's sweeps and residuals use `blocks`).
        let mut fine = Some(fine_matrix::<D>(blocks, layout));
        let mut b = rigid_modes::<D>(layout, coords);
        let mut transfers = Vec::new();
        let mut mats: Vec<Bsr> = Vec::new();
        let mut theta = THETA;
        loop {
            let a = mats
                .last()
                .or(fine.as_ref())
                .expect("the fine or a coarse matrix");
            if a.rows * a.r <= COARSEST_UNKNOWNS || transfers.len() + 1 >= MAX_LEVELS {
                break;
            }
            let strong = strength(a, theta);
            let (aggregate, count) = aggregate(&strong);
            if count * 3 > a.rows * 2 {
                break;
            }
            let modes = b.len() / (a.rows * a.r);
            let (t, next_b, dropped) = tentative(&aggregate, count, &b, a.r, modes);
            let p = smooth_prolongator(a, &t)?;
            let r = p.transposed();
            let mut ac = galerkin(&r, a, &p);
            for &(node, k) in &dropped {
                let e = ac.find(node, node).expect("diagonal block");
                let m = ac.r;
                ac.values[m * m * e + k * m + k] = 1.0;
            }
            transfers.push(Transfer { p, r });
            mats.push(ac);
            fine = None;
            b = next_b;
            theta /= 2.0;
        }
        let last = mats.pop().or(fine).expect("the fine or a coarse matrix");
        let coarsest = if last.rows * last.r <= DENSE_LIMIT {
            Coarsest::Exact(dense_lu(&last)?)
        } else {
            Coarsest::Sweeps(Coarse::new(last)?)
        };
        let coarse = mats
            .into_iter()
            .map(Coarse::new)
            .collect::<Result<Vec<_>>>()?;
        let scratch = transfers
            .iter()
            .map(|t| {
                let n = t.p.cols * t.p.c;
                [vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]]
            })
            .collect();
        let n = layout.order.len() * D;
        Ok(Hierarchy {
            order: layout.order.clone(),
            transfers,
            coarse,
            coarsest,
            scratch,
            fine: [vec![0.0; n], vec![0.0; n]],
        })
    }

    /// Number of levels, the finest included.
    pub(crate) fn levels(&self) -> usize {
        self.transfers.len() + 1
    }

    /// One V-cycle for the fine system, `e ≈ A⁻¹ r`. `smooth(e, r, reverse)`
    /// does one VerBSS sweep of the fine level for `A e = r` in place;
    /// `residual(r, e, out)` sets `out = r − A e`.
    pub(crate) fn vcycle<S, R>(&mut self, r: &[f64], e: &mut [f64], mut smooth: S, residual: R)
    where
        S: FnMut(&mut [f64], &[f64], bool),
        R: Fn(&[f64], &[f64], &mut [f64]),
    {
        if self.transfers.is_empty() {
            e.copy_from_slice(r);
            self.coarsest.solve(e, &mut self.fine[0]);
            return;
        }
        e.fill(0.0);
        smooth(e, r, false);
        let [res, correction] = &mut self.fine;
        residual(r, e, res);
        let t = &self.transfers[0];
        t.r.mul(&t.p, res, &mut self.scratch[0][0]);
        cycle(
            &self.transfers,
            &self.coarse,
            &self.coarsest,
            &mut self.scratch,
            1,
        );
        self.transfers[0].p.mul(&self.scratch[0][1], correction);
        add(e, correction);
        smooth(e, r, true);
    }
}

/// `x += y`.
fn add(x: &mut [f64], y: &[f64]) {
    x.par_iter_mut()
        .zip(y.par_iter())
        .for_each(|(a, b)| *a += b);
}

/// The V-cycle on coarse level `level` (≥ 1): `scratch[0]` is this level's
/// (right-hand side in, correction out, two work vectors), the rest the
/// coarser levels'.
fn cycle(
    transfers: &[Transfer],
    coarse: &[Coarse],
    coarsest: &Coarsest,
    scratch: &mut [[Vec<f64>; 4]],
    level: usize,
) {
    let (head, rest) = scratch.split_first_mut().expect("a level's scratch");
    let [r, e, res, next] = head;
    if level == transfers.len() {
        e.copy_from_slice(r);
        coarsest.solve(e, next);
        return;
    }
    let c = &coarse[level - 1];
    e.fill(0.0);
    c.gauss_seidel(r, e, next, false);
    c.a.mul(e, res);
    res.par_iter_mut()
        .zip(r.par_iter())
        .for_each(|(x, b)| *x = b - *x);
    let t = &transfers[level];
    t.r.mul(&t.p, res, &mut rest[0][0]);
    cycle(transfers, coarse, coarsest, rest, level + 1);
    t.p.mul(&rest[0][1], res);
    add(e, res);
    c.gauss_seidel(r, e, next, true);
}

impl Coarsest {
    /// Replaces the right-hand side `x` by the (approximate) solution.
    fn solve(&self, x: &mut [f64], work: &mut [f64]) {
        match self {
            Coarsest::Exact(lu) => lu.solve(x),
            Coarsest::Sweeps(c) => {
                let r = x.to_vec();
                x.fill(0.0);
                for _ in 0..COARSEST_SWEEPS {
                    c.gauss_seidel(&r, x, work, false);
                    c.gauss_seidel(&r, x, work, true);
                }
            }
        }
    }
}

impl Coarse {
    fn new(a: Bsr) -> Result<Coarse> {
        let inverse = diagonal_inverses(&a)?;
        let graph = Csr::from_pairs(
            a.rows,
            (0..a.rows).flat_map(|i| {
                a.columns[a.offsets[i]..a.offsets[i + 1]]
                    .iter()
                    .map(move |&j| (i, j as usize))
                    .filter(|&(i, j)| i != j)
                    .flat_map(|(i, j)| [(i, j), (j, i)])
            }),
        );
        let order: Vec<usize> = (0..a.rows).collect();
        let (colour, count) = topology::colour(&graph, &order);
        let mut colours = vec![Vec::new(); count as usize];
        for (i, &c) in colour.iter().enumerate() {
            colours[c as usize].push(i as u32);
        }
        Ok(Coarse {
            a,
            inverse,
            colours,
        })
    }

    /// One multicolour block Gauss–Seidel sweep for `A e = r` (colours in
    /// reverse order when `reverse`): `e_i ← A_ii⁻¹ (r_i − Σ_{j≠i} A_ij e_j)`.
    fn gauss_seidel(&self, r: &[f64], e: &mut [f64], next: &mut [f64], reverse: bool) {
        let a = &self.a;
        let b = a.r;
        let kernel = mul_kernel(b, b);
        for k in 0..self.colours.len() {
            let nodes = &self.colours[if reverse {
                self.colours.len() - 1 - k
            } else {
                k
            }];
            let current: &[f64] = e;
            next[..b * nodes.len()]
                .par_chunks_mut(b)
                .zip(nodes.par_iter())
                .for_each(|(out, &i)| {
                    let i = i as usize;
                    let mut s = [0.0; MAX_BLOCK];
                    let s = &mut s[..b];
                    a.row_mul_add(i, current, s, &kernel, Some(i));
                    for (x, v) in s.iter_mut().enumerate() {
                        *v = r[b * i + x] - *v;
                    }
                    out.fill(0.0);
                    kernel(&self.inverse[b * b * i..b * b * (i + 1)], s, out);
                });
            for (k, &i) in nodes.iter().enumerate() {
                let i = i as usize;
                e[b * i..b * (i + 1)].copy_from_slice(&next[b * k..b * (k + 1)]);
            }
        }
    }
}

/// The inverse of every diagonal block of `a`.
fn diagonal_inverses(a: &Bsr) -> Result<Vec<f64>> {
    let b = a.r;
    let mut inverse = vec![0.0; a.rows * b * b];
    for i in 0..a.rows {
        let inv = a
            .find(i, i)
            .and_then(|e| invert(a.block(e), b))
            .ok_or_else(|| {
                Error::InvalidMesh(format!(
                    "the multigrid met a singular diagonal block (row {i} of a {}-row level)",
                    a.rows
                ))
            })?;
        inverse[b * b * i..b * b * (i + 1)].copy_from_slice(&inv);
    }
    Ok(inverse)
}

/// The dense LU of a (small) block matrix.
fn dense_lu(a: &Bsr) -> Result<DenseLu> {
    let (b, n) = (a.r, a.rows * a.r);
    let mut dense = vec![0.0; n * n];
    for i in 0..a.rows {
        for e in a.offsets[i]..a.offsets[i + 1] {
            let j = a.columns[e] as usize;
            let blk = a.block(e);
            for x in 0..b {
                for y in 0..b {
                    dense[(b * i + x) * n + b * j + y] += blk[x * b + y];
                }
            }
        }
    }
    DenseLu::factor(dense, n)
        .ok_or_else(|| Error::InvalidMesh("the multigrid's coarsest system is singular".into()))
}

/// The fine system as full `D × D` blocks in mesh axes: `R_pᵀ K̃_pp R_p`
/// on the diagonal (`K̃` the stored, for a sliding node projected and padded,
/// block; `R_p` its frame) and `−P_p B_pq P_q` off it, `P = I − n nᵀ` for a
/// sliding node.
fn fine_matrix<const D: usize>(blocks: &NodeBlocks, layout: &Layout) -> Bsr {
    let s = packed_len(D);
    let projector = |p: usize| -> [[f64; D]; D] {
        let id = std::array::from_fn(|r| std::array::from_fn(|c| f64::from(u8::from(r == c))));
        layout.frame::<D>(p).map_or(id, |f| f.projector())
    };
    Bsr::from_rows(
        layout.order.len(),
        layout.order.len(),
        (D, D),
        || (),
        |_, p, columns, values| {
            let factor = &blocks.diag[s * p..s * (p + 1)];
            let frame = layout.frame::<D>(p);
            // Column c of R_pᵀ K̃ R_p: the unit vector e_c through the frame.
            let cols: [[f64; D]; D] = std::array::from_fn(|c| {
                let unit: [f64; D] = std::array::from_fn(|k| f64::from(u8::from(k == c)));
                match frame {
                    None => ldlt_mul::<D>(factor, &unit),
                    Some(f) => f.unrotate(&ldlt_mul::<D>(factor, &f.rotate(&unit))),
                }
            });
            columns.push(p as u32);
            values.extend((0..D * D).map(|k| cols[k % D][k / D]));
            let pp = projector(p);
            for e in blocks.offsets[p]..blocks.offsets[p + 1] {
                let q = blocks.neighbours[e] as usize;
                let pq = projector(q);
                let b = &blocks.blocks[s * e..s * (e + 1)];
                columns.push(q as u32);
                // Column c of B P_q, then row r of −P_p (B P_q).
                let bq: [[f64; D]; D] =
                    std::array::from_fn(|c| packed_mul::<D>(b, &std::array::from_fn(|k| pq[k][c])));
                values.extend((0..D * D).map(|k| {
                    let (r, c) = (k / D, k % D);
                    -(0..D).map(|l| pp[r][l] * bq[c][l]).sum::<f64>()
                }));
            }
        },
    )
}

/// The rigid-body modes at each unknown node, `D × m` row-major per node
/// (`m` = 3 in 2D, 6 in 3D): translations, then rotations of the node
/// coordinates about their centroid scaled to unit size; projected on the
/// tangent plane of sliding nodes.
fn rigid_modes<const D: usize>(layout: &Layout, coords: &[f64]) -> Vec<f64> {
    let m = if D == 2 { 3 } else { 6 };
    let n = layout.order.len();
    let mut centre = [0.0; D];
    for &i in &layout.order {
        for k in 0..D {
            centre[k] += coords[D * i + k] / n as f64;
        }
    }
    let radius = layout
        .order
        .iter()
        .map(|&i| {
            (0..D)
                .map(|k| (coords[D * i + k] - centre[k]).powi(2))
                .sum::<f64>()
        })
        .fold(0.0, f64::max)
        .sqrt()
        .max(f64::MIN_POSITIVE);
    let mut out = vec![0.0; n * D * m];
    for (p, &i) in layout.order.iter().enumerate() {
        let x: [f64; 3] = std::array::from_fn(|k| {
            if k < D {
                (coords[D * i + k] - centre[k]) / radius
            } else {
                0.0
            }
        });
        let mut modes = vec![[0.0; D]; m];
        for (k, mode) in modes.iter_mut().enumerate().take(D) {
            mode[k] = 1.0;
        }
        if D == 2 {
            modes[2][0] = -x[1];
            modes[2][1] = x[0];
        } else {
            // ω × x for ω = e_x, e_y, e_z
            modes[3][1] = -x[2];
            modes[3][2] = x[1];
            modes[4][0] = x[2];
            modes[4][2] = -x[0];
            modes[5][0] = -x[1];
            modes[5][1] = x[0];
        }
        if let Some(f) = layout.frame::<D>(p) {
            for mode in &mut modes {
                let given = f.given_part(mode);
                for k in 0..D {
                    mode[k] -= given[k];
                }
            }
        }
        let blk = &mut out[D * m * p..D * m * (p + 1)];
        for (c, mode) in modes.iter().enumerate() {
            for r in 0..D {
                blk[r * m + c] = mode[r];
            }
        }
    }
    out
}

/// The symmetric strong-coupling graph (see the module documentation).
fn strength(a: &Bsr, theta: f64) -> Csr {
    let s = a.r * a.c;
    let norm = |e: usize| {
        a.values[s * e..s * (e + 1)]
            .iter()
            .map(|v| v * v)
            .sum::<f64>()
            .sqrt()
    };
    let diag: Vec<f64> = (0..a.rows)
        .map(|i| a.find(i, i).map_or(0.0, norm))
        .collect();
    let pairs: Vec<(usize, usize)> = (0..a.rows)
        .into_par_iter()
        .flat_map_iter(|i| {
            let diag = &diag;
            (a.offsets[i]..a.offsets[i + 1]).filter_map(move |e| {
                let j = a.columns[e] as usize;
                (j != i && norm(e) >= theta * (diag[i] * diag[j]).sqrt()).then_some((i, j))
            })
        })
        .collect();
    Csr::from_pairs(a.rows, pairs.iter().flat_map(|&(i, j)| [(i, j), (j, i)]))
}

/// Standard aggregation of the strong graph: the aggregate of each node and
/// the number of aggregates.
fn aggregate(strong: &Csr) -> (Vec<u32>, usize) {
    let n = strong.rows();
    let mut agg = vec![u32::MAX; n];
    let mut count = 0u32;
    for i in 0..n {
        let row = strong.row(i);
        if agg[i] == u32::MAX && !row.is_empty() && row.iter().all(|&j| agg[j as usize] == u32::MAX)
        {
            agg[i] = count;
            for &j in row {
                agg[j as usize] = count;
            }
            count += 1;
        }
    }
    let first = agg.clone();
    for (i, a) in agg.iter_mut().enumerate() {
        if *a == u32::MAX {
            if let Some(j) = strong.entries(i).find(|&j| first[j] != u32::MAX) {
                *a = first[j];
            }
        }
    }
    for i in 0..n {
        if agg[i] == u32::MAX {
            agg[i] = count;
            for j in strong.entries(i) {
                if agg[j] == u32::MAX {
                    agg[j] = count;
                }
            }
            count += 1;
        }
    }
    (agg, count as usize)
}

/// The tentative prolongator (`b × m` blocks), the coarse near-null space
/// (`m × m` per aggregate) and the dropped coarse unknowns `(aggregate, mode)`.
fn tentative(
    agg: &[u32],
    count: usize,
    modes: &[f64],
    b: usize,
    m: usize,
) -> (Bsr, Vec<f64>, Vec<(usize, usize)>) {
    let n = agg.len();
    let members = Csr::from_pairs(count, (0..n).map(|i| (agg[i] as usize, i)));
    let mut q = vec![0.0; n * b * m];
    let mut coarse = vec![0.0; count * m * m];
    let mut dropped = Vec::new();
    for a in 0..count {
        let nodes = members.row(a);
        let rows = nodes.len() * b;
        // column-major copy of the aggregate's modes
        let mut cols: Vec<Vec<f64>> = (0..m)
            .map(|c| {
                (0..rows)
                    .map(|k| modes[b * m * nodes[k / b] as usize + (k % b) * m + c])
                    .collect()
            })
            .collect();
        let mut r = vec![0.0; m * m];
        for c in 0..m {
            let original = cols[c].iter().map(|v| v * v).sum::<f64>().sqrt();
            for prev in 0..c {
                let d: f64 = cols[c].iter().zip(&cols[prev]).map(|(x, y)| x * y).sum();
                r[prev * m + c] = d;
                let (left, right) = cols.split_at_mut(c);
                for (x, y) in right[0].iter_mut().zip(&left[prev]) {
                    *x -= d * y;
                }
            }
            let len = cols[c].iter().map(|v| v * v).sum::<f64>().sqrt();
            if len > DROP * original && len > 0.0 {
                r[c * m + c] = len;
                cols[c].iter_mut().for_each(|x| *x /= len);
            } else {
                cols[c].iter_mut().for_each(|x| *x = 0.0);
                dropped.push((a, c));
            }
        }
        for (k, node) in members.entries(a).enumerate() {
            for x in 0..b {
                for c in 0..m {
                    q[b * m * node + x * m + c] = cols[c][k * b + x];
                }
            }
        }
        coarse[m * m * a..m * m * (a + 1)].copy_from_slice(&r);
    }
    let t = Bsr {
        rows: n,
        cols: count,
        r: b,
        c: m,
        offsets: (0..=n).collect(),
        columns: agg.to_vec(),
        values: q,
    };
    (t, coarse, dropped)
}

/// `P = T − (4/3)/ρ · D⁻¹ A T` (see the module documentation).
fn smooth_prolongator(a: &Bsr, t: &Bsr) -> Result<Bsr> {
    let b = a.r;
    let m = t.c;
    let inverse = diagonal_inverses(a)?;
    let weight = 4.0 / 3.0 / spectral_radius(a, &inverse);
    let at = a.product(t);
    let kernel = madd_kernel(b, b, m);
    Ok(Bsr::from_rows(
        at.rows,
        at.cols,
        (b, m),
        || (),
        |_, i, columns, values| {
            let inv = &inverse[b * b * i..b * b * (i + 1)];
            for e in at.offsets[i]..at.offsets[i + 1] {
                let start = values.len();
                values.extend(std::iter::repeat_n(0.0, b * m));
                kernel(inv, at.block(e), &mut values[start..]);
                values[start..].iter_mut().for_each(|v| *v *= -weight);
                if at.columns[e] == t.columns[i] {
                    for (v, tv) in values[start..].iter_mut().zip(t.block(i)) {
                        *v += tv;
                    }
                }
                columns.push(at.columns[e]);
            }
        },
    ))
}

/// ρ(D⁻¹A) by power iteration from a fixed start vector, times 1.05 so that
/// the estimate errs on the safe side.
fn spectral_radius(a: &Bsr, inverse: &[f64]) -> f64 {
    let b = a.r;
    let n = a.rows * b;
    let mut x: Vec<f64> = (0..n)
        .map(|k| 1.0 + ((k * 7919) % 13) as f64 / 13.0)
        .collect();
    let mut y = vec![0.0; n];
    let mut rho = 1.0;
    for _ in 0..POWER_STEPS {
        let len = chunked_sum(&x, |v| v * v).sqrt();
        x.iter_mut().for_each(|v| *v /= len);
        a.mul(&x, &mut y);
        let kernel = mul_kernel(b, b);
        y.par_chunks_mut(b).enumerate().for_each(|(i, yi)| {
            let mut v = [0.0; MAX_BLOCK];
            v[..b].copy_from_slice(yi);
            yi.fill(0.0);
            kernel(&inverse[b * b * i..b * b * (i + 1)], &v[..b], yi);
        });
        rho = chunked_sum(&y, |v| v * v).sqrt();
        std::mem::swap(&mut x, &mut y);
    }
    1.05 * rho.max(f64::MIN_POSITIVE)
}
