use std::path::Path;

use verbss::mesh::Mesh;
use verbss::quality;

use super::*;

/// Red pixels of the legend's inverted swatch at 1600 px: 30 × 30 with a black border.
const SWATCH: usize = 29 * 29;

const SU2: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/meshes/su2/");

fn read(name: &str) -> Mesh {
    verbss::io::read(Path::new(&format!("{SU2}{name}"))).unwrap()
}

/// Quality of every cell on its own orientation, with `bad` flagged inverted.
fn values(mesh: &Mesh, bad: &[usize]) -> (Vec<f64>, Vec<bool>) {
    let q = quality::qualities(mesh, &mesh.coords, &quality::orientation(mesh));
    let mut inverted = vec![false; mesh.cell_count()];
    for &c in bad {
        inverted[c] = true;
    }
    (q, inverted)
}

fn scene(mesh: &Mesh, bad: &[usize], section: &Section) -> Result<Scene> {
    let (q, inv) = values(mesh, bad);
    let state = State {
        coords: &mesh.coords,
        quality: &q,
        inverted: &inv,
    };
    Scene::new(mesh, state, section, Camera::default())
}

/// The fraction of the plot's pixels that show a cell: colours with some
/// saturation (max − min channel > 40: all of viridis, none of the white
/// background or the grey edges and text).
fn coloured(image: &Image, scene: &Scene, options: &Options) -> f64 {
    let [x0, y0, x1, y1] = Layout::new(scene, options).unwrap().plot;
    let mut n = 0;
    for y in y0..y1 {
        for x in x0..x1 {
            let k = 3 * (y as usize * image.width as usize + x as usize);
            let p = &image.rgb[k..k + 3];
            if p.iter().max().unwrap() - p.iter().min().unwrap() > 40 {
                n += 1;
            }
        }
    }
    n as f64 / ((x1 - x0) * (y1 - y0)) as f64
}

#[test]
fn naca0012_png_has_the_asked_width_and_cells_in_colour() {
    let mesh = read("mesh_NACA0012_inv.su2");
    let scene = scene(&mesh, &[], &Section::All).unwrap();
    assert_eq!(scene.len(), 10_216);
    let image = png(&scene, &Options::default()).unwrap();
    assert_eq!(image.width, 1600);
    assert_eq!(image.rgb.len(), 3 * 1600 * image.height as usize);
    let layout = Layout::new(&scene, &Options::default()).unwrap();
    assert_eq!(image.height, layout.height);
    // A circular farfield: an almost square plot.
    let [x0, y0, x1, y1] = layout.plot;
    assert!(((y1 - y0) as f64 / (x1 - x0) as f64 - 1.0).abs() < 0.05);
    // The disc of the farfield fills π/4 of its square, less the padding.
    let f = coloured(&image, &scene, &Options::default());
    assert!(f > 0.7 && f < 0.785, "{f}");
    assert_eq!(
        image.count(colour::INVERTED),
        SWATCH,
        "only the legend's swatch"
    );
}

#[test]
fn inverted_cells_show_in_red_and_the_zoom_window_magnifies() {
    let mesh = read("mesh_NACA0012_inv.su2");
    // The cell nearest the leading edge.
    let near = (0..mesh.cell_count())
        .min_by(|&a, &b| {
            let d = |c: usize| {
                let p = quality::centroid(&mesh, &mesh.coords, c);
                p[0].hypot(p[1])
            };
            d(a).total_cmp(&d(b))
        })
        .unwrap();
    let scene = scene(&mesh, &[near], &Section::All).unwrap();
    assert_eq!(scene.inverted, 1);
    let whole = png(&scene, &Options::default()).unwrap();
    // A window 10 times the cell's size.
    let nodes = mesh.cells.cell(near);
    let size = nodes
        .iter()
        .map(|&a| {
            nodes
                .iter()
                .map(|&b| (mesh.point(a)[0] - mesh.point(b)[0]).abs())
                .fold(0.0, f64::max)
        })
        .fold(0.0, f64::max);
    let c = quality::centroid(&mesh, &mesh.coords, near);
    let options = Options {
        view: Some([
            c[0] - 5.0 * size,
            c[0] + 5.0 * size,
            c[1] - 2.5 * size,
            c[1] + 2.5 * size,
        ]),
        ..Options::default()
    };
    let zoom = png(&scene, &options).unwrap();
    let red = |i: &Image| i.count(colour::INVERTED) - SWATCH;
    assert!(
        red(&zoom) > 100 * red(&whole).max(1),
        "{} {}",
        red(&zoom),
        red(&whole)
    );
    assert!(red(&zoom) > 1000);
}

#[test]
fn svg_has_one_polygon_per_cell_and_the_colour_bar_text() {
    let mesh = read("mesh_NACA0012_inv.su2");
    let scene = scene(&mesh, &[], &Section::All).unwrap();
    let doc = svg(&scene, &Options::default()).unwrap();
    assert_eq!(doc.matches("<polygon").count(), 10_216);
    assert!(doc.contains(">\nquality\n</text>"));
    assert!(doc.contains(">\ninverted: 0\n</text>"));
    assert!(doc.trim_end().ends_with("</svg>"));
}

#[test]
fn brick_surface_shows_three_faces_and_a_group_only_its_own() {
    let mesh = read("mesh_brick_tets_ffd.su2");
    let all = scene(&mesh, &[], &Section::All).unwrap();
    let z_p = scene(&mesh, &[], &Section::Groups(vec!["z_p".into()])).unwrap();
    assert_eq!(z_p.len(), mesh.group("z_p").unwrap().facets.len());
    // z_p is 2 of the box's 10 units of area.
    assert!(all.len() > 4 * z_p.len());
    let image = png(&all, &Options::default()).unwrap();
    let f = coloured(&image, &all, &Options::default());
    assert!(f > 0.5, "{f}");
}

#[test]
fn cut_through_the_hex_brick_is_a_grid_of_quads() {
    let mesh = read("mesh_brick_hex_ffd.su2");
    let cut = scene(&mesh, &[], &Section::Cut { axis: 2, at: 0.51 }).unwrap();
    assert!(cut.len() > 100);
    assert!((0..cut.len()).all(|k| cut.polygon(k).len() == 4));
    assert_eq!(cut.axes, Some(["x", "y"]));
    let b = cut.bounds();
    assert!(
        (b[0] - 0.0).abs() < 1e-9 && (b[1] - 2.0).abs() < 1e-9,
        "{b:?}"
    );
    let image = png(&cut, &Options::default()).unwrap();
    // The 2 × 1 rectangle in its window padded by 0.04 each way.
    let f = coloured(&image, &cut, &Options::default());
    assert!(f > 0.85, "{f}");
}

#[test]
fn bad_sections_and_options_are_errors_that_say_why() {
    let naca = read("mesh_NACA0012_inv.su2");
    let brick = read("mesh_brick_tets_ffd.su2");
    let msg = |r: Result<Scene>| r.err().unwrap().to_string();
    assert_eq!(
        msg(scene(&naca, &[], &Section::Cut { axis: 2, at: 0.0 })),
        "invalid setting: a 2D mesh is drawn whole: groups and cuts are for 3D meshes"
    );
    assert_eq!(
        msg(scene(&brick, &[], &Section::Cut { axis: 0, at: 5.0 })),
        "invalid setting: the plane x = 5 cuts no cell"
    );
    assert_eq!(
        msg(scene(&brick, &[], &Section::Groups(vec!["wing".into()]))),
        "unknown group 'wing' (the mesh has: x_m, x_p, y_m, y_p, z_m, z_p)"
    );
    let s = scene(&naca, &[], &Section::All).unwrap();
    let options = Options {
        view: Some([1.0, 0.0, 0.0, 1.0]),
        ..Options::default()
    };
    assert_eq!(
        png(&s, &options).err().unwrap().to_string(),
        "invalid setting: view window 1,0,0,1 (expected x0 < x1 and y0 < y1, each span finite and above 1e-12 of the coordinates)"
    );
    let dir = tempfile::tempdir().unwrap();
    assert_eq!(
        write(&dir.path().join("a.jpg"), &s, &Options::default())
            .err()
            .unwrap()
            .to_string(),
        format!(
            "invalid setting: {}: unknown picture format (expected .png or .svg)",
            dir.path().join("a.jpg").display()
        )
    );
}

#[test]
fn png_and_gif_files_decode_to_the_pictures_written() {
    let mesh = read("mesh_NACA0012_inv.su2");
    let scene = scene(&mesh, &[], &Section::All).unwrap();
    let options = Options {
        width: 400,
        ..Options::default()
    };
    let image = png(&scene, &options).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("naca.png");
    write(&path, &scene, &options).unwrap();
    let decoder = png::Decoder::new(File::open(&path).unwrap());
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!((info.width, info.height), (image.width, image.height));
    assert_eq!(&buf[..info.buffer_size()], &image.rgb[..]);

    let gif_path = dir.path().join("naca.gif");
    let mut gif = Gif::create(&gif_path, image.width, image.height, 5).unwrap();
    gif.push(&image).unwrap();
    // The inverted swatch, and a few inverted pixels added to the second
    // frame, keep their exact red.
    let mut marked = image.clone();
    marked.rgb[..30].copy_from_slice(&colour::INVERTED.repeat(10));
    gif.push(&marked).unwrap();
    let small = Image {
        width: 10,
        height: 10,
        rgb: vec![0; 300],
    };
    assert_eq!(
        gif.push(&small).err().unwrap().to_string(),
        format!(
            "invalid setting: GIF frame of 10 × 10 pixels, the first was 400 × {}",
            image.height
        )
    );
    // Nothing at the target before `finish`; a dropped GIF leaves nothing.
    assert!(!gif_path.exists());
    gif.finish().unwrap();
    let dropped = dir.path().join("dropped.gif");
    drop(Gif::create(&dropped, 10, 10, 5).unwrap());
    let mut names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(names, ["naca.gif", "naca.png"]);
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options.read_info(File::open(&gif_path).unwrap()).unwrap();
    let mut frames = 0;
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        assert_eq!(
            (u32::from(frame.width), u32::from(frame.height)),
            (400, image.height)
        );
        let red = frame
            .buffer
            .chunks_exact(4)
            .filter(|p| p[..3] == colour::INVERTED)
            .count();
        let expected = if frames == 0 { &image } else { &marked };
        assert_eq!(red, expected.count(colour::INVERTED), "frame {frames}");
        frames += 1;
    }
    assert_eq!(frames, 2);
}
