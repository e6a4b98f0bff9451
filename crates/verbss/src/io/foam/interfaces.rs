//! The coupled patches of a `boundary` file as the mesh's interfaces
//! ([`Interface`]): `cyclicAMI` and `cyclicACMI` pairs (an ACMI side with
//! its `nonOverlapPatch`) and `mapped*` patches (`samplePatch`, when it
//! names a patch of this mesh) slide; `cyclic` (and `cyclicSlip`) pairs are
//! periodic, their transform from `transform translational`
//! (`separationVector`) or `rotational` (`rotationAxis`, `rotationCentre`,
//! `rotationAngle` in degrees), else the translation between the two
//! patches' centroids.

use super::lex::Lexer;
use super::read::{Patch, PolyMesh};
use crate::error::{Error, Result};
use crate::geometry::norm;
use crate::io::shown;
use crate::mesh::{Coupling, Interface, Transform};

/// A patch's coupling entries.
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct Coupled {
    /// `neighbourPatch` and its line.
    pub neighbour: Option<(String, usize)>,
    /// A mapped patch's `samplePatch` (which may name a patch of another
    /// region: then it is no interface of this mesh).
    pub sample: Option<String>,
    /// `nonOverlapPatch` (ACMI) and its line.
    pub non_overlap: Option<(String, usize)>,
    /// `transform`.
    pub transform: Option<String>,
    /// `separationVector`.
    pub separation: Option<[f64; 3]>,
    /// `rotationAxis`.
    pub axis: Option<[f64; 3]>,
    /// `rotationCentre`.
    pub centre: Option<[f64; 3]>,
    /// `rotationAngle`, degrees.
    pub angle: Option<f64>,
}

impl Coupled {
    /// Reads the value of `key` when it is a coupling entry (up to, not
    /// including, its `;`); false for any other key.
    pub(super) fn entry(&mut self, lx: &mut Lexer, key: &str, line: usize) -> Result<bool> {
        let word = |lx: &mut Lexer, what: &str| -> Result<String> {
            Ok(lx.expect_any(what)?.text.to_string())
        };
        match key {
            "neighbourPatch" => self.neighbour = Some((word(lx, "a patch name")?, line)),
            "samplePatch" => self.sample = Some(word(lx, "a patch name")?),
            "nonOverlapPatch" => self.non_overlap = Some((word(lx, "a patch name")?, line)),
            "transform" => self.transform = Some(word(lx, "a transform type")?),
            "separationVector" => self.separation = Some(vector(lx, key)?),
            "rotationAxis" => self.axis = Some(vector(lx, key)?),
            "rotationCentre" => self.centre = Some(vector(lx, key)?),
            "rotationAngle" => self.angle = Some(lx.scalar("rotationAngle (degrees)")?),
            _ => return Ok(false),
        }
        Ok(true)
    }
}

/// `(x y z)`.
fn vector(lx: &mut Lexer, key: &str) -> Result<[f64; 3]> {
    lx.expect("(", &format!("before the 3 components of {key}"))?;
    let v = [lx.scalar("x")?, lx.scalar("y")?, lx.scalar("z")?];
    lx.expect(")", &format!("after the 3 components of {key}"))?;
    Ok(v)
}

/// The interfaces of the patches of `poly`, each pair once, named from
/// the patch listed first. A patch naming a patch that is not there is an
/// error at the line of that entry.
pub(super) fn interfaces(poly: &PolyMesh) -> Result<Vec<Interface>> {
    let path = poly.file("boundary");
    let find = |name: &str, line: usize, entry: &str| -> Result<usize> {
        poly.patches
            .iter()
            .position(|p| p.name == name)
            .ok_or_else(|| Error::Parse {
                path: path.clone(),
                line,
                message: format!("{entry} '{}' is not a patch of this boundary", shown(name)),
            })
    };
    let mut found = Vec::new();
    let mut paired = vec![false; poly.patches.len()];
    for (a, p) in poly.patches.iter().enumerate() {
        let b = match (&p.coupled.neighbour, &p.coupled.sample) {
            (Some((name, line)), _) => find(name, *line, "the neighbour patch")?,
            (None, Some(name)) => match poly.patches.iter().position(|q| &q.name == name) {
                Some(b) => b,
                None => continue,
            },
            (None, None) => continue,
        };
        if paired[a] || b == a {
            continue;
        }
        paired[a] = true;
        paired[b] = true;
        let side = |k: usize| -> Result<Vec<String>> {
            let q = &poly.patches[k];
            let mut names = vec![q.name.clone()];
            if let Some((other, line)) = &q.coupled.non_overlap {
                find(other, *line, "the non-overlapping patch")?;
                names.push(other.clone());
            }
            Ok(names)
        };
        let coupling = if matches!(p.kind.as_str(), "cyclic" | "cyclicSlip") {
            Coupling::Periodic(transform(poly, p, &poly.patches[b]))
        } else {
            Coupling::Sliding
        };
        found.push(Interface {
            sides: [side(a)?, side(b)?],
            coupling,
        });
    }
    Ok(found)
}

/// The transform taking patch `a` onto patch `b`: the file's, turned round
/// when it takes `b` onto `a`, or the translation between their centroids.
fn transform(poly: &PolyMesh, a: &Patch, b: &Patch) -> Transform {
    let (ca, cb) = (centroid(poly, a), centroid(poly, b));
    let given = [&a.coupled, &b.coupled].into_iter().find_map(|c| {
        match (c.transform.as_deref(), c.separation, c.axis, c.centre) {
            (Some("translational"), Some(s), ..) => Some(Transform::Translation(s)),
            (Some("rotational"), _, Some(axis), centre) if norm(&axis) > 0.0 => {
                Some(Transform::Rotation {
                    axis,
                    centre: centre.unwrap_or([0.0; 3]),
                    angle: c.angle.unwrap_or(0.0).to_radians(),
                })
            }
            _ => None,
        }
    });
    let Some(t) = given else {
        return Transform::Translation(std::array::from_fn(|d| cb[d] - ca[d]));
    };
    let miss = |t: &Transform, from: &[f64; 3], to: &[f64; 3]| {
        let p = t.apply(from);
        norm::<3>(&std::array::from_fn(|d| p[d] - to[d]))
    };
    let reverse = match &t {
        Transform::Translation(s) => Transform::Translation(s.map(|x| -x)),
        Transform::Rotation {
            axis,
            centre,
            angle,
        } => Transform::Rotation {
            axis: *axis,
            centre: *centre,
            angle: -angle,
        },
        Transform::Affine(_) => return t,
    };
    if miss(&reverse, &ca, &cb) < miss(&t, &ca, &cb) {
        reverse
    } else {
        t
    }
}

/// The mean of the points of patch `p`'s faces, each point once.
fn centroid(poly: &PolyMesh, p: &Patch) -> [f64; 3] {
    let mut points: Vec<usize> = (p.start_face..p.start_face + p.n_faces)
        .flat_map(|f| poly.face(f).iter().copied())
        .collect();
    points.sort_unstable();
    points.dedup();
    let n = points.len().max(1) as f64;
    std::array::from_fn(|d| points.iter().map(|&i| poly.points[3 * i + d]).sum::<f64>() / n)
}
