//! `report.html`: one self-contained page (no network, no script) that shows a
//! run — pictures of the mesh, the per-step numbers of `report.json` as charts
//! and as a table, the slowest step's convergence and the settings.
//!
//! Every number comes from the run's [`Report`], the same value that
//! `report.json` holds: the table prints each one with Rust's shortest
//! round-trip formatting, so it parses back to the identical `f64`. Charts are
//! SVG drawn by plotters and inlined; pictures are PNG inlined as
//! `data:` URLs.
//!
//! Charts, each against the step `n` (step 0 is the input mesh):
//! - minimum and mean element quality;
//! - the element count of each of the paper's five quality bins (log scale,
//!   zero counts left out);
//! - solver sweeps and wall seconds per step;
//! - the eq.-8 value (mean absolute change of the interior components) of
//!   every sweep of the slowest step (most seconds), when the run recorded
//!   it ([`verbss::solve::SolveParams::record_history`]).

use std::fmt::Write as _;
use std::io::Write;
use std::ops::Range;
use std::path::Path;

use base64::Engine as _;
use plotters::coord::Shift;
use plotters::prelude::*;

use verbss::deform::StepReport;
use verbss::error::{Error, Result};
use verbss::io::write_atomic;
use verbss::quality::BIN_EDGES;
use verbss::report::Report;

use crate::{colour, Image};

/// A picture of the mesh with its caption.
#[derive(Debug, Clone)]
pub struct Picture {
    /// What it shows (e.g. `step 40 (worst)`).
    pub caption: String,
    /// The picture.
    pub image: Image,
}

/// Chart size in pixels.
const CHART: (u32, u32) = (720, 360);

/// Writes the page for `report` with `pictures` to `path` (atomically).
pub fn write(path: &Path, report: &Report, pictures: &[Picture]) -> Result<()> {
    let page = html(report, pictures)?;
    write_atomic(path, |w: &mut dyn Write| w.write_all(page.as_bytes()))
}

/// The page for `report` with `pictures`.
pub fn html(report: &Report, pictures: &[Picture]) -> Result<String> {
    let steps = &report.steps;
    let mut page = String::new();
    let title = format!("verbss report: {}", escape(&report.mesh));
    let _ = write!(
        page,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{title}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n<h1>{title}</h1>\n"
    );
    let accepted = steps
        .iter()
        .filter(|s| s.inverted == 0)
        .count()
        .saturating_sub(1);
    let _ = write!(
        page,
        "<p class=\"outcome {}\">{}</p>\n<p>{}D mesh, {} nodes, {} cells; {} of {} steps accepted; verbss {}.</p>\n",
        if report.outcome == "completed" { "ok" } else { "failed" },
        escape(&report.outcome),
        report.dim,
        report.nodes,
        report.cells,
        accepted,
        report.step_count,
        report.verbss
    );
    if !pictures.is_empty() {
        page.push_str("<h2>The mesh</h2>\n<div class=\"pictures\">\n");
        for p in pictures {
            let png = base64::engine::general_purpose::STANDARD.encode(p.image.png_bytes()?);
            let _ = writeln!(
                page,
                "<figure><img alt=\"{c}\" src=\"data:image/png;base64,{png}\"><figcaption>{c}</figcaption></figure>",
                c = escape(&p.caption)
            );
        }
        page.push_str("</div>\n");
    }
    page.push_str("<h2>Quality, sweeps and time per step</h2>\n<div class=\"charts\">\n");
    page.push_str(&quality_chart(steps)?);
    page.push_str(&bins_chart(steps)?);
    page.push_str(&per_step_chart(steps, "sweeps per step", |s| {
        s.iterations as f64
    })?);
    page.push_str(&per_step_chart(steps, "seconds per step", |s| s.seconds)?);
    page.push_str("</div>\n");
    page.push_str(&convergence(steps)?);
    page.push_str("<h2>Settings</h2>\n<table class=\"settings\">\n");
    for (k, v) in &report.settings {
        let v = match v {
            serde_json::Value::String(s) => s.clone(),
            other => other.to_string(),
        };
        let _ = writeln!(
            page,
            "<tr><th>{}</th><td>{}</td></tr>",
            escape(k),
            escape(&v)
        );
    }
    page.push_str("</table>\n");
    page.push_str(&table(steps));
    page.push_str("</body>\n</html>\n");
    Ok(page)
}

const STYLE: &str = "body{font-family:sans-serif;margin:1.5em auto;max-width:1500px;color:#222}\
h1{font-size:1.5em}h2{font-size:1.2em;margin-top:1.6em}\
.outcome.ok{color:#1a7f37}.outcome.failed{color:#c0001f;font-weight:bold}\
.pictures,.charts{display:flex;flex-wrap:wrap;gap:12px}\
figure{margin:0;width:720px}figure img{width:100%;border:1px solid #ccc}\
figcaption{text-align:center;font-size:.9em}\
table{border-collapse:collapse;font-size:.85em}td,th{border:1px solid #ccc;padding:2px 8px;text-align:right}\
.settings th{text-align:left}";

/// The steps table, with a row per step and the numbers as `report.json` has them.
fn table(steps: &[StepReport]) -> String {
    let mut t = String::from(
        "<h2>Steps</h2>\n<details><summary>every step's numbers (as in report.json)</summary>\n<table class=\"steps\">\n<tr><th>step</th><th>sweeps</th><th>residual</th><th>converged</th><th>seconds</th><th>min quality</th><th>mean quality</th><th>inverted</th>",
    );
    for k in 0..5 {
        let _ = write!(t, "<th>{}–{}</th>", BIN_EDGES[k], BIN_EDGES[k + 1]);
    }
    t.push_str("</tr>\n");
    for s in steps {
        let _ = write!(
            t,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td>",
            s.step, s.iterations, s.residual, s.converged, s.seconds, s.min_quality, s.mean_quality, s.inverted
        );
        for b in s.bins {
            let _ = write!(t, "<td>{b}</td>");
        }
        t.push_str("</tr>\n");
    }
    t.push_str("</table>\n</details>\n");
    t
}

/// `text` with `&`, `<`, `>` and `"` escaped.
fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// A chart drawn by `draw` on an SVG area of [`CHART`] size, as an SVG string.
fn svg_chart(
    draw: impl FnOnce(&DrawingArea<SVGBackend, Shift>) -> std::result::Result<(), String>,
) -> Result<String> {
    crate::register_font();
    let mut doc = String::new();
    {
        let root = SVGBackend::with_string(&mut doc, CHART).into_drawing_area();
        root.fill(&WHITE)
            .map_err(|e| Error::Render(e.to_string()))?;
        draw(&root).map_err(Error::Render)?;
        root.present().map_err(|e| Error::Render(e.to_string()))?;
    }
    doc.push('\n');
    Ok(doc)
}

fn font(size: f64) -> TextStyle<'static> {
    ("sans-serif", size).into_font().color(&BLACK)
}

/// Step axis `0..=last step` (at least `0..1`).
fn step_range(steps: &[StepReport]) -> Range<f64> {
    0.0..steps.last().map_or(1, |s| s.step.max(1)) as f64
}

/// A line's legend label, colour and value per step.
type Series = (&'static str, RGBColor, fn(&StepReport) -> f64);

fn quality_chart(steps: &[StepReport]) -> Result<String> {
    svg_chart(|root| {
        let mut chart = ChartBuilder::on(root)
            .caption("element quality", font(20.0))
            .margin(10)
            .margin_right(30)
            .x_label_area_size(40)
            .y_label_area_size(56)
            .build_cartesian_2d(step_range(steps), 0.0..1.0)
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc("step")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .label_style(font(14.0))
            .draw()
            .map_err(|e| e.to_string())?;
        let series: [Series; 2] = [
            ("mean", RGBColor(31, 119, 180), |s| s.mean_quality),
            ("min", RGBColor(214, 39, 40), |s| s.min_quality),
        ];
        for (label, c, value) in series {
            chart
                .draw_series(LineSeries::new(
                    steps.iter().map(|s| (s.step as f64, value(s))),
                    c.stroke_width(2),
                ))
                .map_err(|e| e.to_string())?
                .label(label)
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2))
                });
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .label_font(font(14.0))
            .position(SeriesLabelPosition::LowerLeft)
            .draw()
            .map_err(|e| e.to_string())
    })
}

fn bins_chart(steps: &[StepReport]) -> Result<String> {
    let top = steps.iter().flat_map(|s| s.bins).max().unwrap_or(1).max(1) as f64;
    svg_chart(|root| {
        let mut chart = ChartBuilder::on(root)
            .caption("elements per quality bin", font(20.0))
            .margin(10)
            .margin_right(30)
            .x_label_area_size(40)
            .y_label_area_size(64)
            .build_cartesian_2d(step_range(steps), (0.8..2.0 * top).log_scale())
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc("step")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_label_formatter(&|v| format!("{v:.0}"))
            .label_style(font(14.0))
            .draw()
            .map_err(|e| e.to_string())?;
        for k in 0..5 {
            let q = 0.5 * (BIN_EDGES[k] + BIN_EDGES[k + 1]);
            let rgb = colour::cell(q, false, 0.85);
            let c = RGBColor(rgb[0], rgb[1], rgb[2]);
            // One line per run of steps with a non-zero count.
            let mut runs: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
            for s in steps {
                match s.bins[k] {
                    0 if runs.last().is_some_and(|r| !r.is_empty()) => runs.push(Vec::new()),
                    0 => {}
                    n => runs
                        .last_mut()
                        .into_iter()
                        .for_each(|r| r.push((s.step as f64, n as f64))),
                }
            }
            let mut first = true;
            for run in runs.into_iter().filter(|r| !r.is_empty()) {
                chart
                    .draw_series(run.iter().map(|&p| Circle::new(p, 2, c.filled())))
                    .map_err(|e| e.to_string())?;
                let series = chart
                    .draw_series(LineSeries::new(run, c.stroke_width(2)))
                    .map_err(|e| e.to_string())?;
                if first {
                    series
                        .label(format!("{}–{}", BIN_EDGES[k], BIN_EDGES[k + 1]))
                        .legend(move |(x, y)| {
                            PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(3))
                        });
                    first = false;
                }
            }
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .label_font(font(14.0))
            .position(SeriesLabelPosition::LowerRight)
            .draw()
            .map_err(|e| e.to_string())
    })
}

fn per_step_chart(
    steps: &[StepReport],
    what: &str,
    value: fn(&StepReport) -> f64,
) -> Result<String> {
    let done: Vec<&StepReport> = steps.iter().filter(|s| s.step > 0).collect();
    let top = done.iter().map(|s| value(s)).fold(0.0, f64::max);
    let top = if top > 0.0 { 1.1 * top } else { 1.0 };
    svg_chart(|root| {
        let mut chart = ChartBuilder::on(root)
            .caption(what, font(20.0))
            .margin(10)
            .margin_right(30)
            .x_label_area_size(40)
            .y_label_area_size(64)
            .build_cartesian_2d(step_range(steps), 0.0..top)
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc("step")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .label_style(font(14.0))
            .draw()
            .map_err(|e| e.to_string())?;
        let c = RGBColor(31, 119, 180);
        chart
            .draw_series(LineSeries::new(
                done.iter().map(|s| (s.step as f64, value(s))),
                c.stroke_width(2),
            ))
            .map_err(|e| e.to_string())?;
        Ok(())
    })
}

/// A wall time as a reader takes it in: `12.35 s`, `287.2 ms` (not the
/// nanosecond digits `report.json` keeps).
fn duration(seconds: f64) -> String {
    if seconds >= 1.0 {
        format!("{seconds:.2} s")
    } else {
        format!("{:.1} ms", 1e3 * seconds)
    }
}

/// The slowest step's eq.-8 value per sweep, or a note when not recorded.
fn convergence(steps: &[StepReport]) -> Result<String> {
    let slowest = steps
        .iter()
        .filter(|s| s.step > 0)
        .max_by(|a, b| a.seconds.total_cmp(&b.seconds));
    let Some(s) = slowest else {
        return Ok(String::new());
    };
    let mut out = format!(
        "<h2>Convergence of the slowest step (step {}, {} sweeps, {})</h2>\n",
        s.step,
        s.iterations,
        duration(s.seconds)
    );
    let history: Vec<(f64, f64)> = s
        .history
        .iter()
        .enumerate()
        .filter(|(_, &v)| v > 0.0 && v.is_finite())
        .map(|(k, &v)| ((k + 1) as f64, v))
        .collect();
    if history.is_empty() {
        out.push_str("<p>The sweeps' eq.-8 values were not recorded for this run.</p>\n");
        return Ok(out);
    }
    let lo = history.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
    let hi = history.iter().map(|p| p.1).fold(0.0, f64::max);
    let sweeps = history.len().max(2) as f64;
    out.push_str(&svg_chart(|root| {
        let mut chart = ChartBuilder::on(root)
            .caption(
                "eq. 8: mean |change| of the interior components",
                font(20.0),
            )
            .margin(10)
            .margin_right(30)
            .x_label_area_size(40)
            .y_label_area_size(72)
            .build_cartesian_2d(1.0..sweeps, (0.5 * lo..2.0 * hi).log_scale())
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc("sweep")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .label_style(font(14.0))
            .draw()
            .map_err(|e| e.to_string())?;
        chart
            .draw_series(LineSeries::new(
                history,
                RGBColor(214, 39, 40).stroke_width(2),
            ))
            .map_err(|e| e.to_string())?;
        Ok(())
    })?);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use verbss::mesh::samples::one_triangle;
    use verbss::settings::Settings;

    fn report() -> Report {
        let mesh = one_triangle();
        let size = (mesh.dim, mesh.node_count(), mesh.cell_count());
        let mut report = Report::new("tri<1>.su2", size, &Settings::new(2));
        for (n, q) in [(0, 0.9), (1, 0.61), (2, 0.3333333333333333)] {
            // `StepReport` is non-exhaustive outside the core: set its fields.
            let mut s = StepReport::default();
            s.step = n;
            s.iterations = 10 * n;
            s.residual = 1e-7;
            s.seconds = 0.001 * n as f64 + 1e-9;
            s.min_quality = q;
            s.mean_quality = q;
            s.bins = [
                0,
                0,
                usize::from(q < 0.4),
                usize::from((0.4..0.7).contains(&q)),
                usize::from(q >= 0.7),
            ];
            s.history = (1..=10 * n).map(|k| 0.5f64.powi(k as i32)).collect();
            report.steps.push(s);
        }
        report.outcome = "completed".into();
        report
    }

    #[test]
    fn page_is_self_contained_and_escapes_names() {
        let page = html(&report(), &[]).unwrap();
        assert!(page.contains("verbss report: tri&lt;1&gt;.su2"));
        assert!(!page.contains("<script"));
        assert!(!page.contains("url(http"));
        assert!(!page.contains("src=\"http"));
        assert!(!page.contains("<link"));
        assert_eq!(page.matches("<svg").count(), 5);
        // Issue 43, 18: the heading showed `0.002000001 s`.
        assert!(page.contains("Convergence of the slowest step (step 2, 20 sweeps, 2.0 ms)"));
        assert!(page.contains("<tr><td>2</td><td>20</td><td>0.0000001</td><td>false</td><td>0.002000001</td><td>0.3333333333333333</td>"));
    }

    #[test]
    fn durations_are_shown_to_a_tenth_of_a_millisecond_or_a_hundredth_of_a_second() {
        assert_eq!(duration(0.287163945), "287.2 ms");
        assert_eq!(duration(12.3456), "12.35 s");
        assert_eq!(duration(1.0), "1.00 s");
    }

    #[test]
    fn pictures_are_inlined_png() {
        let image = Image {
            width: 2,
            height: 1,
            rgb: vec![255, 0, 0, 0, 0, 255],
        };
        let page = html(
            &report(),
            &[Picture {
                caption: "step 0".into(),
                image: image.clone(),
            }],
        )
        .unwrap();
        let png = base64::engine::general_purpose::STANDARD.encode(image.png_bytes().unwrap());
        assert!(page.contains(&format!(
            "src=\"data:image/png;base64,{png}\"><figcaption>step 0</figcaption>"
        )));
    }

    #[test]
    fn without_history_the_page_says_so() {
        let mut r = report();
        for s in &mut r.steps {
            s.history.clear();
        }
        let page = html(&r, &[]).unwrap();
        assert!(page.contains("<p>The sweeps' eq.-8 values were not recorded for this run.</p>"));
        assert_eq!(page.matches("<svg").count(), 4);
    }
}
