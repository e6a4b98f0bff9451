//! What a picture shows, as coloured polygons and edges in picture
//! coordinates `(u, v, depth)`.
//!
//! - 2D mesh: every cell at `(x, y)`, edges the element edges.
//! - 3D mesh, [`Section::All`] or [`Section::Groups`]: boundary facets (all of
//!   them, or those of the named groups) seen from a [`Camera`], orthographic:
//!   `u = p·r`, `v = p·t`, depth `−p·d` with `d` the unit vector towards the
//!   viewer, `r` and `t` the screen's right and up. Each facet takes the colour
//!   of the cell it bounds, shaded by `0.6 + 0.4 |n·d|` (`n` its unit normal).
//! - 3D mesh, [`Section::Cut`]: the polygons where the plane `x_a = c` cuts the
//!   cells (the crossings of the cell edges, ordered by angle about their mean),
//!   in the plane's other two coordinates.

use std::collections::HashMap;

use verbss::error::{Error, Result};
use verbss::mesh::{Cells, Mesh};
use verbss::topology;

use crate::colour::{self, Rgb};

/// The part of the mesh a picture shows.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Section {
    /// 2D: every cell; 3D: the whole boundary surface.
    #[default]
    All,
    /// 3D: the facets of these boundary groups.
    Groups(Vec<String>),
    /// 3D: the cut by the plane `x[axis] = at` (axis 0, 1 or 2).
    Cut {
        /// The coordinate held fixed: 0 (x), 1 (y) or 2 (z).
        axis: usize,
        /// Its value.
        at: f64,
    },
}

/// The direction a 3D surface is seen from, in degrees: the viewer sits at
/// `d = (cos e cos a, cos e sin a, sin e)` (z up).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Azimuth `a` about the z axis from +x.
    pub azimuth: f64,
    /// Elevation `e` above the x–y plane.
    pub elevation: f64,
}

impl Default for Camera {
    /// From +x, −y, +z: `a = −60°`, `e = 25°`.
    fn default() -> Camera {
        Camera {
            azimuth: -60.0,
            elevation: 25.0,
        }
    }
}

/// One state of a mesh: coordinates and the per-cell quality and inversion
/// flags (as [`verbss::deform::Snapshot`] holds them).
#[derive(Debug, Clone, Copy)]
pub struct State<'a> {
    /// Node coordinates, `mesh.dim` per node.
    pub coords: &'a [f64],
    /// Quality of each cell.
    pub quality: &'a [f64],
    /// Whether each cell is inverted.
    pub inverted: &'a [bool],
}

/// Coloured polygons and edges in picture coordinates `(u, v, depth)`.
#[derive(Debug, Clone, Default)]
pub struct Scene {
    /// Polygon corners, all polygons one after the other.
    pub points: Vec<[f64; 3]>,
    /// Polygon `k` is `points[starts[k]..starts[k + 1]]`.
    pub starts: Vec<usize>,
    /// Fill colour of each polygon.
    pub colours: Vec<Rgb>,
    /// Edges to draw over the fill.
    pub edges: Vec<[[f64; 3]; 2]>,
    /// Names of the `u` and `v` axes when they are mesh coordinates (2D, cuts).
    pub axes: Option<[&'static str; 2]>,
    /// How far behind the nearest surface an edge may lie and still show
    /// (depth units).
    pub depth_tolerance: f64,
    /// Smallest quality of the mesh's cells.
    pub min_quality: f64,
    /// Number of inverted cells of the mesh.
    pub inverted: usize,
    /// Number of cells of the mesh.
    pub cells: usize,
}

impl Scene {
    /// The scene of `state` of `mesh` for `section` seen from `camera` (3D only).
    ///
    /// Errors when the section does not fit the mesh (a group or cut of a 2D
    /// mesh, an unknown group, an axis above 2, a cut that misses every cell).
    pub fn new(mesh: &Mesh, state: State, section: &Section, camera: Camera) -> Result<Scene> {
        let n = mesh.cell_count();
        if state.coords.len() != mesh.coords.len()
            || state.quality.len() != n
            || state.inverted.len() != n
        {
            return Err(Error::InvalidSetting(format!(
                "a picture needs {} coordinates and {} cell values, got {}, {} and {}",
                mesh.coords.len(),
                n,
                state.coords.len(),
                state.quality.len(),
                state.inverted.len()
            )));
        }
        let mut scene = Scene {
            starts: vec![0],
            min_quality: state.quality.iter().copied().fold(f64::INFINITY, f64::min),
            inverted: state.inverted.iter().filter(|&&b| b).count(),
            cells: n,
            ..Scene::default()
        };
        match (mesh.dim, section) {
            (2, Section::All) => scene.cells_2d(mesh, state),
            (2, _) => {
                return Err(Error::InvalidSetting(
                    "a 2D mesh is drawn whole: groups and cuts are for 3D meshes".into(),
                ))
            }
            (_, Section::Cut { axis, at }) => scene.cut(mesh, state, *axis, *at)?,
            (_, _) => scene.surface(mesh, state, section, camera)?,
        }
        Ok(scene)
    }

    /// Number of polygons.
    pub fn len(&self) -> usize {
        self.colours.len()
    }

    /// Whether there is no polygon.
    pub fn is_empty(&self) -> bool {
        self.colours.is_empty()
    }

    /// Corners of polygon `k`.
    pub fn polygon(&self, k: usize) -> &[[f64; 3]] {
        &self.points[self.starts[k]..self.starts[k + 1]]
    }

    /// `[u0, u1, v0, v1]`, the bounds of every polygon corner.
    pub fn bounds(&self) -> [f64; 4] {
        let mut b = [
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        for p in &self.points {
            b = [
                b[0].min(p[0]),
                b[1].max(p[0]),
                b[2].min(p[1]),
                b[3].max(p[1]),
            ];
        }
        b
    }

    fn push(&mut self, points: impl IntoIterator<Item = [f64; 3]>, colour: Rgb) {
        self.points.extend(points);
        self.starts.push(self.points.len());
        self.colours.push(colour);
    }

    fn cells_2d(&mut self, mesh: &Mesh, state: State) {
        let at = |i: usize| [state.coords[2 * i], state.coords[2 * i + 1], 0.0];
        for (c, (_, nodes)) in mesh.cells.iter().enumerate() {
            let colour = colour::cell(state.quality[c], state.inverted[c], 1.0);
            self.push(nodes.iter().map(|&i| at(i)), colour);
        }
        self.edges = topology::edges(&mesh.cells, mesh.node_count())
            .iter()
            .map(|&[a, b]| [at(a), at(b)])
            .collect();
        self.axes = Some(["x", "y"]);
    }

    fn surface(
        &mut self,
        mesh: &Mesh,
        state: State,
        section: &Section,
        camera: Camera,
    ) -> Result<()> {
        let owners = facet_owners(mesh);
        let facets = match section {
            Section::Groups(names) => {
                let mut facets = Cells::new();
                for name in names {
                    for (kind, nodes) in mesh.group(name)?.facets.iter() {
                        facets.push(kind, nodes);
                    }
                }
                facets
            }
            _ => topology::boundary_facets(&mesh.cells),
        };
        let (a, e) = (camera.azimuth.to_radians(), camera.elevation.to_radians());
        let d = [e.cos() * a.cos(), e.cos() * a.sin(), e.sin()];
        let r = [-a.sin(), a.cos(), 0.0];
        let t = [-e.sin() * a.cos(), -e.sin() * a.sin(), e.cos()];
        let p = |i: usize| -> [f64; 3] {
            let x = &state.coords[3 * i..3 * i + 3];
            [dot(x, &r), dot(x, &t), -dot(x, &d)]
        };
        let mut pairs = Vec::new();
        for (f, (_, nodes)) in facets.iter().enumerate() {
            let Some(&cell) = owners.get(&key(nodes)) else {
                return Err(Error::InvalidMesh(format!(
                    "boundary facet {f} (nodes {nodes:?}) is not a face of any cell"
                )));
            };
            let x = |k: usize| &state.coords[3 * nodes[k]..3 * nodes[k] + 3];
            let m = nodes.len();
            let normal = cross(&sub(x(2 % m), x(0)), &sub(x((m - 1) % m), x(1 % m)));
            let len = dot(&normal, &normal).sqrt();
            let shade = if len > 0.0 {
                0.6 + 0.4 * (dot(&normal, &d) / len).abs()
            } else {
                0.6
            };
            let colour = colour::cell(state.quality[cell], state.inverted[cell], shade);
            self.push(nodes.iter().map(|&i| p(i)), colour);
            for k in 0..m {
                let (i, j) = (nodes[k], nodes[(k + 1) % m]);
                pairs.push([i.min(j), i.max(j)]);
            }
        }
        pairs.sort_unstable();
        pairs.dedup();
        self.edges = pairs.iter().map(|&[i, j]| [p(i), p(j)]).collect();
        let b = self.bounds();
        self.depth_tolerance = 2e-3 * ((b[1] - b[0]).max(b[3] - b[2]));
        Ok(())
    }

    fn cut(&mut self, mesh: &Mesh, state: State, axis: usize, at: f64) -> Result<()> {
        const NAMES: [&str; 3] = ["x", "y", "z"];
        if axis > 2 {
            return Err(Error::InvalidSetting(format!(
                "cut axis {axis} (expected 0, 1 or 2)"
            )));
        }
        let (iu, iv) = match axis {
            0 => (1, 2),
            1 => (0, 2),
            _ => (0, 1),
        };
        let x = |i: usize| &state.coords[3 * i..3 * i + 3];
        let mut polygon: Vec<[f64; 3]> = Vec::with_capacity(12);
        for (c, (_, nodes)) in mesh.cells.iter().enumerate() {
            let s = |k: usize| x(nodes[k])[axis] - at;
            polygon.clear();
            mesh.cells.local(c).edges(|a, b| {
                let (sa, sb) = (s(a), s(b));
                if (sa < 0.0) != (sb < 0.0) {
                    let t = sa / (sa - sb);
                    let (pa, pb) = (x(nodes[a]), x(nodes[b]));
                    let lerp = |k: usize| pa[k] + t * (pb[k] - pa[k]);
                    polygon.push([lerp(iu), lerp(iv), 0.0]);
                }
            });
            if polygon.len() < 3 {
                continue;
            }
            let m = polygon.len() as f64;
            let cu = polygon.iter().map(|p| p[0]).sum::<f64>() / m;
            let cv = polygon.iter().map(|p| p[1]).sum::<f64>() / m;
            polygon.sort_by(|p, q| {
                (p[1] - cv)
                    .atan2(p[0] - cu)
                    .total_cmp(&(q[1] - cv).atan2(q[0] - cu))
            });
            let colour = colour::cell(state.quality[c], state.inverted[c], 1.0);
            let k = polygon.len();
            for i in 0..k {
                self.edges.push([polygon[i], polygon[(i + 1) % k]]);
            }
            self.push(polygon.iter().copied(), colour);
        }
        if self.is_empty() {
            return Err(Error::InvalidSetting(format!(
                "the plane {} = {at} cuts no cell",
                NAMES[axis]
            )));
        }
        self.axes = Some([NAMES[iu], NAMES[iv]]);
        Ok(())
    }
}

/// Sorted node key of a facet.
fn key(nodes: &[usize]) -> Vec<usize> {
    let mut k = nodes.to_vec();
    k.sort_unstable();
    k
}

/// Every facet of every cell and the first cell that has it.
fn facet_owners(mesh: &Mesh) -> HashMap<Vec<usize>, usize> {
    let mut owners: HashMap<Vec<usize>, usize> = HashMap::new();
    let mut local = Vec::with_capacity(4);
    for (c, (_, nodes)) in mesh.cells.iter().enumerate() {
        mesh.cells.local(c).facets(|f| {
            local.clear();
            local.extend(f.iter().map(|&k| nodes[k]));
            owners.entry(key(&local)).or_insert(c);
        });
    }
    owners
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn sub(a: &[f64], b: &[f64]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
