//! Step progress: a bar on a terminal (step, steps/s, ETA, current minimum
//! quality), one plain line per step otherwise, nothing with `--quiet`.

use std::io::IsTerminal;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use verbss::deform::StepReport;

/// How progress is shown.
enum Mode {
    Bar(ProgressBar),
    Lines,
    Quiet,
}

/// Progress of a run of `steps` steps, on standard error.
pub struct Progress {
    mode: Mode,
    steps: usize,
}

impl Progress {
    /// A bar when standard error is a terminal, plain lines when it is not,
    /// nothing when `quiet`.
    pub fn new(steps: usize, quiet: bool) -> Progress {
        let mode = if quiet {
            Mode::Quiet
        } else if std::io::stderr().is_terminal() {
            let bar =
                ProgressBar::with_draw_target(Some(steps as u64), ProgressDrawTarget::stderr());
            bar.set_style(
                ProgressStyle::with_template(
                    "{bar:30.cyan/blue} step {pos}/{len} · {per_sec} · ETA {eta} · {msg}",
                )
                .expect("valid progress template")
                .progress_chars("=> "),
            );
            Mode::Bar(bar)
        } else {
            Mode::Lines
        };
        Progress { mode, steps }
    }

    /// Reports a finished step.
    pub fn step(&self, r: &StepReport) {
        match &self.mode {
            Mode::Bar(bar) => {
                bar.set_message(format!("min quality {:.4}", r.min_quality));
                bar.set_position(r.step as u64);
            }
            Mode::Lines => {
                let stages: Vec<&str> = r.stages.iter().map(|s| s.name()).collect();
                // No stage: the blended rigid motion left the springs nothing.
                let stages = if stages.is_empty() {
                    "blended motion only".to_string()
                } else {
                    stages.join(" → ")
                };
                eprintln!(
                    "step {}/{}: {} ({} iterations), true residual {:.2e}, error {:.1e} of the \
                     cell height, min quality {:.4}, {} inverted, {:.3} s",
                    r.step,
                    self.steps,
                    stages,
                    r.iterations,
                    r.true_residual,
                    r.error_ratio,
                    r.min_quality,
                    r.inverted,
                    r.seconds
                )
            }
            Mode::Quiet => {}
        }
    }

    /// Removes the bar.
    pub fn finish(&self) {
        if let Mode::Bar(bar) = &self.mode {
            bar.finish_and_clear();
        }
    }
}
