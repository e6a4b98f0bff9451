//! `verbss render MESH -o FILE.png|.svg`: a picture of a mesh coloured by
//! element quality; and the pictures of runs (`--html`, `--gif` of `run`,
//! `deform` and `demo`), recorded step by step by a [`Recorder`].

use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;

use anyhow::Context;
use clap::Args;
use std::path::Path;
use verbss::deform::Snapshot;
use verbss::io::outputs::Output;
use verbss::mesh::Mesh;
use verbss::quality;
use verbss::report::Report;
use verbss_render::html_report::{self, Picture};
use verbss_render::{Camera, Gif, Image, Layout, Options, Scene, Section, State};

/// Arguments of `verbss render`.
#[derive(Args)]
pub struct RenderArgs {
    /// The mesh (.msh, .su2, .vtu, .cgns).
    mesh: PathBuf,
    /// The picture: .png or .svg.
    #[arg(short, long)]
    output: PathBuf,
    /// Zoom window x0,x1,y0,y1 (mesh coordinates; for a 3D surface, screen coordinates).
    #[arg(long, value_parser = parse_view, allow_hyphen_values = true)]
    view: Option<[f64; 4]>,
    /// Width in pixels.
    #[arg(long, default_value_t = 1600, allow_hyphen_values = true)]
    width: u32,
    /// 3D: draw the facets of this boundary group (repeatable) instead of the whole boundary.
    #[arg(long)]
    group: Vec<String>,
    /// 3D: draw the cut by a plane, e.g. `z=0.5`.
    #[arg(long, value_parser = parse_cut, conflicts_with = "group")]
    cut: Option<(usize, f64)>,
    /// 3D: azimuth of the viewer about z, degrees from +x.
    #[arg(long, default_value_t = -60.0, allow_hyphen_values = true, value_parser = parse_angle)]
    azimuth: f64,
    /// 3D: elevation of the viewer above the x–y plane, degrees.
    #[arg(long, default_value_t = 25.0, allow_hyphen_values = true, value_parser = parse_angle)]
    elevation: f64,
    /// Do not draw the element edges.
    #[arg(long)]
    no_edges: bool,
    /// Header text [default: the mesh file's name].
    #[arg(long)]
    title: Option<String>,
}

/// `x0,x1,y0,y1` → a window that can be drawn ([`verbss_render::check_view`]).
fn parse_view(s: &str) -> Result<[f64; 4], String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|x| x.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("'{s}' is not four numbers x0,x1,y0,y1"))?;
    let [x0, x1, y0, y1] = v[..] else {
        return Err(format!("'{s}' is not four numbers x0,x1,y0,y1"));
    };
    let span = |a: f64, b: f64| (b - a).is_finite() && a < b;
    if !(span(x0, x1) && span(y0, y1)) {
        return Err(format!(
            "'{s}': expected finite x0 < x1 and y0 < y1 (with finite x1 - x0 and y1 - y0)"
        ));
    }
    verbss_render::check_view([x0, x1, y0, y1])
        .map(|()| [x0, x1, y0, y1])
        .map_err(|e| e.to_string())
}

/// An angle in degrees, finite.
fn parse_angle(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(a) if a.is_finite() => Ok(a),
        _ => Err(format!("'{s}' is not a finite angle in degrees")),
    }
}

/// `x=0.5`, `y=…`, `z=…` → (axis, value).
fn parse_cut(s: &str) -> Result<(usize, f64), String> {
    let err = || format!("'{s}' is not a plane like z=0.5");
    let (axis, at) = s.split_once('=').ok_or_else(err)?;
    let axis = match axis.trim() {
        "x" => 0,
        "y" => 1,
        "z" => 2,
        _ => return Err(err()),
    };
    match at.trim().parse::<f64>() {
        Ok(at) if at.is_finite() => Ok((axis, at)),
        _ => Err(format!(
            "'{s}': the plane's position must be a finite number"
        )),
    }
}

/// Runs `verbss render`.
pub fn run(args: RenderArgs) -> anyhow::Result<ExitCode> {
    let inputs = crate::overwrite::mesh_inputs(&args.mesh);
    verbss::io::outputs::check(&inputs, &[Output::new("-o", &args.output)])?;
    let mesh = crate::input::read_mesh(&args.mesh)?;
    let orientation = quality::orientation(&mesh);
    let q = quality::qualities(&mesh, &mesh.coords, &orientation);
    let mut inverted = vec![false; mesh.cell_count()];
    for c in quality::inverted_cells(&mesh, &mesh.coords, &orientation) {
        inverted[c] = true;
    }
    let section = match (args.cut, args.group.is_empty()) {
        (Some((axis, at)), _) => Section::Cut { axis, at },
        (None, false) => Section::Groups(args.group.clone()),
        (None, true) => Section::All,
    };
    let camera = Camera {
        azimuth: args.azimuth,
        elevation: args.elevation,
    };
    let state = State {
        coords: &mesh.coords,
        quality: &q,
        inverted: &inverted,
    };
    let scene = Scene::new(&mesh, state, &section, camera)?;
    let mut options = Options::default();
    options.width = args.width;
    options.view = args.view;
    options.edges = !args.no_edges;
    options.title = args.title.unwrap_or_else(|| {
        args.mesh
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default()
    });
    verbss_render::write(&args.output, &scene, &options)?;
    let layout = Layout::new(&scene, &options)?;
    println!(
        "{}: {} × {} px, {} polygons, min quality {:.4}, {} inverted",
        args.output.display(),
        layout.width,
        layout.height,
        scene.len(),
        scene.min_quality,
        scene.inverted
    );
    Ok(ExitCode::SUCCESS)
}

/// The picture options of `run`, `deform` and `demo`.
#[derive(Args, Clone, Default)]
pub struct PictureArgs {
    /// Write a self-contained HTML report (pictures, per-step charts, settings) to FILE.
    #[arg(long, value_name = "FILE")]
    pub html: Option<PathBuf>,
    /// Write an animated GIF of the mesh, one frame per step (or per --gif-every steps), to FILE.
    #[arg(long, value_name = "FILE")]
    pub gif: Option<PathBuf>,
    /// A GIF frame every K steps.
    #[arg(
        long,
        value_name = "K",
        default_value_t = 1,
        allow_hyphen_values = true
    )]
    pub gif_every: usize,
    /// Window x0,x1,y0,y1 of the report's pictures and the GIF (2D; whole mesh by default).
    #[arg(long, value_parser = parse_view, allow_hyphen_values = true)]
    pub view: Option<[f64; 4]>,
}

/// Width of the report's pictures and of the GIF frames.
const REPORT_WIDTH: u32 = 1000;
const GIF_WIDTH: u32 = 640;

/// Records a run's states for its `--html` report and `--gif` animation. A
/// picture that cannot be made is a warning: it never stops the run.
pub struct Recorder {
    args: PictureArgs,
    mesh: Arc<Mesh>,
    steps: usize,
    before: Option<Image>,
    worst: Option<Snapshot>,
    gif: Option<Gif>,
    /// The GIF's window, the first frame's: one frame size per GIF.
    gif_view: Option<[f64; 4]>,
}

impl Recorder {
    /// A recorder for `args` on `mesh` over `steps` steps; `view` is the
    /// window when `args` gives none.
    pub fn new(
        args: &PictureArgs,
        mesh: &Arc<Mesh>,
        steps: usize,
        view: Option<[f64; 4]>,
    ) -> Recorder {
        let mut args = args.clone();
        args.view = args.view.or(view);
        args.gif_every = args.gif_every.max(1);
        Recorder {
            args,
            mesh: Arc::clone(mesh),
            steps,
            before: None,
            worst: None,
            gif: None,
            gif_view: None,
        }
    }

    /// The files it writes: `--html` and `--gif`.
    pub fn outputs(&self) -> Vec<Output> {
        let html = self.args.html.iter().map(|p| Output::new("--html", p));
        html.chain(self.args.gif.iter().map(|p| Output::new("--gif", p)))
            .collect()
    }

    /// Whether the run must record the sweeps' eq.-8 values (for the report).
    pub fn wants_history(&self) -> bool {
        self.args.html.is_some()
    }

    /// The picture of `s` in window `view` (the whole mesh when `None`), and
    /// the window it shows.
    fn picture_in(
        &self,
        s: &Snapshot,
        title: String,
        width: u32,
        view: Option<[f64; 4]>,
    ) -> anyhow::Result<(Image, [f64; 4])> {
        let quality = s.qualities(&self.mesh);
        let state = State {
            coords: &s.coords,
            quality: &quality,
            inverted: &s.inverted,
        };
        let scene = Scene::new(&self.mesh, state, &Section::All, Camera::default())?;
        let mut options = Options::default();
        options.width = width;
        options.view = view;
        options.title = title;
        let window = Layout::new(&scene, &options)?.window;
        Ok((verbss_render::png(&scene, &options)?, window))
    }

    fn picture(&self, s: &Snapshot, title: String, width: u32) -> anyhow::Result<Image> {
        Ok(self.picture_in(s, title, width, self.args.view)?.0)
    }

    /// Adds the frame of `s` to the GIF; on failure warns and drops the GIF
    /// (the target keeps what it held).
    fn gif_frame(&mut self, s: &Snapshot, title: String) {
        let Some(path) = self.args.gif.clone() else {
            return;
        };
        let add = || -> anyhow::Result<()> {
            let view = self.args.view.or(self.gif_view);
            let (frame, window) = self.picture_in(s, title, GIF_WIDTH, view)?;
            self.gif_view.get_or_insert(window);
            if self.gif.is_none() {
                create_parent(&path)?;
                self.gif = Some(Gif::create(&path, frame.width, frame.height, 6)?);
            }
            if let Some(gif) = &mut self.gif {
                gif.push(&frame)?;
            }
            Ok(())
        };
        if let Err(e) = add() {
            eprintln!("warning: no GIF: {e:#}");
            self.gif = None;
            self.args.gif = None;
        }
    }

    /// Records an accepted state (step 0 is the input mesh).
    pub fn step(&mut self, s: &Snapshot) {
        let n = s.report.step;
        if self.args.html.is_some() {
            if n == 0 {
                match self.picture(s, "step 0 (input)".into(), REPORT_WIDTH) {
                    Ok(image) => self.before = Some(image),
                    Err(e) => eprintln!("warning: no picture of the input in the report: {e:#}"),
                }
            } else if self
                .worst
                .as_ref()
                .is_none_or(|w| s.report.min_quality < w.report.min_quality)
            {
                self.worst = Some(s.clone());
            }
        }
        if n.is_multiple_of(self.args.gif_every) || n == self.steps {
            self.gif_frame(s, format!("step {n} / {}", self.steps));
        }
    }

    /// Writes the GIF and the report (pictures of the input, the worst
    /// accepted step, the last accepted step and the failed one); the GIF
    /// ends with the failed state when there is one. A picture or file that
    /// cannot be made is a warning on stderr: the run keeps its outcome.
    pub fn finish(&mut self, report: &Report, last: &Snapshot, failed: Option<&Snapshot>) {
        if let (Some(f), Some(_)) = (failed, &self.gif) {
            self.gif_frame(f, format!("step {} FAILED", f.report.step));
        }
        if let Some(gif) = self.gif.take() {
            if let Err(e) = gif.finish() {
                eprintln!("warning: no GIF: {e:#}");
            }
        }
        let Some(path) = self.args.html.clone() else {
            return;
        };
        let mut pictures = Vec::new();
        if let Some(image) = self.before.take() {
            pictures.push(Picture {
                caption: "step 0 (input)".into(),
                image,
            });
        }
        let last_n = last.report.step;
        let mut wanted = Vec::new();
        if let Some(w) = self.worst.as_ref().filter(|w| w.report.step != last_n) {
            wanted.push((
                w,
                format!("step {} (lowest minimum quality)", w.report.step),
            ));
        }
        if last_n > 0 {
            wanted.push((last, format!("step {last_n} (last accepted)")));
        }
        if let Some(f) = failed {
            let caption = format!("step {} (failed: inverted elements in red)", f.report.step);
            wanted.push((f, caption));
        }
        for (s, caption) in wanted {
            match self.picture(s, caption.clone(), REPORT_WIDTH) {
                Ok(image) => pictures.push(Picture { caption, image }),
                Err(e) => eprintln!("warning: no picture of {caption} in the report: {e:#}"),
            }
        }
        let written = create_parent(&path).and_then(|()| {
            html_report::write(&path, report, &pictures)
                .with_context(|| format!("cannot write the report {}", path.display()))
        });
        if let Err(e) = written {
            eprintln!("warning: no HTML report: {e:#}");
        }
    }
}

/// Creates the folder of `path` if missing.
fn create_parent(path: &Path) -> anyhow::Result<()> {
    match path.parent().filter(|d| !d.as_os_str().is_empty()) {
        Some(dir) => std::fs::create_dir_all(dir)
            .with_context(|| format!("cannot create the folder {}", dir.display())),
        None => Ok(()),
    }
}
