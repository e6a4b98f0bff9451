//! A small rasteriser into an RGB buffer: scanline triangle fill with a depth
//! buffer, and antialiased lines (Xiaolin Wu) blended over it.
//!
//! Pixel `(i, j)` covers `[i, i+1) × [j, j+1)`; a triangle fills the pixels
//! whose centre `(i + ½, j + ½)` lies inside it (left edge inclusive, right
//! edge exclusive), computing each edge's crossing from its endpoints in one
//! fixed order, so two triangles sharing an edge leave neither gap nor
//! overlap. Depth is the distance from the viewer (smaller is nearer),
//! interpolated on the triangle's plane; a pixel is written when its depth is
//! `≤` the stored one (in 2D every depth is 0 and the last cell drawn wins).

use crate::colour::Rgb;

/// An RGB buffer with a depth buffer and a clip rectangle.
pub struct Canvas<'a> {
    width: usize,
    rgb: &'a mut [u8],
    depth: Vec<f32>,
    /// Clip rectangle `[x0, y0, x1, y1)` in pixels.
    clip: [i64; 4],
}

impl<'a> Canvas<'a> {
    /// A canvas over `rgb` (`3·width·height` bytes) drawing only inside
    /// `clip = [x0, y0, x1, y1)`.
    pub fn new(rgb: &'a mut [u8], width: usize, clip: [i64; 4]) -> Canvas<'a> {
        let height = rgb.len() / (3 * width);
        Canvas {
            width,
            rgb,
            depth: vec![f32::INFINITY; width * height],
            clip,
        }
    }

    /// Fills triangle `p` (pixel x, pixel y, depth) with `colour`.
    pub fn triangle(&mut self, p: [[f64; 3]; 3], colour: Rgb) {
        let mut v = p;
        v.sort_by(|a, b| a[1].total_cmp(&b[1]).then(a[0].total_cmp(&b[0])));
        let [a, b, c] = v;
        let area = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
        if area == 0.0 || !area.is_finite() {
            return;
        }
        // Depth plane z = a.z + dzdx (x − a.x) + dzdy (y − a.y).
        let dzdx = ((b[2] - a[2]) * (c[1] - a[1]) - (c[2] - a[2]) * (b[1] - a[1])) / area;
        let dzdy = ((c[2] - a[2]) * (b[0] - a[0]) - (b[2] - a[2]) * (c[0] - a[0])) / area;
        let row0 = ((a[1] - 0.5).ceil() as i64).max(self.clip[1]);
        let row1 = ((c[1] - 0.5).ceil() as i64).min(self.clip[3]);
        for row in row0..row1 {
            let y = row as f64 + 0.5;
            let long = crossing(a, c, y);
            let short = if y < b[1] {
                crossing(a, b, y)
            } else {
                crossing(b, c, y)
            };
            let (xl, xr) = (long.min(short), long.max(short));
            let col0 = ((xl - 0.5).ceil() as i64).max(self.clip[0]);
            let col1 = ((xr - 0.5).ceil() as i64).min(self.clip[2]);
            for col in col0..col1 {
                let x = col as f64 + 0.5;
                let z = (a[2] + dzdx * (x - a[0]) + dzdy * (y - a[1])) as f32;
                let k = row as usize * self.width + col as usize;
                if z <= self.depth[k] {
                    self.depth[k] = z;
                    self.rgb[3 * k..3 * k + 3].copy_from_slice(&colour);
                }
            }
        }
    }

    /// Fills a polygon (points in order) as the fan of triangles from its first point.
    pub fn polygon(&mut self, p: &[[f64; 3]], colour: Rgb) {
        for k in 1..p.len().saturating_sub(1) {
            self.triangle([p[0], p[k], p[k + 1]], colour);
        }
    }

    /// Draws an antialiased 1-pixel line from `a` to `b` in `colour` with
    /// opacity `alpha`, where its depth is within `tolerance` of the depth
    /// buffer or nearer (hidden parts of 3D edges stay hidden).
    pub fn line(&mut self, a: [f64; 3], b: [f64; 3], colour: Rgb, alpha: f64, tolerance: f64) {
        let steep = (b[1] - a[1]).abs() > (b[0] - a[0]).abs();
        let (mut a, mut b) = if steep {
            ([a[1], a[0], a[2]], [b[1], b[0], b[2]])
        } else {
            (a, b)
        };
        if a[0] > b[0] {
            std::mem::swap(&mut a, &mut b);
        }
        if !a.iter().chain(&b).all(|x| x.is_finite()) {
            return;
        }
        let dx = b[0] - a[0];
        let gradient = if dx == 0.0 { 0.0 } else { (b[1] - a[1]) / dx };
        let dz = if dx == 0.0 { 0.0 } else { (b[2] - a[2]) / dx };
        // Stepped only across the clip rectangle, however long the line.
        let (lo, hi) = if steep {
            (self.clip[1], self.clip[3])
        } else {
            (self.clip[0], self.clip[2])
        };
        let start = ((a[0] - 0.5).round() as i64).max(lo);
        let end = ((b[0] - 0.5).round() as i64).min(hi - 1);
        for i in start..=end {
            let x = i as f64 + 0.5;
            let t = (x - a[0]).clamp(0.0, dx.max(0.0));
            let y = a[1] + gradient * t - 0.5;
            let z = a[2] + dz * t;
            let j = y.floor();
            let f = y - j;
            for (jj, cover) in [(j as i64, 1.0 - f), ((j as i64).saturating_add(1), f)] {
                let (px, py) = if steep { (jj, i) } else { (i, jj) };
                self.blend(px, py, z, tolerance, colour, alpha * cover);
            }
        }
    }

    fn blend(&mut self, x: i64, y: i64, z: f64, tolerance: f64, colour: Rgb, alpha: f64) {
        if x < self.clip[0] || x >= self.clip[2] || y < self.clip[1] || y >= self.clip[3] {
            return;
        }
        let k = y as usize * self.width + x as usize;
        if z > f64::from(self.depth[k]) + tolerance {
            return;
        }
        for (c, e) in self.rgb[3 * k..3 * k + 3].iter_mut().zip(colour) {
            *c = (f64::from(*c) * (1.0 - alpha) + f64::from(e) * alpha).round() as u8;
        }
    }
}

/// The x where segment `p → q` (`p.y ≤ q.y`) crosses height `y`.
fn crossing(p: [f64; 3], q: [f64; 3], y: f64) -> f64 {
    if q[1] == p[1] {
        p[0].min(q[0])
    } else {
        p[0] + (y - p[1]) * (q[0] - p[0]) / (q[1] - p[1])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn count(rgb: &[u8], c: Rgb) -> usize {
        rgb.chunks(3).filter(|p| *p == c).count()
    }

    #[test]
    fn two_triangles_of_a_square_cover_it_exactly_once() {
        let lower = [[2., 2., 0.], [12., 2., 0.], [12., 12., 0.]];
        let upper = [[2., 2., 0.], [12., 12., 0.], [2., 12., 0.]];
        let fill = |tris: &[[[f64; 3]; 3]]| {
            let mut rgb = vec![0u8; 3 * 20 * 20];
            let mut canvas = Canvas::new(&mut rgb, 20, [0, 0, 20, 20]);
            for t in tris {
                canvas.triangle(*t, [255, 0, 0]);
            }
            count(&rgb, [255, 0, 0])
        };
        // 45 pixel centres strictly on each side, the 10 on the diagonal on one side only.
        assert_eq!(fill(&[lower]) + fill(&[upper]), 100);
        assert_eq!(fill(&[lower]).min(fill(&[upper])), 45);
        assert_eq!(fill(&[lower, upper]), 100);
    }

    #[test]
    fn nearer_triangles_hide_farther_ones_whatever_the_order() {
        let mut rgb = vec![0u8; 3 * 10 * 10];
        let mut canvas = Canvas::new(&mut rgb, 10, [0, 0, 10, 10]);
        let tri = |z: f64| [[0., 0., z], [10., 0., z], [0., 10., z]];
        canvas.triangle(tri(1.0), [0, 0, 255]);
        canvas.triangle(tri(2.0), [255, 0, 0]);
        assert_eq!(count(&rgb, [255, 0, 0]), 0);
        assert_eq!(count(&rgb, [0, 0, 255]), 45);
    }

    #[test]
    fn clip_rectangle_bounds_fills_and_lines() {
        let mut rgb = vec![0u8; 3 * 10 * 10];
        let mut canvas = Canvas::new(&mut rgb, 10, [2, 2, 8, 8]);
        canvas.polygon(
            &[
                [-5., -5., 0.],
                [15., -5., 0.],
                [15., 15., 0.],
                [-5., 15., 0.],
            ],
            [9, 9, 9],
        );
        canvas.line([0., 5.5, 0.], [10., 5.5, 0.], [200, 200, 200], 1.0, 0.0);
        assert_eq!(count(&rgb, [9, 9, 9]) + count(&rgb, [200, 200, 200]), 36);
        assert_eq!(count(&rgb, [200, 200, 200]), 6);
    }

    #[test]
    fn huge_lines_are_clipped_not_stepped() {
        let mut rgb = vec![0u8; 3 * 10 * 10];
        let mut canvas = Canvas::new(&mut rgb, 10, [0, 0, 10, 10]);
        canvas.line([-1e300, 5.5, 0.], [1e300, 5.5, 0.], [7, 7, 7], 1.0, 0.0);
        canvas.line([5.5, -1e18, 0.], [5.5, 1e18, 0.], [7, 7, 7], 1.0, 0.0);
        canvas.line([f64::NAN, 0., 0.], [5., 5., 0.], [8, 8, 8], 1.0, 0.0);
        assert_eq!(count(&rgb, [7, 7, 7]), 19);
        assert_eq!(count(&rgb, [8, 8, 8]), 0);
    }
}
