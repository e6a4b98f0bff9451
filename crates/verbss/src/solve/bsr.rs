//! Block sparse rows: the matrices of the multigrid hierarchy (`solve/amg.rs`).
//!
//! With them, the small dense kernels they need: block products and a
//! pivoted LU ([`DenseLu`]) for block inverses and the coarsest level.
//!
//! A [`Bsr`] holds `rows × cols` blocks of `r × c` dense numbers, row-major;
//! block row `i` is entries `offsets[i]..offsets[i + 1]`, entry `e` has block
//! column `columns[e]` and values `values[r·c·e..r·c·(e + 1)]`. Every
//! operation works block row by block row, so its result does not depend on
//! how the rows are spread over threads.

use std::ops::Range;

use rayon::prelude::*;

/// Block rows handled by one parallel task.
const ROWS_PER_TASK: usize = 256;

/// A block sparse matrix (see the module documentation).
#[derive(Debug, Clone, Default)]
pub(crate) struct Bsr {
    /// Block rows.
    pub(crate) rows: usize,
    /// Block columns.
    pub(crate) cols: usize,
    /// Rows of one block.
    pub(crate) r: usize,
    /// Columns of one block.
    pub(crate) c: usize,
    /// Start of each block row, plus the end.
    pub(crate) offsets: Vec<usize>,
    /// Block column of each entry.
    pub(crate) columns: Vec<u32>,
    /// The blocks, `r·c` numbers each.
    pub(crate) values: Vec<f64>,
}

impl Bsr {
    /// The block of entry `e`.
    #[inline]
    pub(crate) fn block(&self, e: usize) -> &[f64] {
        let s = self.r * self.c;
        &self.values[s * e..s * (e + 1)]
    }

    /// Builds the matrix block row by block row in parallel: `row(i, columns,
    /// values)` appends row `i`'s entries, reusing per-task scratch `S`.
    pub(crate) fn from_rows<S, I, F>(
        rows: usize,
        cols: usize,
        (r, c): (usize, usize),
        init: I,
        row: F,
    ) -> Bsr
    where
        I: Fn() -> S + Sync + Send,
        F: Fn(&mut S, usize, &mut Vec<u32>, &mut Vec<f64>) + Sync,
    {
        let parts: Vec<(Vec<usize>, Vec<u32>, Vec<f64>)> = (0..rows.div_ceil(ROWS_PER_TASK))
            .into_par_iter()
            .map_init(init, |scratch, t| {
                let (mut lens, mut columns, mut values) = (Vec::new(), Vec::new(), Vec::new());
                for i in t * ROWS_PER_TASK..((t + 1) * ROWS_PER_TASK).min(rows) {
                    let before = columns.len();
                    row(scratch, i, &mut columns, &mut values);
                    lens.push(columns.len() - before);
                }
                (lens, columns, values)
            })
            .collect();
        let mut offsets = Vec::with_capacity(rows + 1);
        offsets.push(0);
        for len in parts.iter().flat_map(|p| &p.0) {
            offsets.push(offsets[offsets.len() - 1] + len);
        }
        // One allocation each, filled part by part in parallel (a serial
        // append of the parts was a tenth of a multigrid set-up).
        let total = offsets[rows];
        let mut columns = vec![0u32; total];
        let mut values = vec![0.0; total * r * c];
        let column_parts = split_by(&mut columns, parts.iter().map(|p| p.1.len()));
        let value_parts = split_by(&mut values, parts.iter().map(|p| p.2.len()));
        parts
            .into_par_iter()
            .zip(column_parts)
            .zip(value_parts)
            .for_each(|(((_, part_columns, part_values), columns), values)| {
                columns.copy_from_slice(&part_columns);
                values.copy_from_slice(&part_values);
            });
        Bsr {
            rows,
            cols,
            r,
            c,
            offsets,
            columns,
            values,
        }
    }

    /// `y = A x`.
    pub(crate) fn mul(&self, x: &[f64], y: &mut [f64]) {
        let r = self.r;
        let kernel = mul_kernel(self.r, self.c);
        y.par_chunks_mut(r * ROWS_PER_TASK)
            .enumerate()
            .for_each(|(t, out)| {
                for (k, yi) in out.chunks_exact_mut(r).enumerate() {
                    yi.fill(0.0);
                    self.row_mul_add(t * ROWS_PER_TASK + k, x, yi, &kernel, None);
                }
            });
    }

    /// `y_i += Σ_j A_ij x_j` over block row `i`, skipping block column `skip`.
    #[inline]
    pub(crate) fn row_mul_add(
        &self,
        i: usize,
        x: &[f64],
        yi: &mut [f64],
        kernel: &MulKernel,
        skip: Option<usize>,
    ) {
        let c = self.c;
        for e in self.offsets[i]..self.offsets[i + 1] {
            let j = self.columns[e] as usize;
            if Some(j) != skip {
                kernel(self.block(e), &x[c * j..c * (j + 1)], yi);
            }
        }
    }

    /// `Aᵀ` as a [`Transposed`] view of this matrix's blocks; its rows keep
    /// their entries in increasing column order.
    pub(crate) fn transposed(&self) -> Transposed {
        let mut offsets = vec![0usize; self.cols + 1];
        for &j in &self.columns {
            offsets[j as usize + 1] += 1;
        }
        for j in 0..self.cols {
            offsets[j + 1] += offsets[j];
        }
        let nnz = self.columns.len();
        let (mut columns, mut entries) = (vec![0u32; nnz], vec![0usize; nnz]);
        let mut fill = offsets.clone();
        for i in 0..self.rows {
            for e in self.offsets[i]..self.offsets[i + 1] {
                let slot = &mut fill[self.columns[e] as usize];
                columns[*slot] = i as u32;
                entries[*slot] = e;
                *slot += 1;
            }
        }
        Transposed {
            rows: self.cols,
            cols: self.rows,
            r: self.c,
            c: self.r,
            offsets,
            columns,
            entries,
        }
    }

    /// `A B` (row by row, Gustavson): blocks `r × c` times `c × c'`.
    pub(crate) fn product(&self, other: &Bsr) -> Bsr {
        self.product_rows(other, 0..self.rows, true)
    }

    /// Block rows `rows` of `A B`, as a matrix of `rows.len()` block rows;
    /// with `values` false only its pattern (blocks of 0 × 0 numbers), with
    /// the block columns of each row in the same order.
    fn product_rows(&self, other: &Bsr, rows: Range<usize>, values: bool) -> Bsr {
        assert_eq!(self.c, other.r, "block sizes of a product");
        let shape = if values { (self.r, other.c) } else { (0, 0) };
        let s2 = shape.0 * shape.1;
        let kernel = madd_kernel(self.r, self.c, other.c);
        Bsr::from_rows(
            rows.len(),
            other.cols,
            shape,
            || (vec![u32::MAX; other.cols], Vec::<u32>::new()),
            |(slot, cols), i, columns, out| {
                cols.clear();
                let start = out.len();
                for e in self.offsets[rows.start + i]..self.offsets[rows.start + i + 1] {
                    let k = self.columns[e] as usize;
                    for f in other.offsets[k]..other.offsets[k + 1] {
                        let at = start + s2 * claim(slot, cols, out, other.columns[f], s2);
                        if values {
                            kernel(self.block(e), other.block(f), &mut out[at..at + s2]);
                        }
                    }
                }
                for &j in cols.iter() {
                    slot[j as usize] = u32::MAX;
                }
                columns.extend_from_slice(cols);
            },
        )
    }

    /// The entry of block `(i, j)`, if stored.
    pub(crate) fn find(&self, i: usize, j: usize) -> Option<usize> {
        (self.offsets[i]..self.offsets[i + 1]).find(|&e| self.columns[e] as usize == j)
    }
}

/// `whole` cut into consecutive slices of the given lengths.
fn split_by<T>(whole: &mut [T], lengths: impl Iterator<Item = usize>) -> Vec<&mut [T]> {
    let mut rest = whole;
    lengths
        .map(|len| {
            let (head, tail) = std::mem::take(&mut rest).split_at_mut(len);
            rest = tail;
            head
        })
        .collect()
}

/// `Aᵀ` for a [`Bsr`] `A`, without copies of its blocks: block row `i` lists
/// the entries of `A`'s block column `i` in increasing row order, entry `e`
/// being block `entries[e]` of `A`, read transposed. The multigrid's
/// restriction `R = Pᵀ` is one: storing `R`'s blocks doubled the memory of
/// the transfers.
#[derive(Debug, Clone, Default)]
pub(crate) struct Transposed {
    /// Block rows (`A`'s block columns).
    pub(crate) rows: usize,
    /// Block columns (`A`'s block rows).
    pub(crate) cols: usize,
    /// Rows of one block (`A`'s block columns' width).
    pub(crate) r: usize,
    /// Columns of one block.
    pub(crate) c: usize,
    /// Start of each block row, plus the end.
    pub(crate) offsets: Vec<usize>,
    /// Block column of each entry.
    pub(crate) columns: Vec<u32>,
    /// The entry of `A` each entry reads.
    entries: Vec<usize>,
}

impl Transposed {
    /// `y = Aᵀ x`, `a` the matrix this was made from; every block sums its
    /// terms in the order of a stored transpose.
    pub(crate) fn mul(&self, a: &Bsr, x: &[f64], y: &mut [f64]) {
        let (r, c) = (self.r, self.c);
        let kernel = mul_kernel_of::<true>(r, c);
        y.par_chunks_mut(r * ROWS_PER_TASK)
            .enumerate()
            .for_each(|(t, out)| {
                for (k, yi) in out.chunks_exact_mut(r).enumerate() {
                    yi.fill(0.0);
                    let i = t * ROWS_PER_TASK + k;
                    for e in self.offsets[i]..self.offsets[i + 1] {
                        let j = self.columns[e] as usize;
                        kernel(a.block(self.entries[e]), &x[c * j..c * (j + 1)], yi);
                    }
                }
            });
    }

    /// The entries of block row `i` with block columns in `columns`.
    fn entries_between(&self, i: usize, columns: &Range<usize>) -> Range<usize> {
        let row = &self.columns[self.offsets[i]..self.offsets[i + 1]];
        let first = row.partition_point(|&j| (j as usize) < columns.start);
        let last = row.partition_point(|&j| (j as usize) < columns.end);
        self.offsets[i] + first..self.offsets[i] + last
    }
}

/// The slot of block column `j` in the row being formed (`cols`, with its
/// blocks of `s2` numbers at the end of `values`): found through `slot`, or
/// appended as a zero block.
fn claim(slot: &mut [u32], cols: &mut Vec<u32>, values: &mut Vec<f64>, j: u32, s2: usize) -> usize {
    let j = j as usize;
    if slot[j] == u32::MAX {
        slot[j] = cols.len() as u32;
        cols.push(j as u32);
        values.extend(std::iter::repeat_n(0.0, s2));
    }
    slot[j] as usize
}

/// Fine block rows of `A P` formed at a time by [`galerkin`].
const GALERKIN_ROWS: usize = 8192;

/// The coarse matrix `Pᵀ (A P)`, `r` the [`Transposed`] of `p`. `A P`,
/// the largest matrix of a multigrid setup, is never held whole: it is
/// formed [`GALERKIN_ROWS`] block rows at a time, first as a pattern to
/// find each coarse row's block columns, then with its values, whose terms
/// `R_ik (A P)_kj` are added in place before the next slice is formed.
/// Every block sums its terms in the order of `R.product(&a.product(p))`,
/// `R` the transpose stored, and so equals it bit for bit.
pub(crate) fn galerkin(r: &Transposed, a: &Bsr, p: &Bsr) -> Bsr {
    galerkin_in_slices(r, a, p, GALERKIN_ROWS)
}

/// [`galerkin`] with slices of `slice` fine block rows.
fn galerkin_in_slices(r: &Transposed, a: &Bsr, p: &Bsr, slice: usize) -> Bsr {
    assert!(
        r.cols == a.rows && a.cols == p.rows && r.c == a.r,
        "shapes of R A P"
    );
    let slices = || {
        (0..a.rows)
            .step_by(slice)
            .map(|lo| lo..(lo + slice).min(a.rows))
    };
    let marks = || vec![u32::MAX; p.cols];
    // Each coarse row's block columns, in the order the whole product meets them.
    let mut patterns: Vec<Vec<u32>> = vec![Vec::new(); r.rows];
    for fine in slices() {
        let ap = a.product_rows(p, fine.clone(), false);
        patterns
            .par_iter_mut()
            .enumerate()
            .for_each_init(marks, |slot, (i, cols)| {
                let entries = r.entries_between(i, &fine);
                if entries.is_empty() {
                    return;
                }
                for (n, &j) in cols.iter().enumerate() {
                    slot[j as usize] = n as u32;
                }
                for e in entries {
                    let k = r.columns[e] as usize - fine.start;
                    for f in ap.offsets[k]..ap.offsets[k + 1] {
                        claim(slot, cols, &mut Vec::new(), ap.columns[f], 0);
                    }
                }
                for &j in cols.iter() {
                    slot[j as usize] = u32::MAX;
                }
            });
    }
    let s2 = r.r * p.c;
    let mut offsets = Vec::with_capacity(r.rows + 1);
    offsets.push(0);
    for cols in &patterns {
        offsets.push(offsets[offsets.len() - 1] + cols.len());
    }
    let columns: Vec<u32> = patterns.into_iter().flatten().collect();
    let mut values = vec![0.0; s2 * columns.len()];
    let mut rows = split_by(&mut values, offsets.windows(2).map(|w| s2 * (w[1] - w[0])));
    let kernel = madd_kernel_of::<true>(r.r, r.c, p.c);
    for fine in slices() {
        let ap = a.product_rows(p, fine.clone(), true);
        rows.par_iter_mut()
            .enumerate()
            .for_each_init(marks, |slot, (i, out)| {
                let entries = r.entries_between(i, &fine);
                if entries.is_empty() {
                    return;
                }
                let cols = &columns[offsets[i]..offsets[i + 1]];
                for (n, &j) in cols.iter().enumerate() {
                    slot[j as usize] = n as u32;
                }
                for e in entries {
                    let k = r.columns[e] as usize - fine.start;
                    for f in ap.offsets[k]..ap.offsets[k + 1] {
                        let at = s2 * slot[ap.columns[f] as usize] as usize;
                        kernel(p.block(r.entries[e]), ap.block(f), &mut out[at..at + s2]);
                    }
                }
                for &j in cols {
                    slot[j as usize] = u32::MAX;
                }
            });
    }
    drop(rows);
    Bsr {
        rows: r.rows,
        cols: p.cols,
        r: r.r,
        c: p.c,
        offsets,
        columns,
        values,
    }
}

/// `y += A x` for one block.
pub(crate) type MulKernel = Box<dyn Fn(&[f64], &[f64], &mut [f64]) + Sync + Send>;

/// `y += A x` for an `R × C` block, stored row-major, or with `T` its
/// transpose stored row-major (`C × R`): the same terms in the same order.
#[inline(always)]
fn mul_add<const R: usize, const C: usize, const T: bool>(a: &[f64], x: &[f64], y: &mut [f64]) {
    let (a, x, y) = (&a[..R * C], &x[..C], &mut y[..R]);
    for (k, yk) in y.iter_mut().enumerate() {
        let mut s = 0.0;
        for l in 0..C {
            s += a[if T { l * R + k } else { k * C + l }] * x[l];
        }
        *yk += s;
    }
}

/// The [`mul_add`] of an `r × c` block.
pub(crate) fn mul_kernel(r: usize, c: usize) -> MulKernel {
    mul_kernel_of::<false>(r, c)
}

/// The [`mul_add`] of an `r × c` block (stored transposed with `T`):
/// compiled for the block shapes of the hierarchy (node blocks 2, 3;
/// near-null space sizes 3, 6), a generic loop otherwise.
fn mul_kernel_of<const T: bool>(r: usize, c: usize) -> MulKernel {
    match (r, c) {
        (2, 2) => Box::new(mul_add::<2, 2, T>),
        (3, 3) => Box::new(mul_add::<3, 3, T>),
        (6, 6) => Box::new(mul_add::<6, 6, T>),
        (2, 3) => Box::new(mul_add::<2, 3, T>),
        (3, 2) => Box::new(mul_add::<3, 2, T>),
        (3, 6) => Box::new(mul_add::<3, 6, T>),
        (6, 3) => Box::new(mul_add::<6, 3, T>),
        _ => Box::new(move |a: &[f64], x: &[f64], y: &mut [f64]| {
            for (k, yk) in y.iter_mut().enumerate().take(r) {
                *yk += (0..c)
                    .map(|l| a[if T { l * r + k } else { k * c + l }] * x[l])
                    .sum::<f64>();
            }
        }),
    }
}

/// `out += A B` for blocks `A` (`R × C`; stored transposed with `T`) and
/// `B` (`C × K`), row-major.
#[inline(always)]
fn madd<const R: usize, const C: usize, const K: usize, const T: bool>(
    a: &[f64],
    b: &[f64],
    out: &mut [f64],
) {
    let (a, b, out) = (&a[..R * C], &b[..C * K], &mut out[..R * K]);
    for x in 0..R {
        for z in 0..C {
            let v = a[if T { z * R + x } else { x * C + z }];
            for y in 0..K {
                out[x * K + y] += v * b[z * K + y];
            }
        }
    }
}

/// The [`madd`] of blocks `r × c` and `c × k`.
pub(crate) fn madd_kernel(r: usize, c: usize, k: usize) -> MulKernel {
    madd_kernel_of::<false>(r, c, k)
}

/// The [`madd`] of blocks `r × c` (stored transposed with `T`) and `c × k`,
/// compiled for the products of the hierarchy, a generic loop otherwise.
fn madd_kernel_of<const T: bool>(r: usize, c: usize, k: usize) -> MulKernel {
    match (r, c, k) {
        (2, 2, 3) => Box::new(madd::<2, 2, 3, T>),
        (3, 2, 3) => Box::new(madd::<3, 2, 3, T>),
        (3, 3, 3) => Box::new(madd::<3, 3, 3, T>),
        (3, 3, 6) => Box::new(madd::<3, 3, 6, T>),
        (6, 3, 6) => Box::new(madd::<6, 3, 6, T>),
        (6, 6, 6) => Box::new(madd::<6, 6, 6, T>),
        _ => Box::new(move |a: &[f64], b: &[f64], out: &mut [f64]| {
            for x in 0..r {
                for z in 0..c {
                    let v = a[if T { z * r + x } else { x * c + z }];
                    for y in 0..k {
                        out[x * k + y] += v * b[z * k + y];
                    }
                }
            }
        }),
    }
}

/// A dense LU factorisation with row pivots (`P A = L U`, `L` unit lower
/// triangular stored below the diagonal of `lu`, `U` on and above it).
pub(crate) struct DenseLu {
    n: usize,
    lu: Vec<f64>,
    pivots: Vec<usize>,
}

impl DenseLu {
    /// Factors the `n × n` row-major matrix `a` by Gaussian elimination with
    /// partial pivoting; `None` when a pivot is zero or not finite.
    pub(crate) fn factor(mut lu: Vec<f64>, n: usize) -> Option<DenseLu> {
        let mut pivots = vec![0; n];
        for col in 0..n {
            let p = (col..n)
                .max_by(|&x, &y| lu[x * n + col].abs().total_cmp(&lu[y * n + col].abs()))?;
            let v = lu[p * n + col];
            if !(v.is_finite() && v != 0.0) {
                return None;
            }
            pivots[col] = p;
            if p != col {
                for k in 0..n {
                    lu.swap(p * n + k, col * n + k);
                }
            }
            for row in col + 1..n {
                let f = lu[row * n + col] / v;
                lu[row * n + col] = f;
                if f != 0.0 {
                    for k in col + 1..n {
                        lu[row * n + k] -= f * lu[col * n + k];
                    }
                }
            }
        }
        Some(DenseLu { n, lu, pivots })
    }

    /// Solves `A x = b` in place (`x` holds `b` on entry).
    pub(crate) fn solve(&self, x: &mut [f64]) {
        let n = self.n;
        for col in 0..n {
            x.swap(col, self.pivots[col]);
        }
        for i in 0..n {
            let s: f64 = (0..i).map(|k| self.lu[i * n + k] * x[k]).sum();
            x[i] -= s;
        }
        for i in (0..n).rev() {
            let s: f64 = (i + 1..n).map(|k| self.lu[i * n + k] * x[k]).sum();
            x[i] = (x[i] - s) / self.lu[i * n + i];
        }
    }
}

/// The inverse of the dense `n × n` row-major matrix `a`, column by column
/// from its [`DenseLu`]; `None` when `a` is singular to working precision.
pub(crate) fn invert(a: &[f64], n: usize) -> Option<Vec<f64>> {
    let lu = DenseLu::factor(a.to_vec(), n)?;
    let mut inv = vec![0.0; n * n];
    let mut column = vec![0.0; n];
    for c in 0..n {
        column.fill(0.0);
        column[c] = 1.0;
        lu.solve(&mut column);
        for (r, v) in column.iter().enumerate() {
            inv[r * n + c] = *v;
        }
    }
    inv.iter().all(|v| v.is_finite()).then_some(inv)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 3×2 block matrix of 2×1 blocks from dense rows.
    fn dense_to_bsr(d: &[Vec<f64>], (r, c): (usize, usize)) -> Bsr {
        let rows = d.len() / r;
        let cols = d[0].len() / c;
        Bsr::from_rows(
            rows,
            cols,
            (r, c),
            || (),
            |_, i, columns, values| {
                for j in 0..cols {
                    let block: Vec<f64> = (0..r * c)
                        .map(|k| d[i * r + k / c][j * c + k % c])
                        .collect();
                    if block.iter().any(|&v| v != 0.0) {
                        columns.push(j as u32);
                        values.extend(block);
                    }
                }
            },
        )
    }

    fn to_dense(m: &Bsr) -> Vec<Vec<f64>> {
        let mut d = vec![vec![0.0; m.cols * m.c]; m.rows * m.r];
        for i in 0..m.rows {
            for e in m.offsets[i]..m.offsets[i + 1] {
                let j = m.columns[e] as usize;
                for k in 0..m.r * m.c {
                    d[i * m.r + k / m.c][j * m.c + k % m.c] += m.block(e)[k];
                }
            }
        }
        d
    }

    /// The transpose `t` of `a` with its blocks stored.
    fn stored(t: &Transposed, a: &Bsr) -> Bsr {
        Bsr::from_rows(
            t.rows,
            t.cols,
            (t.r, t.c),
            || (),
            |_, i, columns, values| {
                for e in t.offsets[i]..t.offsets[i + 1] {
                    columns.push(t.columns[e]);
                    let b = a.block(t.entries[e]);
                    values.extend((0..t.r * t.c).map(|k| b[(k % t.c) * t.r + k / t.c]));
                }
            },
        )
    }

    #[test]
    fn product_transpose_and_mul_agree_with_dense_algebra() {
        let a = vec![
            vec![2.0, -1.0, 0.0, 0.0],
            vec![0.5, 3.0, 0.0, 1.0],
            vec![0.0, 0.0, 4.0, 0.0],
            vec![1.0, 0.0, -2.0, 5.0],
        ];
        let p = vec![
            vec![1.0, 0.0, 0.0],
            vec![2.0, 0.0, 0.0],
            vec![0.0, 1.0, -1.0],
            vec![0.0, 3.0, 0.5],
        ];
        let am = dense_to_bsr(&a, (2, 2));
        let pm = dense_to_bsr(&p, (2, 3));
        let ap = to_dense(&am.product(&pm));
        for i in 0..4 {
            for j in 0..3 {
                let want: f64 = (0..4).map(|k| a[i][k] * p[k][j]).sum();
                assert_eq!(ap[i][j], want);
            }
        }
        let pt = to_dense(&stored(&pm.transposed(), &pm));
        for i in 0..4 {
            for j in 0..3 {
                assert_eq!(pt[j][i], p[i][j]);
            }
        }
        let z = [0.5, -1.0, 2.0, 4.0];
        let mut w = [0.0; 3];
        pm.transposed().mul(&pm, &z, &mut w);
        for j in 0..3 {
            assert_eq!(w[j], (0..4).map(|k| p[k][j] * z[k]).sum::<f64>());
        }
        let x = [1.0, -2.0, 0.5, 3.0];
        let mut y = [0.0; 4];
        am.mul(&x, &mut y);
        for i in 0..4 {
            assert_eq!(y[i], (0..4).map(|k| a[i][k] * x[k]).sum::<f64>());
        }
        assert_eq!(am.find(1, 0), Some(am.offsets[1]));
    }

    /// A `rows × cols` matrix of `r × c` blocks with up to `per_row`
    /// pseudo-random blocks per row (columns in no particular order).
    fn scattered(
        rows: usize,
        cols: usize,
        (r, c): (usize, usize),
        per_row: usize,
        seed: u64,
    ) -> Bsr {
        let hash = |i: usize, k: usize| {
            let mut h = (seed ^ (i as u64) << 20 ^ k as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15);
            h ^= h >> 31;
            h.wrapping_mul(0xbf58_476d_1ce4_e5b9) >> 33
        };
        Bsr::from_rows(
            rows,
            cols,
            (r, c),
            || (),
            |_, i, columns, values| {
                for k in 0..1 + hash(i, 0) as usize % per_row {
                    let j = (hash(i, 1000 + k) as usize % cols) as u32;
                    if !columns.contains(&j) {
                        columns.push(j);
                        values.extend(
                            (0..r * c).map(|l| hash(i, 2000 + 100 * k + l) as f64 / 1e9 - 2.0),
                        );
                    }
                }
            },
        )
    }

    #[test]
    fn galerkin_in_slices_equals_the_whole_product_bit_for_bit() {
        let a = scattered(40, 40, (3, 3), 6, 7);
        let p = scattered(40, 9, (3, 6), 3, 11);
        let r = p.transposed();
        let whole = stored(&r, &p).product(&a.product(&p));
        for slice in [1, 3, 7, 40, 100] {
            let sliced = galerkin_in_slices(&r, &a, &p, slice);
            assert_eq!(sliced.offsets, whole.offsets, "slice {slice}");
            assert_eq!(sliced.columns, whole.columns, "slice {slice}");
            let bits = |m: &Bsr| m.values.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&sliced), bits(&whole), "slice {slice}");
        }
        assert_eq!((whole.rows, whole.cols, whole.r, whole.c), (9, 9, 6, 6));
    }

    #[test]
    fn inverse_with_pivoting() {
        let a = [0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0];
        let inv = invert(&a, 3).expect("regular");
        for i in 0..3 {
            for j in 0..3 {
                let v: f64 = (0..3).map(|k| a[i * 3 + k] * inv[k * 3 + j]).sum();
                assert!((v - f64::from(u8::from(i == j))).abs() < 1e-14);
            }
        }
        assert!(invert(&[1.0, 2.0, 2.0, 4.0], 2).is_none());
        let lu = DenseLu::factor(a.to_vec(), 3).expect("regular");
        let mut x = [1.0, -2.0, 0.5];
        lu.solve(&mut x);
        for i in 0..3 {
            let v: f64 = (0..3).map(|k| a[i * 3 + k] * x[k]).sum();
            assert!((v - [1.0, -2.0, 0.5][i]).abs() < 1e-14);
        }
    }
}
