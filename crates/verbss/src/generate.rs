//! Built-in meshes: the demo's NACA0012 airfoil O-grid.

use crate::error::{Error, Result};
use crate::mesh::{CellKind, Cells, Group, Mesh};

/// Settings of [`naca0012`]: an O-grid of `around × layers` nodes.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct AirfoilGrid {
    /// Nodes around the airfoil (even, ≥ 8).
    pub around: usize,
    /// Node rings from the airfoil (ring 0) to the farfield (≥ 2).
    pub layers: usize,
    /// Farfield radius in chords, about the mid-chord point.
    pub farfield_radius: f64,
}

impl Default for AirfoilGrid {
    /// 150 × 30 = 4,500 nodes and 8,700 triangles (the paper's §4.2 mesh has
    /// 4,485 nodes and 8,664 triangles), farfield at 15 chords.
    fn default() -> Self {
        AirfoilGrid {
            around: 150,
            layers: 30,
            farfield_radius: 15.0,
        }
    }
}

/// Half-thickness of the NACA0012 section with a closed trailing edge:
/// `y = 0.6 (0.2969 √x − 0.1260 x − 0.3516 x² + 0.2843 x³ − 0.1036 x⁴)`, `x ∈ [0, 1]`.
pub fn naca0012_thickness(x: f64) -> f64 {
    0.6 * (0.2969 * x.sqrt() - 0.1260 * x - 0.3516 * x * x + 0.2843 * x.powi(3)
        - 0.1036 * x.powi(4))
}

/// A triangular O-grid around a NACA0012 airfoil of unit chord (leading edge
/// at the origin, trailing edge at (1, 0), closed).
///
/// Surface node `j` sits at `β = 2πj/n`, on the upper side for `β ≤ π`,
/// counter-clockwise from the trailing edge, at
/// `x = ¼ (1 − cos πu) + ½ (1 − cos(πu/2))` with `u = |1 − β/π|` (0 at the
/// leading edge, 1 at the trailing edge): quadratic clustering at the
/// leading edge and half the mid-chord spacing at the trailing edge (full
/// cosine spacing would make trailing-edge cells so thin that the wake
/// behind them is a sliver of ρ ≈ 0.002 elements). Its ray leaves the wall
/// along the wall normal `n` (smoothed over a few neighbours, so that the
/// trailing edge's turn is shared by the rays beside it) and bends to the
/// straight line towards the farfield point `F = (½ + R cos β, R sin β)`:
/// `x(t) = S + t (F − S) + L t (1 − t)⁴ (n − e)`, `L = |F − S|`,
/// `e = (F − S)/L`. The nodes along a ray follow a geometric series in `t L`
/// whose first spacing is the local surface spacing (near-square cells at the
/// wall) and whose ratio is chosen to reach the farfield. Each quad is split
/// into two counter-clockwise triangles along alternating diagonals, so that
/// the diagonals of the first ring meet at the trailing edge. Groups:
/// `airfoil` and `farfield`.
pub fn naca0012(grid: &AirfoilGrid) -> Result<Mesh> {
    let (n, m) = (grid.around, grid.layers);
    if n < 8 || n % 2 != 0 || m < 2 || grid.farfield_radius <= 1.0 {
        return Err(Error::InvalidSetting(format!(
            "airfoil grid {n} × {m} with farfield radius {} (expected an even count ≥ 8 around, ≥ 2 layers, radius > 1)",
            grid.farfield_radius
        )));
    }
    let pi = std::f64::consts::PI;
    let tau = 2.0 * pi;
    let surface: Vec<[f64; 2]> = (0..n)
        .map(|j| {
            let u = (1.0 - 2.0 * j as f64 / n as f64).abs();
            let x = 0.25 * (1.0 - (pi * u).cos()) + 0.5 * (1.0 - (0.5 * pi * u).cos());
            let y = naca0012_thickness(x);
            match j {
                0 => [1.0, 0.0],
                _ if 2 * j <= n => [x, y],
                _ => [x, -y],
            }
        })
        .collect();
    let dist = |a: [f64; 2], b: [f64; 2]| ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt();
    let normals = smoothed_normals(&surface);
    let mut coords = vec![0.0; 2 * n * m];
    for j in 0..n {
        let s = surface[j];
        let beta = tau * j as f64 / n as f64;
        let far = [
            0.5 + grid.farfield_radius * beta.cos(),
            grid.farfield_radius * beta.sin(),
        ];
        let spacing = 0.5 * (dist(s, surface[(j + 1) % n]) + dist(s, surface[(j + n - 1) % n]));
        let length = dist(s, far);
        let e = [(far[0] - s[0]) / length, (far[1] - s[1]) / length];
        let bend = [normals[j][0] - e[0], normals[j][1] - e[1]];
        let ratio = growth_ratio(spacing, length, m - 1);
        let mut d = 0.0;
        let mut step = spacing;
        for k in 0..m {
            let t = if k == m - 1 { 1.0 } else { d / length };
            let w = length * t * (1.0 - t).powi(BEND_DECAY);
            let node = k * n + j;
            coords[2 * node] = s[0] + t * (far[0] - s[0]) + w * bend[0];
            coords[2 * node + 1] = s[1] + t * (far[1] - s[1]) + w * bend[1];
            d += step;
            step *= ratio;
        }
    }
    let node = |j: usize, k: usize| k * n + j % n;
    let mut cells = Cells::new();
    for k in 0..m - 1 {
        for j in 0..n {
            let (a, b, c, d) = (
                node(j, k),
                node(j + 1, k),
                node(j + 1, k + 1),
                node(j, k + 1),
            );
            if (j + k) % 2 == 0 {
                cells.push(CellKind::Triangle, &[a, c, b]);
                cells.push(CellKind::Triangle, &[a, d, c]);
            } else {
                cells.push(CellKind::Triangle, &[a, d, b]);
                cells.push(CellKind::Triangle, &[b, d, c]);
            }
        }
    }
    let ring = |name: &str, k: usize| {
        let mut facets = Cells::new();
        for j in 0..n {
            facets.push(CellKind::Line, &[node(j, k), node(j + 1, k)]);
        }
        Group {
            name: name.to_string(),
            tag: None,
            facets,
        }
    };
    let groups = vec![ring("airfoil", 0), ring("farfield", m - 1)];
    Mesh::new(2, coords, cells, groups)
}

/// How fast a ray turns from the wall normal to the straight line to the farfield.
const BEND_DECAY: i32 = 4;

/// Smoothing passes of the wall normals (spreads the trailing edge's turn
/// over the rays beside it).
const NORMAL_PASSES: usize = 4;

/// Outward unit normals of a closed counter-clockwise polygon at its
/// vertices (bisectors of the adjacent edges' normals), smoothed by
/// [`NORMAL_PASSES`] passes of `n_j ← unit(n_{j−1} + 2 n_j + n_{j+1})`.
fn smoothed_normals(p: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let n = p.len();
    let unit = |v: [f64; 2]| {
        let l = (v[0] * v[0] + v[1] * v[1]).sqrt();
        [v[0] / l, v[1] / l]
    };
    let edge_normal = |a: [f64; 2], b: [f64; 2]| unit([b[1] - a[1], a[0] - b[0]]);
    let mut normals: Vec<[f64; 2]> = (0..n)
        .map(|j| {
            let before = edge_normal(p[(j + n - 1) % n], p[j]);
            let after = edge_normal(p[j], p[(j + 1) % n]);
            unit([before[0] + after[0], before[1] + after[1]])
        })
        .collect();
    for _ in 0..NORMAL_PASSES {
        normals = (0..n)
            .map(|j| {
                let (a, b, c) = (normals[(j + n - 1) % n], normals[j], normals[(j + 1) % n]);
                unit([a[0] + 2.0 * b[0] + c[0], a[1] + 2.0 * b[1] + c[1]])
            })
            .collect();
    }
    normals
}

/// The ratio `r ≥ 1` of a geometric series of `cells` spacings starting at
/// `first` that sums to `length`: `first (rᶜ − 1)/(r − 1) = length` (1 when
/// uniform spacing already reaches it), by bisection.
fn growth_ratio(first: f64, length: f64, cells: usize) -> f64 {
    let sum = |r: f64| first * (0..cells).map(|i| r.powi(i as i32)).sum::<f64>();
    if sum(1.0) >= length {
        return 1.0;
    }
    let (mut lo, mut hi) = (1.0, 2.0);
    while sum(hi) < length {
        hi *= 2.0;
    }
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if sum(mid) < length {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::corner_jacobian;

    #[test]
    fn default_grid_is_paper_sized_valid_and_closed() {
        let mesh = naca0012(&AirfoilGrid::default()).unwrap();
        assert_eq!(mesh.node_count(), 4500);
        assert_eq!(mesh.cell_count(), 8700);
        for (_, nodes) in mesh.cells.iter() {
            let j = corner_jacobian::<2>(&mesh.coords, nodes, &[0, 1, 2, 0]);
            assert!(j > 0.0);
        }
        let airfoil = mesh.group("airfoil").unwrap().nodes();
        assert_eq!(airfoil.len(), 150);
        assert_eq!(mesh.point(0), &[1.0, 0.0]);
        assert_eq!(mesh.point(75), &[0.0, 0.0]);
        let far = mesh.group("farfield").unwrap().nodes();
        for i in far {
            let p = mesh.point(i);
            let r = ((p[0] - 0.5).powi(2) + p[1] * p[1]).sqrt();
            assert!((r - 15.0).abs() < 1e-12);
        }
    }

    #[test]
    fn thickness_is_twelve_percent_and_closed() {
        assert_eq!(naca0012_thickness(0.0), 0.0);
        assert!(naca0012_thickness(1.0).abs() < 1e-15);
        let max = (0..1000)
            .map(|i| naca0012_thickness(i as f64 / 1000.0))
            .fold(0.0, f64::max);
        assert!((2.0 * max - 0.12).abs() < 1e-3);
    }

    #[test]
    fn growth_ratio_sums_to_the_length() {
        let r = growth_ratio(0.01, 15.0, 29);
        let sum: f64 = (0..29).map(|i| 0.01 * r.powi(i)).sum();
        assert!((sum - 15.0).abs() < 1e-9);
        assert_eq!(growth_ratio(1.0, 2.0, 5), 1.0);
    }

    #[test]
    fn rejects_odd_counts() {
        let grid = AirfoilGrid {
            around: 9,
            ..AirfoilGrid::default()
        };
        assert_eq!(
            naca0012(&grid).unwrap_err().to_string(),
            "invalid setting: airfoil grid 9 × 30 with farfield radius 15 (expected an even count ≥ 8 around, ≥ 2 layers, radius > 1)"
        );
    }
}
