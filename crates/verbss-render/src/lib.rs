//! # verbss-render — pictures of verbss meshes and the HTML run report
//!
//! The drawing half of verbss, kept out of the core library (which Python, C
//! and MPI link, none of which draws): pictures of a mesh coloured by element
//! quality as PNG, SVG and GIF, and the self-contained HTML report of a run
//! ([`html_report`]).
//!
//! A [`Scene`] turns one state of a mesh (coordinates, per-cell quality and
//! inversion flags) into coloured polygons: every cell of a 2D mesh, the
//! boundary surface (or some groups) of a 3D mesh seen from a [`Camera`], or
//! the cut of a 3D mesh by a plane ([`Section`]). Cells are coloured by
//! quality with viridis (0 dark purple → 1 yellow) and inverted cells in a
//! loud red ([`colour::INVERTED`]); the element edges are drawn over them.
//!
//! [`png`](fn@png) rasterises the polygons itself (a scanline fill with a depth
//! buffer, [`raster`]; its speed is in CHANGELOG.md) and lets
//! plotters draw the header, the axes and the colour bar onto the same pixels,
//! with an embedded font (DejaVu Sans, this crate's `fonts/`), so no system
//! font is needed. [`svg`] writes the same picture as SVG (cells with their
//! float coordinates, so a zoom in a browser stays exact). [`Gif`] collects
//! frames into an animation.
//!
//! ```no_run
//! use verbss_render::{Camera, Options, Scene, Section, State};
//! let mesh = verbss::io::read("wing.su2".as_ref())?;
//! let orientation = verbss::quality::orientation(&mesh);
//! let quality = verbss::quality::qualities(&mesh, &mesh.coords, &orientation);
//! let inverted = vec![false; mesh.cell_count()];
//! let state = State { coords: &mesh.coords, quality: &quality, inverted: &inverted };
//! let scene = Scene::new(&mesh, state, &Section::All, Camera::default())?;
//! verbss_render::png(&scene, &Options::default())?.write_png("wing.png".as_ref())?;
//! # Ok::<(), verbss::Error>(())
//! ```

#![warn(missing_docs)]
#![forbid(unsafe_code)]

mod clip;
pub mod colour;
mod frame;
pub mod html_report;
pub mod raster;
mod scene;

use std::fmt::Write as _;
use std::fs::File;
use std::io::{BufWriter, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::sync::Once;

use plotters::prelude::*;
use plotters::style::FontStyle;

use verbss::error::{Error, Result};
use verbss::io::write_atomic;

pub use frame::{check_view, Layout};
pub use scene::{Camera, Scene, Section, State};

use raster::Canvas;

/// Cells and edges are clipped to the window grown by this fraction of its
/// spans (the cut lines stay outside the plot).
const CLIP_MARGIN: f64 = 0.02;

/// The embedded font of the pictures' text.
const FONT: &[u8] = include_bytes!("../fonts/DejaVuSans-subset.ttf");

/// Registers the embedded font as plotters' `sans-serif` (once).
fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The font is a fixed, valid file: a failure would show as missing text.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

/// How to draw a picture.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Options {
    /// Width in pixels (the height follows the window's aspect ratio).
    pub width: u32,
    /// The window `[u0, u1, v0, v1]` to show (mesh coordinates in 2D and cuts,
    /// screen coordinates of the camera in 3D); the whole scene when `None`.
    /// It must pass [`check_view`].
    pub view: Option<[f64; 4]>,
    /// Draw the element edges.
    pub edges: bool,
    /// Text at the start of the header line (e.g. the file, the step).
    pub title: String,
}

impl Default for Options {
    /// 1600 px wide, whole scene, edges drawn, no title.
    fn default() -> Options {
        Options {
            width: 1600,
            view: None,
            edges: true,
            title: String::new(),
        }
    }
}

/// An RGB picture, 3 bytes per pixel, rows top to bottom.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The pixels.
    pub rgb: Vec<u8>,
}

impl Image {
    /// The picture encoded as PNG.
    pub fn png_bytes(&self) -> Result<Vec<u8>> {
        let mut out = Vec::new();
        encode_png(self, &mut out).map_err(|e| Error::Render(e.to_string()))?;
        Ok(out)
    }

    /// Writes the picture as a PNG file (atomically).
    pub fn write_png(&self, path: &Path) -> Result<()> {
        write_atomic(path, |w: &mut dyn Write| {
            encode_png(self, w).map_err(std::io::Error::other)
        })
    }

    /// Number of pixels of colour `c`.
    pub fn count(&self, c: colour::Rgb) -> usize {
        self.rgb.chunks_exact(3).filter(|p| *p == c).count()
    }
}

fn encode_png(image: &Image, w: &mut dyn Write) -> std::result::Result<(), png::EncodingError> {
    let mut encoder = png::Encoder::new(w, image.width, image.height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::Default);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(&image.rgb)?;
    writer.finish()
}

/// Draws `scene` as an RGB picture: plotters' frame, then the polygons filled
/// with a depth buffer, then the edges (antialiased, opacity
/// [`colour::edge_alpha`] of their length in pixels, hidden behind nearer
/// surfaces).
pub fn png(scene: &Scene, options: &Options) -> Result<Image> {
    let layout = Layout::new(scene, options)?;
    let (w, h) = (layout.width, layout.height);
    let mut rgb = vec![255u8; 3 * w as usize * h as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
        frame::draw(&root, &layout, scene, &options.title)?;
        root.present().map_err(|e| Error::Render(e.to_string()))?;
    }
    let [x0, y0, x1, y1] = layout.plot;
    let mut canvas = Canvas::new(&mut rgb, w as usize, [x0, y0, x1, y1]);
    let window = clip::grown(layout.window, CLIP_MARGIN);
    let (mut inside, mut corners) = (Vec::with_capacity(8), Vec::with_capacity(8));
    for k in 0..scene.len() {
        clip::polygon(scene.polygon(k), window, &mut inside);
        corners.clear();
        corners.extend(inside.iter().map(|&p| layout.map(p)));
        canvas.polygon(&corners, scene.colours[k]);
    }
    if options.edges {
        for e in &scene.edges {
            let Some([a, b]) = clip::segment(e[0], e[1], window) else {
                continue;
            };
            let alpha = colour::edge_alpha(layout.length(e[0], e[1]));
            let (a, b) = (layout.map(a), layout.map(b));
            canvas.line(a, b, colour::EDGE, alpha, scene.depth_tolerance);
        }
    }
    Ok(Image {
        width: w,
        height: h,
        rgb,
    })
}

/// Draws `scene` as an SVG document: plotters' frame, then the polygons (far
/// to near, each with its outline) with float coordinates; cells outside the
/// window are left out and those across its border cut at its margin.
pub fn svg(scene: &Scene, options: &Options) -> Result<String> {
    let layout = Layout::new(scene, options)?;
    let mut doc = String::new();
    {
        let root =
            SVGBackend::with_string(&mut doc, (layout.width, layout.height)).into_drawing_area();
        frame::draw(&root, &layout, scene, &options.title)?;
        root.present().map_err(|e| Error::Render(e.to_string()))?;
    }
    let end = doc
        .rfind("</svg>")
        .ok_or_else(|| Error::Render("plotters wrote no </svg>".into()))?;
    doc.truncate(end);
    let [x0, y0, x1, y1] = layout.plot;
    let _ = write!(
        doc,
        "<clipPath id=\"plot\"><rect x=\"{x0}\" y=\"{y0}\" width=\"{}\" height=\"{}\"/></clipPath>\n<g clip-path=\"url(#plot)\" stroke-linejoin=\"round\">\n",
        x1 - x0,
        y1 - y0
    );
    let mut order: Vec<usize> = (0..scene.len()).collect();
    let depth = |k: usize| {
        let p = scene.polygon(k);
        p.iter().map(|q| q[2]).sum::<f64>() / p.len() as f64
    };
    order.sort_by(|&a, &b| depth(b).total_cmp(&depth(a)));
    let e = colour::EDGE;
    let window = clip::grown(layout.window, CLIP_MARGIN);
    let mut inside = Vec::with_capacity(8);
    for k in order {
        let polygon = scene.polygon(k);
        clip::polygon(polygon, window, &mut inside);
        if inside.is_empty() {
            continue;
        }
        let c = scene.colours[k];
        let _ = write!(doc, "<polygon points=\"");
        let mut len = 0.0;
        for (i, &p) in polygon.iter().enumerate() {
            len += layout.length(p, polygon[(i + 1) % polygon.len()]);
        }
        for &p in &inside {
            let p = layout.map(p);
            let _ = write!(doc, "{:.2},{:.2} ", p[0], p[1]);
        }
        let _ = write!(doc, "\" fill=\"#{:02x}{:02x}{:02x}\"", c[0], c[1], c[2]);
        if options.edges {
            let alpha = colour::edge_alpha(len / polygon.len() as f64);
            let _ = write!(
                doc,
                " stroke=\"#{:02x}{:02x}{:02x}\" stroke-opacity=\"{alpha:.2}\" stroke-width=\"0.7\"",
                e[0], e[1], e[2]
            );
        }
        doc.push_str("/>\n");
    }
    doc.push_str("</g>\n</svg>\n");
    Ok(doc)
}

/// Writes `scene` to `path`, as SVG when its extension is `.svg` and PNG when
/// it is `.png`.
pub fn write(path: &Path, scene: &Scene, options: &Options) -> Result<()> {
    match path.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("png") => png(scene, options)?.write_png(path),
        Some(e) if e.eq_ignore_ascii_case("svg") => {
            let doc = svg(scene, options)?;
            write_atomic(path, |w: &mut dyn Write| w.write_all(doc.as_bytes()))
        }
        _ => Err(Error::InvalidSetting(format!(
            "{}: unknown picture format (expected .png or .svg)",
            path.display()
        ))),
    }
}

/// An animated GIF being written, one [`Image`] per frame; every frame must
/// have the first one's size. The frames are spooled to an anonymous
/// temporary file (gone with the process, however it ends) and
/// [`Gif::finish`] writes the whole GIF with [`write_atomic`]: until then (a
/// failed or killed run) the target keeps what it held.
pub struct Gif {
    path: PathBuf,
    encoder: gif::Encoder<BufWriter<File>>,
    size: (u32, u32),
    delay: u16,
}

impl Gif {
    /// Starts `path` with frames `width × height` shown `delay` hundredths of
    /// a second each, looping forever.
    pub fn create(path: &Path, width: u32, height: u32, delay: u16) -> Result<Gif> {
        let (w, h) = (u16::try_from(width), u16::try_from(height));
        let (Ok(w), Ok(h)) = (w, h) else {
            return Err(Error::InvalidSetting(format!(
                "a GIF frame of {width} × {height} pixels (at most 65535 each way)"
            )));
        };
        let spool = tempfile::tempfile().map_err(|source| Error::Io {
            path: std::env::temp_dir(),
            source,
        })?;
        let mut encoder =
            gif::Encoder::new(BufWriter::new(spool), w, h, &[]).map_err(|e| gif_error(path, e))?;
        encoder
            .set_repeat(gif::Repeat::Infinite)
            .map_err(|e| gif_error(path, e))?;
        Ok(Gif {
            path: path.to_path_buf(),
            encoder,
            size: (width, height),
            delay,
        })
    }

    /// Ends the GIF and writes it to its target (atomically).
    pub fn finish(self) -> Result<()> {
        let io = |source| Error::Io {
            path: self.path.clone(),
            source,
        };
        let mut spool = self
            .encoder
            .into_inner()
            .and_then(|w| w.into_inner().map_err(|e| e.into_error()))
            .map_err(io)?;
        spool.seek(SeekFrom::Start(0)).map_err(io)?;
        write_atomic(&self.path, |w: &mut dyn Write| {
            std::io::copy(&mut spool, w).map(|_| ())
        })
    }

    /// Appends a frame, quantised to 255 colours learnt from it (NeuQuant)
    /// plus [`colour::INVERTED`] exactly, so that inverted cells stay the loud
    /// red of the PNG and SVG pictures however few pixels they cover.
    pub fn push(&mut self, image: &Image) -> Result<()> {
        if (image.width, image.height) != self.size {
            return Err(Error::InvalidSetting(format!(
                "GIF frame of {} × {} pixels, the first was {} × {}",
                image.width, image.height, self.size.0, self.size.1
            )));
        }
        let rgba: Vec<u8> = image
            .rgb
            .chunks_exact(3)
            .flat_map(|p| [p[0], p[1], p[2], 255])
            .collect();
        let learnt = color_quant::NeuQuant::new(10, 255, &rgba);
        let mut palette = learnt.color_map_rgb();
        let inverted = (palette.len() / 3) as u8;
        palette.extend_from_slice(&colour::INVERTED);
        let pixels: Vec<u8> = rgba
            .chunks_exact(4)
            .map(|p| {
                if p[..3] == colour::INVERTED {
                    inverted
                } else {
                    learnt.index_of(p) as u8
                }
            })
            .collect();
        let mut frame = gif::Frame::from_palette_pixels(
            self.size.0 as u16,
            self.size.1 as u16,
            pixels,
            palette,
            None,
        );
        frame.delay = self.delay;
        self.encoder
            .write_frame(&frame)
            .map_err(|e| gif_error(&self.path, e))
    }
}

fn gif_error(path: &Path, e: gif::EncodingError) -> Error {
    match e {
        gif::EncodingError::Io(source) => Error::Io {
            path: path.to_path_buf(),
            source,
        },
        other => Error::Render(format!("{}: {other}", path.display())),
    }
}

#[cfg(test)]
mod tests;
