//! Colours: quality → viridis, inverted → a loud red, 3D shading.

use plotters::style::colors::colormaps::{ColorMap, ViridisRGB};

/// An RGB colour.
pub type Rgb = [u8; 3];

/// The colour of inverted elements: a red that viridis never reaches.
pub const INVERTED: Rgb = [235, 0, 40];

/// The colour of element edges (blended with an opacity that depends on the
/// edge's length in pixels, see [`edge_alpha`]).
pub const EDGE: Rgb = [15, 15, 25];

/// Background of the picture.
pub const BACKGROUND: Rgb = [255, 255, 255];

/// The viridis colour of quality `q ∈ [0, 1]` (0 dark purple, 1 yellow);
/// values outside are clamped.
pub fn quality(q: f64) -> Rgb {
    let c = ViridisRGB.get_color_normalized(q.clamp(0.0, 1.0), 0.0, 1.0);
    [c.0, c.1, c.2]
}

/// The colour of a cell: [`INVERTED`] when inverted, else [`quality`],
/// scaled by `shade ∈ [0, 1]` (1 in 2D, Lambert shading in 3D).
pub fn cell(q: f64, inverted: bool, shade: f64) -> Rgb {
    let base = if inverted { INVERTED } else { quality(q) };
    base.map(|c| (f64::from(c) * shade).round().clamp(0.0, 255.0) as u8)
}

/// Opacity of an edge `len` pixels long: `clamp(len / 14, 0.12, 0.7)`, so
/// that edges of cells a few pixels wide shade the colours instead of
/// hiding them.
pub fn edge_alpha(len: f64) -> f64 {
    (len / 14.0).clamp(0.12, 0.7)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ends_of_the_map_and_inverted() {
        assert_eq!(quality(0.0), [68, 1, 84]);
        assert_eq!(quality(1.0), [254, 232, 37]);
        assert_eq!(quality(-3.0), quality(0.0));
        assert_eq!(cell(0.5, true, 1.0), INVERTED);
        assert_eq!(cell(1.0, false, 0.5), [127, 116, 19]);
    }
}
