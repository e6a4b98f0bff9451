//! The frames of constrained nodes (docs/method.md, "Unknowns").
//!
//! A node sliding in a plane of unit normal `n` ([`NodeRole::Slide`]), or
//! along a line of unit direction `t` ([`NodeRole::Line`], where two slide
//! planes meet), is solved in an orthonormal frame `R` (rows `r₁ … r_D`):
//! the components along its first `free` rows are unknowns (the plane's
//! `D − 1` tangents, or `t` alone) and those along the other rows (`n`, or
//! the line's two normals) keep the values they were given. With
//! `T = [r₁ … r_free]` and the given part `f = Σ_{k ≥ free} (r_k·u) r_k`,
//! `u = f + T a` and the node's equation is the projected one,
//! `Tᵀ K_ii T a = Tᵀ (Σ_j B_ij u_j − K_ii f)`.

use crate::error::{Error, Result};
use crate::geometry::{norm, normal_frame, packed_index, packed_len, packed_mul};

use super::NodeRole;

/// One constrained node's frame: rows `r₁ … r_D`, the first `free` of them
/// the directions it moves in.
#[derive(Clone, Copy, Debug)]
pub struct Frame<const D: usize> {
    rows: [[f64; D]; D],
    free: usize,
}

impl<const D: usize> Frame<D> {
    /// The frame of a node of role `role`, `None` for a free or fixed node.
    /// `directions`: unit plane normals ([`NodeRole::Slide`]) and line
    /// directions ([`NodeRole::Line`]).
    pub fn of_role(role: NodeRole, directions: &[[f64; 3]]) -> Option<Frame<D>> {
        let direction = |k: usize| -> [f64; D] { std::array::from_fn(|c| directions[k][c]) };
        match role {
            NodeRole::Free | NodeRole::Fixed => None,
            NodeRole::Slide(k) => Some(Frame {
                rows: normal_frame(&direction(k)),
                free: D - 1,
            }),
            NodeRole::Line(k) => {
                // normal_frame(t) has rows (n₁ … n_{D−1}, t); t goes first.
                let mut rows = normal_frame(&direction(k));
                rows.rotate_right(1);
                Some(Frame { rows, free: 1 })
            }
        }
    }

    /// The frame of a free node: the mesh axes, every component unknown.
    pub fn identity() -> Frame<D> {
        Frame {
            rows: std::array::from_fn(|r| std::array::from_fn(|c| f64::from(u8::from(r == c)))),
            free: D,
        }
    }

    /// Number of unknown components: the leading rows.
    #[inline(always)]
    pub fn free(&self) -> usize {
        self.free
    }

    /// The rows `r₁ … r_D`.
    #[inline(always)]
    pub fn rows(&self) -> &[[f64; D]; D] {
        &self.rows
    }

    /// `R v`: `v` in frame components.
    #[inline(always)]
    pub fn rotate(&self, v: &[f64; D]) -> [f64; D] {
        std::array::from_fn(|k| (0..D).map(|l| self.rows[k][l] * v[l]).sum())
    }

    /// `Rᵀ a`: frame components `a` back in mesh axes.
    #[inline(always)]
    pub fn unrotate(&self, a: &[f64; D]) -> [f64; D] {
        std::array::from_fn(|l| (0..D).map(|k| self.rows[k][l] * a[k]).sum())
    }

    /// Zeroes the given (constrained) components of frame components `a`.
    #[inline(always)]
    pub fn clear_given(&self, a: &mut [f64; D]) {
        a[self.free..].fill(0.0);
    }

    /// The given part `f = Σ_{k ≥ free} (r_k·u) r_k` of `u`.
    #[inline(always)]
    pub fn given_part(&self, u: &[f64; D]) -> [f64; D] {
        let mut a = self.rotate(u);
        a[..self.free].fill(0.0);
        self.unrotate(&a)
    }

    /// `T Tᵀ = Σ_{k < free} r_k r_kᵀ`: the projection on the directions the
    /// node moves in.
    pub fn projector(&self) -> [[f64; D]; D] {
        std::array::from_fn(|r| {
            std::array::from_fn(|c| {
                (0..self.free)
                    .map(|k| self.rows[k][r] * self.rows[k][c])
                    .sum()
            })
        })
    }

    /// The packed block `R K Rᵀ` of packed `k`, its given rows and columns
    /// replaced by the identity: `[[Tᵀ K T, 0], [0, I]]`.
    pub fn project(&self, k: &[f64], out: &mut [f64]) {
        let kr: [[f64; D]; D] = std::array::from_fn(|b| packed_mul::<D>(k, &self.rows[b]));
        for a in 0..D {
            for b in 0..=a {
                out[packed_index(a, b)] = if a >= self.free || b >= self.free {
                    f64::from(u8::from(a == b))
                } else {
                    (0..D).map(|c| self.rows[a][c] * kr[b][c]).sum()
                };
            }
        }
    }
}

/// The frames of the constrained nodes among a numbering of unknowns
/// ("positions"), stored flat.
#[derive(Clone, Debug, Default)]
pub struct Frames {
    /// Per position: the index of its frame, `u32::MAX` for a free node.
    slot: Vec<u32>,
    /// `D × D` numbers per frame: its rows.
    rows: Vec<f64>,
    /// Per frame: its number of free rows.
    free: Vec<u8>,
}

impl Frames {
    /// The frames of `roles`, one per position.
    pub fn new<const D: usize>(
        roles: impl Iterator<Item = NodeRole>,
        directions: &[[f64; 3]],
    ) -> Frames {
        let mut frames = Frames::default();
        for role in roles {
            match Frame::<D>::of_role(role, directions) {
                None => frames.slot.push(u32::MAX),
                Some(f) => {
                    frames.slot.push(frames.free.len() as u32);
                    frames.rows.extend(f.rows.iter().flatten());
                    frames.free.push(f.free as u8);
                }
            }
        }
        frames
    }

    /// The frame of position `p`, `None` for a free node.
    #[inline(always)]
    pub fn get<const D: usize>(&self, p: usize) -> Option<Frame<D>> {
        let s = self.slot[p];
        (s != u32::MAX).then(|| {
            let s = s as usize;
            let f = &self.rows[D * D * s..D * D * (s + 1)];
            Frame {
                rows: std::array::from_fn(|r| std::array::from_fn(|c| f[D * r + c])),
                free: usize::from(self.free[s]),
            }
        })
    }

    /// The frame index of position `p`, `None` for a free node.
    #[inline(always)]
    pub fn slot(&self, p: usize) -> Option<usize> {
        let s = self.slot[p];
        (s != u32::MAX).then_some(s as usize)
    }

    /// Number of positions.
    pub fn len(&self) -> usize {
        self.slot.len()
    }

    /// Whether there are no positions.
    pub fn is_empty(&self) -> bool {
        self.slot.is_empty()
    }

    /// Number of unknown components: `D` per free node, `free` per
    /// constrained one.
    pub fn unknowns<const D: usize>(&self) -> usize {
        D * (self.slot.len() - self.free.len())
            + self.free.iter().map(|&f| usize::from(f)).sum::<usize>()
    }

    /// Bytes stored.
    pub fn bytes(&self) -> usize {
        self.slot.len() * std::mem::size_of::<u32>()
            + self.rows.len() * std::mem::size_of::<f64>()
            + self.free.len()
    }

    /// Replaces the packed diagonal blocks (`diag`, one per position) of the
    /// constrained positions by their projection ([`Frame::project`]) and
    /// returns the original blocks, packed, one per frame (for
    /// [`Frames::given_pull`]).
    pub fn project_diagonal<const D: usize>(&self, diag: &mut [f64]) -> Vec<f64> {
        let s = packed_len(D);
        let mut unprojected = vec![0.0; s * self.free.len()];
        for p in 0..self.slot.len() {
            if let (Some(f), Some(slot)) = (self.get::<D>(p), self.slot(p)) {
                let k = &mut unprojected[s * slot..s * (slot + 1)];
                k.copy_from_slice(&diag[s * p..s * (p + 1)]);
                f.project(k, &mut diag[s * p..s * (p + 1)]);
            }
        }
        unprojected
    }

    /// `K_pp f` for position `p` with displacement `u`, `f` its given part,
    /// from the blocks `unprojected` that [`Frames::project_diagonal`] returned;
    /// `None` for a free node.
    #[inline]
    pub fn given_pull<const D: usize>(
        &self,
        unprojected: &[f64],
        p: usize,
        u: &[f64; D],
    ) -> Option<[f64; D]> {
        let s = packed_len(D);
        let slot = self.slot(p)?;
        let f = self.get::<D>(p)?;
        Some(packed_mul::<D>(
            &unprojected[s * slot..s * (slot + 1)],
            &f.given_part(u),
        ))
    }
}

/// The unit directions of `directions` (the first `dim` numbers of each),
/// after checking that each is finite and nonzero and that every
/// [`NodeRole::Slide`] or [`NodeRole::Line`] in `roles` names one;
/// `tag(i)` names node `i` in the error.
pub fn unit_directions(
    dim: usize,
    roles: &[NodeRole],
    directions: &[[f64; 3]],
    tag: impl Fn(usize) -> u64,
) -> Result<Vec<[f64; 3]>> {
    let mut unit = Vec::with_capacity(directions.len());
    for (k, v) in directions.iter().enumerate() {
        let len = norm(&[v[0], v[1], if dim == 3 { v[2] } else { 0.0 }]);
        if !(len > 0.0 && len.is_finite()) {
            return Err(Error::InvalidSetting(format!(
                "sliding normal {k} is zero or not finite"
            )));
        }
        let mut u = [v[0] / len, v[1] / len, 0.0];
        if dim == 3 {
            u[2] = v[2] / len;
        }
        unit.push(u);
    }
    for (i, role) in roles.iter().enumerate() {
        if let NodeRole::Slide(k) | NodeRole::Line(k) = role {
            if *k >= directions.len() {
                return Err(Error::InvalidSetting(format!(
                    "node {} slides on normal {k} but {} normals were given",
                    tag(i),
                    directions.len()
                )));
            }
        }
    }
    Ok(unit)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_frame_moves_along_the_line_and_keeps_both_normals() {
        let t = [1.0, 2.0, 2.0].map(|v: f64| v / 3.0);
        let f = Frame::<3>::of_role(NodeRole::Line(0), &[t]).unwrap();
        assert_eq!(f.free(), 1);
        assert_eq!(f.rows()[0], t);
        let u = [0.3, -0.7, 1.1];
        let along: f64 = (0..3).map(|c| t[c] * u[c]).sum();
        let given = f.given_part(&u);
        for c in 0..3 {
            assert!((given[c] - (u[c] - along * t[c])).abs() < 1e-15);
        }
        let p = f.projector();
        for r in 0..3 {
            for c in 0..3 {
                assert!((p[r][c] - t[r] * t[c]).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn projecting_a_block_keeps_the_free_rows_and_pads_the_given_ones() {
        // K = diag(1, 2, 3) seen along the x axis: Tᵀ K T = 1, the rest I.
        let k = {
            let mut k = vec![0.0; packed_len(3)];
            for (d, v) in [1.0, 2.0, 3.0].iter().enumerate() {
                k[packed_index(d, d)] = *v;
            }
            k
        };
        let f = Frame::<3>::of_role(NodeRole::Line(0), &[[0.0, 0.0, 1.0]]).unwrap();
        let mut out = vec![0.0; packed_len(3)];
        f.project(&k, &mut out);
        assert_eq!(out[packed_index(0, 0)], 3.0);
        for (a, b) in [(1, 1), (2, 2)] {
            assert_eq!(out[packed_index(a, b)], 1.0);
        }
        for (a, b) in [(1, 0), (2, 0), (2, 1)] {
            assert_eq!(out[packed_index(a, b)], 0.0);
        }
    }
}
