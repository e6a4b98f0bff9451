//! `verbss render` pictures and the `--html` / `--gif` outputs of `verbss run`.

use std::path::Path;

mod common;

use common::verbss;

const SU2: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/meshes/su2/");
const CASE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../cases/naca0012_bump.toml"
);

/// Width, height and RGB pixels of a PNG file.
fn decode(path: &Path) -> (u32, u32, Vec<u8>) {
    let decoder = png::Decoder::new(std::fs::File::open(path).unwrap());
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb);
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

/// Pixels with some saturation (max − min channel > 40): cells, not the
/// white background, the grey edges or the text.
fn coloured(rgb: &[u8]) -> usize {
    rgb.chunks_exact(3)
        .filter(|p| p.iter().max().unwrap() - p.iter().min().unwrap() > 40)
        .count()
}

#[test]
fn render_png_of_a_2d_mesh_is_1600_wide_and_mostly_cells() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("naca.png");
    let mesh = format!("{SU2}mesh_NACA0012_inv.su2");
    let o = verbss(&["render", &mesh, "-o", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (w, h, rgb) = decode(&out);
    assert_eq!(w, 1600);
    assert!(h > 1000 && h < 1700, "{h}");
    // The circular farfield covers well over a third of the picture.
    assert!(
        coloured(&rgb) as f64 > 0.4 * f64::from(w * h),
        "{}",
        coloured(&rgb)
    );
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains(&format!("1600 × {h} px, 10216 polygons")),
        "{stdout}"
    );
}

#[test]
fn render_svg_zoom_and_3d_cut() {
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("rae.svg");
    let mesh = format!("{SU2}mesh_RAE2822_turb_ffd.su2");
    let o = verbss(&[
        "render",
        &mesh,
        "-o",
        svg.to_str().unwrap(),
        "--view",
        "-0.1,1.1,-0.3,0.3",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let doc = std::fs::read_to_string(&svg).unwrap();
    assert_eq!(doc.matches("<polygon").count(), 18_042 + 4_800);

    let cut = dir.path().join("cut.png");
    let brick = format!("{SU2}mesh_brick_tets_ffd.su2");
    let o = verbss(&[
        "render",
        &brick,
        "-o",
        cut.to_str().unwrap(),
        "--cut",
        "y=0.5",
        "--width",
        "800",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (w, h, rgb) = decode(&cut);
    assert_eq!(w, 800);
    assert!(coloured(&rgb) as f64 > 0.4 * f64::from(w * h));

    let o = verbss(&[
        "render",
        &brick,
        "-o",
        cut.to_str().unwrap(),
        "--cut",
        "w=1",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("'w=1' is not a plane like z=0.5"));
}

/// The numbers of the steps table in report.html, row by row.
fn table_rows(page: &str) -> Vec<Vec<f64>> {
    let table = &page[page.find("<table class=\"steps\">").unwrap()..];
    let table = &table[..table.find("</table>").unwrap()];
    table
        .split("<tr>")
        .filter(|row| row.starts_with("<td>"))
        .map(|row| {
            row.split("<td>")
                .skip(1)
                .map(|cell| {
                    let v = &cell[..cell.find("</td>").unwrap()];
                    match v {
                        "true" => 1.0,
                        "false" => 0.0,
                        v => v.parse().unwrap(),
                    }
                })
                .collect()
        })
        .collect()
}

#[test]
fn run_html_report_shows_the_numbers_of_report_json_and_gif_has_a_frame_per_step() {
    let dir = tempfile::tempdir().unwrap();
    let html = dir.path().join("report.html");
    let gif = dir.path().join("bump.gif");
    let o = verbss(&[
        "run",
        CASE,
        "--out",
        dir.path().to_str().unwrap(),
        "-q",
        "--html",
        html.to_str().unwrap(),
        "--gif",
        gif.to_str().unwrap(),
        "--view",
        "-0.2,1.2,-0.5,0.5",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let page = std::fs::read_to_string(&html).unwrap();
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("report.json")).unwrap())
            .unwrap();
    let steps = json["steps"].as_array().unwrap();
    let rows = table_rows(&page);
    assert_eq!(rows.len(), steps.len());
    for (row, s) in rows.iter().zip(steps) {
        let f = |k: &str| s[k].as_f64().unwrap();
        let mut expected = vec![
            f("step"),
            f("iterations"),
            f("residual"),
            if s["converged"].as_bool().unwrap() {
                1.0
            } else {
                0.0
            },
            f("seconds"),
            f("min_quality"),
            f("mean_quality"),
            f("inverted"),
        ];
        expected.extend(
            s["bins"]
                .as_array()
                .unwrap()
                .iter()
                .map(|b| b.as_f64().unwrap()),
        );
        assert_eq!(row, &expected);
    }
    // Self-contained: pictures inline, charts inline, nothing fetched.
    // The input, the last step and the worst step when it is another one.
    let min_q = |s: &serde_json::Value| s["min_quality"].as_f64().unwrap();
    let worst = steps[1..]
        .iter()
        .reduce(|a, b| if min_q(b) < min_q(a) { b } else { a })
        .unwrap();
    let pictures = if worst["step"] == steps.last().unwrap()["step"] {
        2
    } else {
        3
    };
    assert_eq!(
        page.matches("src=\"data:image/png;base64,").count(),
        pictures
    );
    assert_eq!(page.matches("<svg").count(), 5);
    assert!(!page.contains("src=\"http") && !page.contains("<link") && !page.contains("<script"));
    // The slowest step's convergence comes from report.json's history.
    let slowest = steps[1..]
        .iter()
        .max_by(|a, b| {
            a["seconds"]
                .as_f64()
                .unwrap()
                .total_cmp(&b["seconds"].as_f64().unwrap())
        })
        .unwrap();
    assert_eq!(
        slowest["history"].as_array().unwrap().len(),
        slowest["iterations"].as_u64().unwrap() as usize
    );
    assert!(page.contains(&format!(
        "Convergence of the slowest step (step {}, {} sweeps,",
        slowest["step"], slowest["iterations"]
    )));

    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options
        .read_info(std::fs::File::open(&gif).unwrap())
        .unwrap();
    let mut frames = 0;
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        assert_eq!(frame.width, 640);
        let rgb: Vec<u8> = frame
            .buffer
            .chunks_exact(4)
            .flat_map(|p| [p[0], p[1], p[2]])
            .collect();
        assert!(coloured(&rgb) > rgb.len() / 3 / 3);
        frames += 1;
    }
    assert_eq!(frames, steps.len());
}
