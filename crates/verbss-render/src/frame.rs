//! The picture's layout and everything drawn with plotters around the mesh:
//! header, axes, colour bar, the inverted swatch.
//!
//! Sizes scale with the width `W` (`s = W/1600`): header 56s, margin 24s,
//! legend column 210s, axis label areas 90s (left) and 64s (bottom) when the
//! picture's axes are mesh coordinates. The plot keeps equal scales on both
//! axes: its height is its width times `Δv/Δu`, with `Δv/Δu` first widened
//! into `[1/4, 7/5]` about the window's centre.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use verbss::error::{Error, Result};

use crate::colour::{self, Rgb};
use crate::scene::Scene;
use crate::Options;

/// Pixel layout of a picture and the window it shows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Layout {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The plot rectangle `[x0, y0, x1, y1)` in pixels.
    pub plot: [i64; 4],
    /// The window `[u0, u1, v0, v1]` the plot shows.
    pub window: [f64; 4],
    scale: f64,
    top: i64,
    margin: i64,
    legend: i64,
    bar: i64,
}

impl Layout {
    /// The layout of `scene` drawn with `options`.
    pub fn new(scene: &Scene, options: &Options) -> Result<Layout> {
        if !(200..=10_000).contains(&options.width) {
            return Err(Error::InvalidSetting(format!(
                "picture width {} (expected 200 to 10000 pixels)",
                options.width
            )));
        }
        let mut w = match options.view {
            Some(v) => {
                check_view(v)?;
                v
            }
            None => {
                let b = scene.bounds();
                let pad = 0.02 * (b[1] - b[0]).max(b[3] - b[2]).max(f64::MIN_POSITIVE);
                let w = [b[0] - pad, b[1] + pad, b[2] - pad, b[3] + pad];
                if !drawable(w) {
                    return Err(Error::InvalidSetting(format!(
                        "the picture's extent {},{},{},{} cannot be drawn (not finite)",
                        b[0], b[1], b[2], b[3]
                    )));
                }
                w
            }
        };
        let (du, dv) = (w[1] - w[0], w[3] - w[2]);
        if dv < 0.25 * du {
            let c = 0.5 * (w[2] + w[3]);
            w[2] = c - 0.125 * du;
            w[3] = c + 0.125 * du;
        } else if dv > 1.4 * du {
            let c = 0.5 * (w[0] + w[1]);
            w[0] = c - dv / 2.8;
            w[1] = c + dv / 2.8;
        }
        let s = f64::from(options.width) / 1600.0;
        let px = |x: f64| (x * s).round() as i64;
        let (top, margin, legend) = (px(56.0), px(24.0), px(210.0));
        let (ylab, xlab) = match scene.axes {
            Some(_) => (px(90.0), px(64.0)),
            None => (0, 0),
        };
        let width = i64::from(options.width);
        let plot_w = width - margin - ylab - legend;
        // The ratio first: the spans themselves may be near f64::MAX.
        let plot_h = (plot_w as f64 * ((w[3] - w[2]) / (w[1] - w[0]))).round() as i64;
        let bar = ((0.7 * plot_h as f64) as i64).clamp(px(150.0), px(480.0));
        let height = (top + plot_h + xlab + margin).max(top + bar + px(170.0));
        Ok(Layout {
            width: options.width,
            height: height as u32,
            plot: [margin + ylab, top, width - legend, top + plot_h],
            window: w,
            scale: s,
            top,
            margin,
            legend,
            bar,
        })
    }

    /// Pixel position of picture point `(u, v, depth)` (depth kept).
    pub fn map(&self, p: [f64; 3]) -> [f64; 3] {
        let [x0, y0, x1, y1] = self.plot.map(|v| v as f64);
        let w = &self.window;
        [
            x0 + (p[0] - w[0]) / (w[1] - w[0]) * (x1 - x0),
            y1 - (p[1] - w[2]) / (w[3] - w[2]) * (y1 - y0),
            p[2],
        ]
    }

    /// Length in pixels of segment `a → b` of the picture.
    pub fn length(&self, a: [f64; 3], b: [f64; 3]) -> f64 {
        let [x0, y0, x1, y1] = self.plot.map(|v| v as f64);
        let w = &self.window;
        let du = (b[0] - a[0]) / (w[1] - w[0]) * (x1 - x0);
        let dv = (b[1] - a[1]) / (w[3] - w[2]) * (y1 - y0);
        du.hypot(dv)
    }

    fn px(&self, x: f64) -> i32 {
        (x * self.scale).round() as i32
    }

    fn font(&self, size: f64) -> TextStyle<'static> {
        ("sans-serif", size * self.scale).into_font().color(&BLACK)
    }
}

/// Refuses a window `[x0, x1, y0, y1]` that cannot be drawn (see [`Options::view`]).
pub fn check_view(v: [f64; 4]) -> Result<()> {
    if drawable(v) {
        return Ok(());
    }
    Err(Error::InvalidSetting(format!(
        "view window {},{},{},{} (expected x0 < x1 and y0 < y1, each span finite \
         and above 1e-12 of the coordinates)",
        v[0], v[1], v[2], v[3]
    )))
}

/// Whether window `[x0, x1, y0, y1]` can be drawn: finite, positive spans
/// that the coordinates resolve (above 1e-12 of them).
fn drawable(w: [f64; 4]) -> bool {
    let span = |a: f64, b: f64| {
        let d = b - a;
        d.is_finite() && d > 0.0 && d > 1e-12 * a.abs().max(b.abs())
    };
    span(w[0], w[1]) && span(w[2], w[3])
}

/// The power of ten an axis over `[a, b]` counts its ticks in: 0 (plain
/// numbers) for spans from 1e-4 to 1e6, else the span's own (ticks in
/// scientific notation, however far the window is from 1).
fn label_exponent(a: f64, b: f64) -> i32 {
    let e = (b - a).log10().floor() as i32;
    if (-4..=5).contains(&e) {
        0
    } else {
        e
    }
}

/// The axis range `[a, b]` counted in units of `10^e`.
fn scaled(a: f64, b: f64, e: i32) -> std::ops::Range<f64> {
    let unit = 10f64.powi(e);
    a / unit..b / unit
}

/// The label of tick `t` counted in units of `10^e` (`e ≠ 0`), in
/// scientific notation to a hundredth of the unit, e.g. `1.00005e300`.
fn label(t: f64, e: i32) -> String {
    let n = (t * 100.0).round();
    if n == 0.0 {
        return "0".into();
    }
    let digits = format!("{}", n.abs() as u64);
    let sign = if n < 0.0 { "-" } else { "" };
    let (head, tail) = digits.split_at(1);
    let tail = tail.trim_end_matches('0');
    let exponent = i64::from(e) - 2 + digits.len() as i64 - 1;
    let point = if tail.is_empty() { "" } else { "." };
    format!("{sign}{head}{point}{tail}e{exponent}")
}

fn rgb(c: Rgb) -> RGBColor {
    RGBColor(c[0], c[1], c[2])
}

/// Draws the background, header, axes and legend of `scene` on `root`.
pub fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    layout: &Layout,
    scene: &Scene,
    title: &str,
) -> Result<()> {
    draw_inner(root, layout, scene, title).map_err(|e| Error::Render(e.to_string()))
}

fn draw_inner<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    layout: &Layout,
    scene: &Scene,
    title: &str,
) -> std::result::Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    crate::register_font();
    let l = layout;
    root.fill(&WHITE)?;
    let header = format!(
        "{title}{}min quality {:.4}  ·  {} inverted  ·  {} cells",
        if title.is_empty() { "" } else { "   —   " },
        scene.min_quality,
        scene.inverted,
        scene.cells
    );
    root.draw(&Text::new(
        header,
        (l.margin as i32, l.px(16.0)),
        l.font(26.0),
    ))?;
    if let Some([u, v]) = scene.axes {
        let [x0, _, x1, y1] = l.plot;
        let w = l.window;
        let (ex, ey) = (label_exponent(w[0], w[1]), label_exponent(w[2], w[3]));
        let mut chart = ChartBuilder::on(root)
            .margin_left(l.margin as i32)
            .margin_top(l.top as i32)
            .margin_right((i64::from(l.width) - x1) as i32)
            .margin_bottom((i64::from(l.height) - y1 - i64::from(l.px(64.0))).max(0) as i32)
            .x_label_area_size(l.px(64.0))
            .y_label_area_size((x0 - l.margin) as i32)
            .build_cartesian_2d(scaled(w[0], w[1], ex), scaled(w[2], w[3], ey))?;
        let (fx, fy) = (|t: &f64| label(*t, ex), |t: &f64| label(*t, ey));
        let mut axes = chart.configure_mesh();
        axes.disable_mesh()
            .x_desc(u)
            .y_desc(v)
            .x_labels(8)
            .y_labels(8)
            .label_style(l.font(20.0))
            .axis_desc_style(l.font(24.0));
        if ex != 0 {
            axes.x_label_formatter(&fx);
        }
        if ey != 0 {
            axes.y_label_formatter(&fy);
        }
        axes.draw()?;
    }
    let bx = i64::from(l.width) - l.legend + (52.0 * l.scale) as i64;
    let (bw, by, bh) = (l.px(30.0), (l.top + l.px(44.0) as i64) as i32, l.bar as i32);
    let bx = bx as i32;
    root.draw(&Text::new("quality", (bx, by - l.px(36.0)), l.font(24.0)))?;
    for row in 0..bh {
        let q = 1.0 - f64::from(row) / f64::from(bh - 1);
        root.draw(&Rectangle::new(
            [(bx, by + row), (bx + bw, by + row + 1)],
            rgb(colour::quality(q)).filled(),
        ))?;
    }
    root.draw(&Rectangle::new([(bx, by), (bx + bw, by + bh)], BLACK))?;
    let y_of = |q: f64| by + ((1.0 - q) * f64::from(bh - 1)).round() as i32;
    let label = l.font(20.0).pos(Pos::new(HPos::Left, VPos::Center));
    for k in 0..=5 {
        let q = f64::from(k) / 5.0;
        let y = y_of(q);
        root.draw(&PathElement::new(
            vec![(bx + bw, y), (bx + bw + l.px(7.0), y)],
            BLACK,
        ))?;
        root.draw(&Text::new(
            format!("{q:.1}"),
            (bx + bw + l.px(11.0), y),
            label.clone(),
        ))?;
    }
    if scene.min_quality.is_finite() {
        let y = y_of(scene.min_quality);
        let stroke = BLACK.stroke_width(l.px(3.0).max(1) as u32);
        root.draw(&PathElement::new(
            vec![(bx - l.px(8.0), y), (bx + bw, y)],
            stroke,
        ))?;
        root.draw(&Text::new(
            "min",
            (bx - l.px(12.0), y),
            l.font(18.0).pos(Pos::new(HPos::Right, VPos::Center)),
        ))?;
    }
    let sy = by + bh + l.px(30.0);
    root.draw(&Rectangle::new(
        [(bx, sy), (bx + bw, sy + bw)],
        rgb(colour::INVERTED).filled(),
    ))?;
    root.draw(&Rectangle::new([(bx, sy), (bx + bw, sy + bw)], BLACK))?;
    root.draw(&Text::new(
        format!("inverted: {}", scene.inverted),
        (bx + bw + l.px(11.0), sy + bw / 2),
        label,
    ))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn far_and_tiny_windows_label_their_ticks_in_scientific_notation() {
        assert_eq!(label_exponent(0.999, 1.001), 0);
        assert_eq!(label_exponent(-1e307, 1e307), 307);
        assert_eq!(label_exponent(0.0, 1e-300), -300);
        assert_eq!(label(1.5, -300), "1.5e-300");
        assert_eq!(label(-2.0, 307), "-2e307");
        assert_eq!(label(100000.25, 295), "1.0000025e300");
        assert_eq!(label(1e-9, 12), "0");
        let r = scaled(1e300, 1.00001e300, label_exponent(1e300, 1.00001e300));
        assert!((1.0..=10.0).contains(&(r.end - r.start)), "{r:?}");
    }
}
