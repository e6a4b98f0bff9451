//! `PAPER.md`: every table of the paper with the paper's numbers beside ours,
//! and where they differ, by how much and why.
//!
//! The tables are in [`tables`], the sections of §4.2 to §5.3 in [`sections`],
//! the differences from the paper in [`differences`](mod@differences).

mod differences;
mod sections;
mod tables;

use std::fmt::Write;

use crate::results::{CaseResult, MethodResult};
use crate::Results;

use differences::differences;
use sections::{naca, sphere, split, threads};
use tables::{limits, table1, table2};

/// The methods' column order.
const ORDER: [&str; 4] = ["spring", "laplacian", "ball-vertex", "verbss"];

/// Seconds with three significant digits.
fn secs(s: f64) -> String {
    if !s.is_finite() || s <= 0.0 {
        "—".into()
    } else if s >= 1.0 {
        format!("{s:.3}")
    } else {
        let digits = (2 - s.log10().floor() as i32).max(0) as usize;
        format!("{s:.digits$}")
    }
}

/// A ratio `a / b` as `12.3×`.
fn times(a: f64, b: f64) -> String {
    if a.is_finite() && b.is_finite() && a > 0.0 && b > 0.0 {
        format!("{:.2}×", a / b)
    } else {
        "—".into()
    }
}

/// Relative difference of ours from the paper's, as `+3.1 %`.
fn diff(ours: f64, paper: f64) -> String {
    format!("{:+.1} %", 100.0 * (ours - paper) / paper)
}

fn method<'a>(c: &'a CaseResult, name: &str) -> &'a MethodResult {
    c.methods
        .iter()
        .find(|m| m.method == name)
        .expect("every method runs on every case")
}

fn case<'a>(r: &'a Results, name: &str) -> Option<&'a CaseResult> {
    r.cases.iter().find(|c| c.name == name)
}

/// A number without trailing zeros.
fn trim(x: f64) -> String {
    let s = format!("{x:.3}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// A point as `(x, y[, z])` with 3 decimals.
fn point(p: &[f64]) -> String {
    let xs: Vec<String> = p.iter().map(|x| format!("{x:.3}")).collect();
    format!("({})", xs.join(", "))
}

/// Writes `PAPER.md` for `r`.
pub fn render(r: &Results) -> String {
    let mut o = String::new();
    let w = &mut o;
    let _ = writeln!(w, "# The VerBSS paper, reproduced\n");
    let _ = writeln!(
        w,
        "Every table of T.J. Lin, Z.Q. Guan, J.H. Chang, S.H. Lo, *Vertex-Ball Spring \
Smoothing: an efficient method for unstructured dynamic hybrid meshes*, with the \
paper's numbers beside ours. Written by `verbss-paper` (numbers in \
[`results.json`](results.json)):\n"
    );
    let _ = writeln!(w, "```sh\n{}\n```\n", r.command);
    let _ = writeln!(w, "- date: {}", r.date);
    let _ = writeln!(w, "- machine: `{}`", r.machine.uname);
    let _ = writeln!(w, "- processor: {}", r.machine.cpu);
    let _ = writeln!(
        w,
        "- load average (1, 5, 15 min) at the start: {}; at the end: {}",
        r.machine.load_at_start, r.machine.load_at_end
    );
    let _ = writeln!(w, "- whole run: {:.0} s\n", r.seconds);
    let _ = writeln!(
        w,
        "**Timings.** The machine is a shared 2-core virtual machine on which other work \
ran at the same time. Absolute seconds are noisy and not comparable with the \
paper's (a 2.66 GHz dual core in §4, a four-core machine in §5, CPU time where we \
measure wall time); what we compare are ratios measured in the same run, above \
all each method's seconds against `ball-vertex` with the scalar SOR solver. Even those \
move by tens of per cent between runs (methods run one after the other while the load \
changes); a load above 2 means the two cores were already busy, so a second thread \
cannot help.\n"
    );
    settings(w, r);
    meshes(w, r);
    limits(w, r);
    table1(w, r);
    table2(w, r);
    naca(w, r);
    if case(r, "three-element").is_some() {
        let _ = writeln!(w, "## §4.3, three-element airfoil\n");
    }
    split(w, r, "three-element", 6, "§4.3, three-element airfoil");
    sphere(w, r);
    threads(w, r, "two-fish", 8, "§5.2, two fish");
    threads(w, r, "bending-wing", 9, "§5.3, bending wing");
    differences(w, r);
    pictures(w, r);
    o
}

fn settings(w: &mut String, r: &Results) {
    let Some(c) = r.cases.first() else { return };
    let setting = |name: &str| match &c.settings[name] {
        serde_json::Value::String(s) => s.clone(),
        other => other.to_string(),
    };
    let _ = writeln!(w, "## How we measured\n");
    let _ = writeln!(
        w,
        "- Every case is its case file `cases/<name>.toml` (mesh, motion, steps; reference \
`{}`: the paper's option 1, springs rebuilt on the current mesh each step, solving for \
the increment), run once per method: `spring` (edge springs), `laplacian` (component-wise, \
k = 1/L), `ball-vertex` (edge + ball-vertex springs, one global system, scalar SOR over \
all D·N unknowns: the paper's baseline) and `verbss` (the same system, node by node, \
block SOR with per-node LDLᵀ).",
        setting("reference")
    );
    let _ = writeln!(
        w,
        "- Solver settings, the same for every method and case: ω = {}, stop when the \
eq.-8 value is below {:e} × the step's largest boundary displacement{}, at most {} sweeps, \
1 thread (except Tables 8 and 9). The paper used an absolute eq.-8 tolerance (1e-6 in \
§4.1, 1e-5 in §4.2–5.1, 1e-4 in §5.2–5.3) and at most 300 SOR sweeps; an absolute \
1e-5 stops after a few sweeps on a fine mesh, before the nodes next to a rotating \
trailing edge have followed it (docs/case-file.md), so we use the relative form everywhere.",
        setting("omega"),
        c.settings["tolerance"].as_f64().unwrap_or(f64::NAN),
        if c.settings["absolute_tolerance"] == true {
            " (absolute)"
        } else {
            ""
        },
        setting("max_iterations")
    );
    let _ = writeln!(
        w,
        "- **Largest motion before the first inverted element.** The paper moved each \
body in increments (its §4.1 fig. 6, §4.2, §5.1) and reports the amplitude at which \
elements invert. We step with a fixed increment per step (the case file's: 0.1 unit \
for the rectangles, 0.5 unit for the sphere; 1° of rotation about the quarter chord for \
the airfoil, as the paper's rotation to 96°), each step from the last valid mesh, \
check every element after every step, and report the amplitude of the last valid step: \
the true limit lies between it and one increment more. The search stops at a cap \
(6.9 units for the rectangles: the wall is 7 away; 19.5 for the sphere: the wall is 20 \
away; 180° for the airfoil). For the three-element airfoil, the fish and the wing the \
paper gives no limit; we only check the prescribed motion (limit in multiples of it, \
cap 1), which also keeps the 106,755-node wing affordable.\n"
    );
    let _ = writeln!(
        w,
        "- Seconds per step are means over the valid steps of the case file's motion \
(at most N); `form` is the paper's Part I (springs and per-node factors), `solve` its \
Part II (the sweeps), `update` the rest of the step (boundary motion, coordinate \
update and our quality and inversion check of every element).\n"
    );
}

fn meshes(w: &mut String, r: &Results) {
    let _ = writeln!(w, "## Meshes\n");
    let _ = writeln!(
        w,
        "Generated with Gmsh by the scripts in `cases/meshes/` (the paper's meshes are \
not available; geometry the paper leaves open is chosen and documented in each \
script and case file).\n"
    );
    let _ = writeln!(
        w,
        "| case | § | paper nodes | our nodes | Δ | paper elements | our elements | motion |"
    );
    let _ = writeln!(w, "|---|---|---|---|---|---|---|---|");
    for c in &r.cases {
        let _ = writeln!(
            w,
            "| {} | {} | {} | {} | {} | {} | {} | {} |",
            c.name,
            c.section,
            c.paper.nodes,
            c.nodes,
            diff(c.nodes as f64, c.paper.nodes as f64),
            c.paper.cells.map_or("—".into(), |n| n.to_string()),
            c.cells,
            c.motion
        );
    }
    let _ = writeln!(w);
}

fn pictures(w: &mut String, r: &Results) {
    let _ = writeln!(w, "## Pictures\n");
    let _ = writeln!(
        w,
        "Elements coloured by quality (eq. 9, viridis: dark 0, yellow 1; inverted in \
red). `before`: the initial mesh; `after`: VerBSS at the end of the case file's \
motion; `spring-inverted`: the spring method's first inverted state in the limit \
search; `verbss-limit`: VerBSS at its largest rotation.\n"
    );
    for c in &r.cases {
        if c.pictures.is_empty() {
            continue;
        }
        let _ = writeln!(w, "### {}\n", c.name);
        for p in &c.pictures {
            let _ = writeln!(w, "![{p}]({p})");
        }
        let _ = writeln!(w);
    }
}
