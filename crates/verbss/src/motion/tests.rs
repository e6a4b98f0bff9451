use super::*;
use std::f64::consts::PI;

fn clock(step: usize, steps: usize) -> Clock {
    Clock {
        step,
        steps,
        dt: 0.1,
    }
}

fn moved(m: &Motion, p: &[f64], c: Clock) -> Vec<f64> {
    let mut q = p.to_vec();
    m.apply(0, &mut q, c, &Frame::default()).unwrap();
    q
}

fn close(a: &[f64], b: &[f64]) {
    for (x, y) in a.iter().zip(b) {
        assert!((x - y).abs() < 1e-12, "{a:?} vs {b:?}");
    }
}

#[test]
fn translation_grows_linearly() {
    let m = Motion::Translation {
        displacement: [1.0, -2.0, 0.5],
    };
    close(&moved(&m, &[1.0, 1.0], clock(1, 4)), &[1.25, 0.5]);
    close(&moved(&m, &[0.0, 0.0, 0.0], clock(4, 4)), &[1.0, -2.0, 0.5]);
}

#[test]
fn rotation_2d_and_3d() {
    let m = Motion::Rotation {
        center: [1.0, 0.0, 0.0],
        axis: [0.0, 0.0, 1.0],
        angle: PI,
    };
    close(&moved(&m, &[2.0, 0.0], clock(1, 2)), &[1.0, 1.0]);
    close(&moved(&m, &[2.0, 0.0], clock(2, 2)), &[0.0, 0.0]);
    let m = Motion::Rotation {
        center: [0.0; 3],
        axis: [2.0, 0.0, 0.0],
        angle: PI / 2.0,
    };
    close(&moved(&m, &[5.0, 1.0, 0.0], clock(1, 1)), &[5.0, 0.0, 1.0]);
}

#[test]
fn pitch_plunge_follows_eq_10() {
    let (t0, h0, n_steps) = (40f64.to_radians(), 0.2, 160);
    let m = Motion::PitchPlunge {
        center: [0.25, 0.0, 0.0],
        axis: [0.0, 0.0, 1.0],
        pitch: t0,
        plunge: [0.0, h0, 0.0],
        period: None,
    };
    for n in [0, 13, 40, 100, 160] {
        let s = (2.0 * PI * n as f64 / n_steps as f64).sin();
        let (th, h) = (t0 * s, h0 * s);
        let expected = [0.25 + 0.75 * th.cos(), 0.75 * th.sin() + h];
        close(&moved(&m, &[1.0, 0.0], clock(n, n_steps)), &expected);
    }
}

#[test]
fn undulation_follows_eq_11() {
    let m = Motion::Undulation {
        head: [1.0, 0.0, 0.0],
        axis: [1.0, 0.0, 0.0],
        lateral: [0.0, 1.0, 0.0],
        amplitude: vec![0.02, -0.08, 0.16],
        wavelength: 1.0,
        speed: 1.5,
        ramp: 0,
    };
    for (n, x) in [(0, 1.0), (3, 1.4), (7, 2.0)] {
        let xi: f64 = x - 1.0;
        let t = n as f64 * 0.1;
        let a = 0.02 - 0.08 * xi + 0.16 * xi * xi;
        let y = a * (2.0 * PI / 1.0 * (xi - 1.5 * t)).cos();
        close(
            &moved(&m, &[x, 0.3, -1.0], clock(n, 60)),
            &[x, 0.3 + y, -1.0],
        );
    }
}

/// The paper's wing: span 2 along y from the origin, tip deflection 0.8 in z.
fn wing() -> Motion {
    Motion::Bending {
        root: [0.0; 3],
        span_axis: [0.0, 1.0, 0.0],
        direction: [0.0, 0.0, 1.0],
        span: 2.0,
        tip: 0.8,
    }
}

#[test]
fn bending_deflects_the_tip_and_turns_its_section() {
    let m = wing();
    // The clamped root and inboard points do not move.
    close(
        &moved(&m, &[0.3, 0.0, 0.1], clock(40, 40)),
        &[0.3, 0.0, 0.1],
    );
    close(
        &moved(&m, &[0.3, -0.5, 0.1], clock(40, 40)),
        &[0.3, -0.5, 0.1],
    );
    // The tip's axis point moves by δ_tip, half-way by δ_tip/2 at n = N/2.
    close(
        &moved(&m, &[0.3, 2.0, 0.0], clock(40, 40)),
        &[0.3, 2.0, 0.8],
    );
    close(
        &moved(&m, &[0.3, 2.0, 0.0], clock(20, 40)),
        &[0.3, 2.0, 0.4],
    );
    // A point above the tip's axis turns with the section: φ = atan(0.8).
    let phi = 0.8f64.atan();
    assert!((phi.to_degrees() - 38.66).abs() < 0.01);
    close(
        &moved(&m, &[0.3, 2.0, 0.1], clock(40, 40)),
        &[0.3, 2.0 - 0.1 * phi.sin(), 0.8 + 0.1 * phi.cos()],
    );
    // Mid-span: w = δ/4, φ = atan(δ/L).
    let phi = 0.4f64.atan();
    close(
        &moved(&m, &[0.0, 1.0, -0.2], clock(40, 40)),
        &[0.0, 1.0 + 0.2 * phi.sin(), 0.2 - 0.2 * phi.cos()],
    );
}

/// Outboard of the tip the parabola is not continued: a point beyond the
/// tip keeps its distance to the tip section's points (a rigid motion).
#[test]
fn beyond_the_tip_points_move_rigidly_with_the_tip_section() {
    let m = wing();
    let phi = 0.8f64.atan();
    // 0.3 beyond the tip on the axis: along the tip section's turned axis.
    close(
        &moved(&m, &[0.3, 2.3, 0.0], clock(40, 40)),
        &[0.3, 2.0 + 0.3 * phi.cos(), 0.8 + 0.3 * phi.sin()],
    );
    let tip = [[0.3, 2.0, 0.0], [0.3, 2.0, 0.1], [-0.2, 2.0, -0.05]];
    for outboard in [[0.3, 2.3, 0.1], [0.0, 2.15, -0.2]] {
        let after = moved(&m, &outboard, clock(40, 40));
        for t in tip {
            let was: f64 = (0..3).map(|d| (outboard[d] - t[d]).powi(2)).sum();
            let moved_t = moved(&m, &t, clock(40, 40));
            let is: f64 = (0..3).map(|d| (after[d] - moved_t[d]).powi(2)).sum();
            assert!(
                (is.sqrt() - was.sqrt()).abs() < 1e-12,
                "{outboard:?} to {t:?}"
            );
        }
    }
}

#[test]
fn final_positions_are_reached_exactly() {
    let p = vec![0.1 + 0.2, 0.7];
    let m = Motion::Positions(PositionSource::Final(HashMap::from([(3, p.clone())])));
    let mut q = vec![0.3, -1.0 / 3.0];
    m.apply(3, &mut q, clock(5, 5), &Frame::default()).unwrap();
    assert_eq!(q, p);
    let mut q = vec![0.3, 0.0];
    m.apply(3, &mut q, clock(1, 2), &Frame::default()).unwrap();
    close(&q, &[0.3 / 2.0 + p[0] / 2.0, 0.35]);
    let e = m
        .apply(4, &mut q, clock(1, 2), &Frame::default())
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "invalid setting: the positions give no position for node index 4 of a moving group"
    );
}

#[test]
fn invalid_settings_are_named() {
    let m = Motion::Bending {
        root: [0.0; 3],
        span_axis: [0.0, 1.0, 0.0],
        direction: [0.0, 2.0, 0.0],
        span: 1.0,
        tip: 0.1,
    };
    assert_eq!(
        m.validate(3).unwrap_err().to_string(),
        "invalid setting: the bending direction (normal to the span axis) must be a non-zero \
         vector of finite numbers (got 0, 0, 0)"
    );
}

/// A direction of huge finite numbers is a direction (its length
/// overflowed to infinity and it was called zero); an infinite one is
/// refused naming it.
#[test]
fn a_direction_of_huge_numbers_is_one() {
    let n = unit(&[1e308, 1e308, 0.0], "n").unwrap();
    assert!(
        (n[0] - 0.5f64.sqrt()).abs() < 1e-15 && n[0] == n[1] && n[2] == 0.0,
        "{n:?}"
    );
    assert_eq!(
        unit(&[f64::INFINITY, 0.0, 0.0], "the plane's normal").unwrap_err().to_string(),
        "invalid setting: the plane's normal must be a non-zero vector of finite numbers (got inf, 0, 0)"
    );
}
