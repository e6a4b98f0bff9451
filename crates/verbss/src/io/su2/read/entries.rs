//! The data lines of the reader's sections: points, elements, marker elements.

use super::{MaxRef, Parser};
use crate::error::Result;
use crate::io::shown;
use crate::io::su2::{kind_name, NAMES};
use crate::mesh::{CellKind, Cells};

impl Parser<'_> {
    /// `x y [z] [index …]`.
    pub(super) fn point(&mut self, text: &str) -> Result<()> {
        let dim = self.dim();
        let mut tokens = text.split_whitespace();
        for k in 0..dim {
            let Some(t) = tokens.next() else {
                return Err(self.err(
                    self.line,
                    format!(
                        "expected NDIME= {dim} coordinates, found {k} in '{}'",
                        shown(text)
                    ),
                ));
            };
            let x: f64 = t.parse().map_err(|_| {
                self.err(
                    self.line,
                    format!("expected a coordinate, found '{}'", shown(t)),
                )
            })?;
            if !x.is_finite() {
                return Err(self.err(
                    self.line,
                    format!(
                        "non-finite coordinate '{}' (expected a finite number)",
                        shown(t)
                    ),
                ));
            }
            self.state.coords.push(x);
        }
        self.trailing_indices(tokens, &format!("the {dim} coordinates"))
    }

    /// Anything after a point's coordinates or an element's nodes must be an index.
    fn trailing_indices<'t>(
        &self,
        tokens: impl Iterator<Item = &'t str>,
        after: &str,
    ) -> Result<()> {
        for t in tokens {
            if t.parse::<u64>().is_err() {
                return Err(self.err(
                    self.line,
                    format!("expected an index after {after}, found '{}'", shown(t)),
                ));
            }
        }
        Ok(())
    }

    /// A volume element line `type n1 … nk [index …]`.
    pub(super) fn element(&mut self, text: &str) -> Result<()> {
        let dim = self.dim();
        let kind = self.element_kind(text, |k| k.dim() == dim)?;
        let mut cells = std::mem::take(&mut self.state.cells);
        let done = self.element_nodes(text, kind, &mut cells);
        self.state.cells = cells;
        done
    }

    /// A marker element line `type n1 … nk [index …]`.
    pub(super) fn marker_element(&mut self, text: &str) -> Result<()> {
        let dim = self.dim();
        let kind = self.element_kind(text, |k| k.dim() < dim)?;
        let mut m = self
            .state
            .markers
            .pop()
            .expect("a marker section has a marker");
        let done = self.element_nodes(text, kind, &mut m.facets);
        self.state.markers.push(m);
        done
    }

    /// The kind named by the line's type id, which must pass `allowed`.
    fn element_kind(&self, text: &str, allowed: impl Fn(CellKind) -> bool) -> Result<CellKind> {
        let first = text.split_whitespace().next().unwrap_or("");
        let expected = || {
            let names: Vec<String> = NAMES
                .iter()
                .filter(|t| allowed(t.0))
                .map(|t| format!("{} {}", t.0.vtk_id(), t.1))
                .collect();
            let (last, rest) = names.split_last().expect("every place allows a kind");
            if rest.is_empty() {
                last.clone()
            } else {
                format!("{} or {last}", rest.join(", "))
            }
        };
        let Ok(id) = first.parse::<u32>() else {
            return Err(self.err(
                self.line,
                format!(
                    "expected an SU2 element type ({}), found '{}'",
                    expected(),
                    shown(first)
                ),
            ));
        };
        match CellKind::from_vtk_id(id.into()).filter(|k| !k.is_general()) {
            Some(kind) if allowed(kind) => Ok(kind),
            Some(kind) => Err(self.err(
                self.line,
                format!(
                    "SU2 element type {id} ({}) does not belong in the {} of a {}D mesh \
                     (expected {})",
                    kind_name(kind),
                    self.open_what(),
                    self.dim(),
                    expected()
                ),
            )),
            None => Err(self.err(
                self.line,
                format!(
                    "unsupported SU2 element type {id} (expected {})",
                    expected()
                ),
            )),
        }
    }

    /// What the section being read holds (the section may have just been closed).
    fn open_what(&self) -> &'static str {
        self.state
            .open
            .as_ref()
            .or(self.state.closed.as_ref())
            .map_or("elements", |s| s.block.what())
    }

    /// Reads the node indices after the type id into `cells`.
    fn element_nodes(&mut self, text: &str, kind: CellKind, cells: &mut Cells) -> Result<()> {
        let n = kind.node_count();
        let mut tokens = text.split_whitespace().skip(1);
        let start = cells.nodes.len();
        for k in 0..n {
            let Some(t) = tokens.next() else {
                return Err(self.err(
                    self.line,
                    format!(
                        "{} (type {}) needs {n} node indices, found {k}",
                        kind_name(kind),
                        kind.vtk_id()
                    ),
                ));
            };
            let Ok(i) = t.parse::<usize>() else {
                return Err(self.err(
                    self.line,
                    format!("expected a node index, found '{}'", shown(t)),
                ));
            };
            cells.nodes.push(i);
        }
        let mut stored = [0usize; 8];
        stored[..n].copy_from_slice(&cells.nodes[start..]);
        for (k, slot) in cells.nodes[start..].iter_mut().enumerate() {
            *slot = stored[kind.vtk_local(k)];
        }
        cells.kinds.push(kind);
        cells.offsets.push(cells.nodes.len());
        let top = cells.nodes[start..].iter().copied().max().unwrap_or(0);
        let line = self.line;
        let max = self
            .state
            .max_refs
            .last_mut()
            .expect("an element section has a max");
        if max.line == 0 || top > max.index {
            *max = MaxRef { index: top, line };
        }
        self.trailing_indices(tokens, &format!("the {n} node indices"))
    }
}
