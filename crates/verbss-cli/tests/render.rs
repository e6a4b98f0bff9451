//! `verbss render` pictures and the `--html` / `--gif` outputs of `verbss run`.

use std::path::Path;

mod common;

use common::{stderr, verbss, SQUARE};

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
    // Of the 18,042 + 4,800 cells, those meeting the window (grown by 2 %).
    assert_eq!(doc.matches("<polygon").count(), 8_277);

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

/// `verbss ARGS` in a child killed after 20 s (only a hang takes that
/// long): the exit code and stderr.
fn within_20_s(args: &[&str]) -> (Option<i32>, String) {
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_verbss"))
        .args(args)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("run verbss");
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(20);
    while child.try_wait().expect("wait").is_none() {
        if std::time::Instant::now() > deadline {
            child.kill().expect("kill");
            panic!("verbss {args:?} still running after 20 s");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let out = child.wait_with_output().expect("output");
    (out.status.code(), stderr(&out))
}

#[test]
fn deep_and_far_windows_are_clipped_drawn_or_refused() {
    let dir = tempfile::tempdir().unwrap();
    let naca = format!("{SU2}mesh_NACA0012_inv.su2");
    let png = dir.path().join("z.png");
    let png = png.to_str().unwrap();
    // The trailing edge at 1e-4 and 1e-8: the cells around it fill the plot.
    for view in [
        "0.9999,1.0001,-0.0001,0.0001",
        "0.99999999,1.00000001,-1e-8,1e-8",
    ] {
        let (code, err) = within_20_s(&["render", &naca, "-o", png, &format!("--view={view}")]);
        assert_eq!(code, Some(0), "{view}: {err}");
        let (w, h, rgb) = decode(Path::new(png));
        assert!(coloured(&rgb) as f64 > 0.4 * f64::from(w * h), "{view}");
    }
    for view in [
        "0,1e-300,0,1e-300",
        "-1e307,1e307,-1e307,1e307",
        "1e300,1.00001e300,0,1e295",
    ] {
        let (code, err) = within_20_s(&["render", &naca, "-o", png, &format!("--view={view}")]);
        assert_eq!(code, Some(0), "{view}: {err}");
    }
    // The SVG of a zoom holds only the cells near the window, with small numbers.
    let svg = dir.path().join("z.svg");
    let view = "--view=0.9999,1.0001,-0.0001,0.0001";
    let (code, err) = within_20_s(&["render", &naca, "-o", svg.to_str().unwrap(), view]);
    assert_eq!(code, Some(0), "{err}");
    let doc = std::fs::read_to_string(&svg).unwrap();
    let polygons: Vec<&str> = doc.split("<polygon points=\"").skip(1).collect();
    assert!((1..200).contains(&polygons.len()), "{}", polygons.len());
    for p in polygons {
        let points = &p[..p.find('"').unwrap()];
        for x in points.split([' ', ',']).filter(|x| !x.is_empty()) {
            assert!(x.parse::<f64>().unwrap().abs() < 1e4, "{x}");
        }
    }
    for (view, message) in [
        (
            "-1e308,1e308,-1e308,1e308",
            "with finite x1 - x0 and y1 - y0",
        ),
        ("1,1.000000000000001,0,1", "above 1e-12 of the coordinates"),
        ("nan,1,0,1", "expected finite x0 < x1"),
    ] {
        let (code, err) = within_20_s(&["render", &naca, "-o", png, &format!("--view={view}")]);
        assert_eq!(code, Some(2), "{view}: {err}");
        assert!(err.contains("--view") && err.contains(message), "{err}");
    }
}

#[test]
fn non_finite_numbers_of_render_are_refused() {
    let brick = format!("{SU2}mesh_brick_tets_ffd.su2");
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("b.png");
    for (option, value, message) in [
        ("--azimuth", "NaN", "'NaN' is not a finite angle in degrees"),
        (
            "--elevation",
            "inf",
            "'inf' is not a finite angle in degrees",
        ),
        (
            "--cut",
            "z=NaN",
            "the plane's position must be a finite number",
        ),
    ] {
        let o = verbss(&["render", &brick, "-o", png.to_str().unwrap(), option, value]);
        assert_eq!(o.status.code(), Some(2), "{option} {value}");
        let err = stderr(&o);
        assert!(err.contains(option) && err.contains(message), "{err}");
    }
    assert!(!png.exists());
}

/// The unit square of `common` in `dir`.
fn square(dir: &Path) -> String {
    let path = dir.join("square.su2");
    std::fs::write(&path, SQUARE).unwrap();
    path.to_str().unwrap().to_owned()
}

/// `verbss deform` of the square's group `rest` in `steps` steps, with `extra`.
fn deform_square(square: &str, out: &Path, steps: &str, extra: &[&str]) -> std::process::Output {
    let mut args = vec![
        "deform",
        square,
        "-o",
        out.to_str().unwrap(),
        "--moving",
        "rest",
        "--translate",
        "0.01,0",
        "--steps",
        steps,
        "--quiet",
    ];
    args.extend_from_slice(extra);
    verbss(&args)
}

/// The number of frames of a complete GIF (panics on a truncated one).
fn gif_frames(path: &Path) -> usize {
    let mut decoder = gif::DecodeOptions::new()
        .read_info(std::fs::File::open(path).unwrap())
        .unwrap();
    let mut frames = 0;
    while decoder.read_next_frame().unwrap().is_some() {
        frames += 1;
    }
    frames
}

/// The names in `dir`, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    names
}

#[test]
fn the_view_of_run_deform_and_demo_is_checked_like_render() {
    let dir = tempfile::tempdir().unwrap();
    let square = square(dir.path());
    let out = dir.path().join("moved.su2");
    for view in ["--view=1,1.000000000000001,0,1", "--view=0,inf,0,1"] {
        let o = deform_square(&square, &out, "2", &["--gif", "x.gif", view]);
        assert_eq!(o.status.code(), Some(2), "{view}");
        assert!(stderr(&o).contains("--view"), "{}", stderr(&o));
        let o = verbss(&["demo", "--out", dir.path().to_str().unwrap(), view]);
        assert_eq!(o.status.code(), Some(2), "{view}");
        assert!(stderr(&o).contains("--view"), "{}", stderr(&o));
    }
    assert!(!out.exists());
}

#[test]
fn pictures_that_cannot_be_written_never_cost_the_mesh_or_the_exit_code() {
    let dir = tempfile::tempdir().unwrap();
    let square = square(dir.path());
    let blocker = dir.path().join("blocker");
    std::fs::write(&blocker, "a regular file").unwrap();
    let out = dir.path().join("moved.su2");
    let html = blocker.join("report.html");
    let gif = blocker.join("moved.gif");
    let o = deform_square(
        &square,
        &out,
        "2",
        &[
            "--html",
            html.to_str().unwrap(),
            "--gif",
            gif.to_str().unwrap(),
        ],
    );
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert!(
        err.contains("warning: no HTML report: cannot create the folder"),
        "{err}"
    );
    assert!(
        err.contains("warning: no GIF: cannot create the folder"),
        "{err}"
    );
    assert!(out.exists());
}

#[test]
fn a_gif_is_only_ever_replaced_by_a_complete_one() {
    let dir = tempfile::tempdir().unwrap();
    let square = square(dir.path());
    let pictures = dir.path().join("pictures");
    std::fs::create_dir(&pictures).unwrap();
    let gif = pictures.join("moved.gif");
    let gif_arg = ["--gif", gif.to_str().unwrap()];
    let out = dir.path().join("moved.su2");
    let o = deform_square(&square, &out, "2", &gif_arg);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(gif_frames(&gif), 3);
    let valid = std::fs::read(&gif).unwrap();

    // A run failing with exit 2 at its end (its mesh's path is a folder).
    let folder = dir.path().join("folder.su2");
    std::fs::create_dir(&folder).unwrap();
    let o = deform_square(&square, &folder, "3", &gif_arg);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(std::fs::read(&gif).unwrap(), valid);
    assert_eq!(names(&pictures), ["moved.gif"]);

    // Two runs at once: each exits 0 and the GIF is one of theirs, whole.
    let runs: Vec<_> = ["3", "5"]
        .into_iter()
        .map(|steps| {
            let (square, out) = (square.clone(), dir.path().join(format!("m{steps}.su2")));
            let gif_arg = gif_arg.map(str::to_owned);
            std::thread::spawn(move || {
                let gif_arg: Vec<&str> = gif_arg.iter().map(String::as_str).collect();
                deform_square(&square, &out, steps, &gif_arg)
            })
        })
        .collect();
    for run in runs {
        let o = run.join().unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
    }
    assert!([4, 6].contains(&gif_frames(&gif)));
    assert_eq!(names(&pictures), ["moved.gif"]);

    // A run killed (SIGKILL) mid-way leaves the GIF as it was, and nothing beside it.
    let valid = std::fs::read(&gif).unwrap();
    let demo = dir.path().join("demo");
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_verbss"))
        .args([
            "demo",
            "--out",
            demo.to_str().unwrap(),
            "--quiet",
            "--every",
            "1",
        ])
        .args(gif_arg)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let second_step = demo.join("naca0012_0002.vtu");
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(120);
    while !second_step.exists() && std::time::Instant::now() < deadline {
        assert!(child.try_wait().unwrap().is_none(), "the demo ended early");
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
    assert!(second_step.exists(), "the demo wrote no step 2 in 120 s");
    let running = child.try_wait().unwrap().is_none();
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(running, "the demo ended before it was killed");
    assert_eq!(std::fs::read(&gif).unwrap(), valid);
    assert_eq!(names(&pictures), ["moved.gif"]);
}
