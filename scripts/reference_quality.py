#!/usr/bin/env python3
"""Reference element-quality values for the SU2 meshes, computed independently.

Each mesh in assets/meshes/su2/ is read with meshio and measured with VTK's
vtkMeshQuality (Sandia's Verdict library). The result goes to
assets/expected/<mesh>.json, which crates/verbss/tests/real_meshes.rs compares
with what verbss reads and computes.

Measures (the contract of crates/verbss/src/quality.rs):
  triangle, tetra            quality = 1 / RadiusRatio  (= C r/R, C = 2 or 3)
  quad, hexahedron, wedge,
  pyramid                    quality = ScaledJacobian clamped to [0, 1]

Verdict's scaled Jacobians of hexahedra, wedges and pyramids are signed by the
node order; every 3D cell of these files is positively oriented in Verdict's
sense (the script checks it: no ScaledJacobian is negative), so the clamped
value is the quality relative to the cell's own orientation. Verdict's quad
scaled Jacobian is relative to the quad's centre normal, hence already
independent of the orientation.

Histogram bins are the VerBSS paper's: [0, 0.02), [0.02, 0.1), [0.1, 0.4),
[0.4, 0.7), [0.7, 1.0] (numpy.histogram's convention: lo <= q < hi, the last
bin closed).

"elements" are the volume cells (cells of the mesh's dimension) in file order;
an element's index is its 0-based position among them. meshio groups cells by
kind, so file order and meshio's order agree only when each kind forms one run
in the file; the script checks that against the file's NELEM section.

meshio replaces SU2 marker names by their 1-based position; the names are taken
from the MARKER_TAG lines of the file, in the same order.

Usage: pip install meshio vtk numpy; python3 scripts/reference_quality.py
"""

import contextlib
import io
import json
import re
import sys
from pathlib import Path

import meshio
import numpy as np
import vtk
from vtkmodules.util.numpy_support import (
    numpy_to_vtk,
    numpy_to_vtkIdTypeArray,
    vtk_to_numpy,
)

ROOT = Path(__file__).resolve().parent.parent
MESHES = ROOT / "assets" / "meshes" / "su2"
EXPECTED = ROOT / "assets" / "expected"

BIN_EDGES = [0.0, 0.02, 0.1, 0.4, 0.7, 1.0]
SAMPLE_WORST = 10
SAMPLE_SPREAD = 40

# meshio cell type -> (VTK cell type, topological dimension, VTK measure)
KINDS = {
    "triangle": (vtk.VTK_TRIANGLE, 2, "RadiusRatio"),
    "quad": (vtk.VTK_QUAD, 2, "ScaledJacobian"),
    "tetra": (vtk.VTK_TETRA, 3, "RadiusRatio"),
    "hexahedron": (vtk.VTK_HEXAHEDRON, 3, "ScaledJacobian"),
    "wedge": (vtk.VTK_WEDGE, 3, "ScaledJacobian"),
    "pyramid": (vtk.VTK_PYRAMID, 3, "ScaledJacobian"),
}

# SU2 element type numbers (VTK's) of the volume kinds.
SU2_TYPES = {5: "triangle", 9: "quad", 10: "tetra", 12: "hexahedron", 13: "wedge", 14: "pyramid"}


def read_quietly(path):
    """meshio prints a warning for every line of the FFD sections it skips."""
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        return meshio.read(path)


def file_kinds_in_order(path):
    """The kind of each NELEM entry, read straight from the file."""
    kinds = []
    with open(path) as f:
        for line in f:
            m = re.match(r"\s*NELEM\s*=\s*(\d+)", line)
            if m:
                for _ in range(int(m.group(1))):
                    kinds.append(SU2_TYPES[int(next(f).split()[0])])
                return kinds
    raise ValueError(f"{path}: no NELEM section")


def marker_names(path):
    names = []
    with open(path) as f:
        for line in f:
            m = re.match(r"\s*MARKER_TAG\s*=\s*(\S+)", line)
            if m:
                names.append(m.group(1))
    return names


def vtk_quality(points, blocks):
    """Per-cell (raw VTK measure, measure name) over the blocks, in block order."""
    pts = np.zeros((len(points), 3))
    pts[:, : points.shape[1]] = points
    vpoints = vtk.vtkPoints()
    vpoints.SetData(numpy_to_vtk(pts, deep=True))

    conn = np.concatenate([b.data.ravel() for b in blocks]).astype(np.int64)
    sizes = np.concatenate([np.full(len(b.data), b.data.shape[1]) for b in blocks])
    offsets = np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)
    types = np.concatenate([np.full(len(b.data), KINDS[b.type][0]) for b in blocks])
    cells = vtk.vtkCellArray()
    cells.SetData(numpy_to_vtkIdTypeArray(offsets, deep=True), numpy_to_vtkIdTypeArray(conn, deep=True))

    grid = vtk.vtkUnstructuredGrid()
    grid.SetPoints(vpoints)
    grid.SetCells(numpy_to_vtk(types.astype(np.uint8), deep=True, array_type=vtk.VTK_UNSIGNED_CHAR), cells)

    mq = vtk.vtkMeshQuality()
    mq.SetInputData(grid)
    mq.SetTriangleQualityMeasureToRadiusRatio()
    mq.SetTetQualityMeasureToRadiusRatio()
    mq.SetQuadQualityMeasureToScaledJacobian()
    mq.SetHexQualityMeasureToScaledJacobian()
    mq.SetWedgeQualityMeasureToScaledJacobian()
    mq.SetPyramidQualityMeasureToScaledJacobian()
    mq.Update()
    raw = vtk_to_numpy(mq.GetOutput().GetCellData().GetArray("Quality")).astype(float)
    measures = np.concatenate([np.full(len(b.data), KINDS[b.type][2], dtype=object) for b in blocks])
    return raw, measures


def reference(path):
    mesh = read_quietly(path)
    dim = mesh.points.shape[1]
    blocks = [b for b in mesh.cells if b.type in KINDS and KINDS[b.type][1] == dim]
    kinds = np.concatenate([np.full(len(b.data), b.type, dtype=object) for b in blocks])
    if list(kinds) != file_kinds_in_order(path):
        sys.exit(f"{path}: meshio's cell order differs from the file's")

    raw, measures = vtk_quality(mesh.points, blocks)
    radius = measures == "RadiusRatio"
    if np.any(raw[~radius] < 0):
        sys.exit(f"{path}: a negatively oriented cell; the clamped measure would not be orientation-relative")
    quality = np.where(radius, 1.0 / raw, np.clip(raw, 0.0, 1.0))

    tags = mesh.cell_data["su2:tag"]
    names = marker_names(path)
    groups = {}
    for b, t in zip(mesh.cells, tags):
        if b.type in KINDS and KINDS[b.type][1] == dim:
            continue
        for tag in np.unique(t):
            nodes = np.unique(b.data[t == tag])
            name = names[int(tag) - 1]
            groups[name] = len(np.union1d(nodes, groups.get(name, [])))

    counts, _ = np.histogram(quality, bins=BIN_EDGES)
    worst = np.argsort(quality, kind="stable")[:SAMPLE_WORST]
    spread = np.linspace(0, len(quality) - 1, SAMPLE_SPREAD).round().astype(int)
    sample = sorted(set(worst.tolist()) | set(spread.tolist()))

    return {
        "source": "meshio " + meshio.__version__ + ", VTK " + vtk.vtkVersion.GetVTKVersion() + " vtkMeshQuality",
        "dimension": dim,
        "nodes": len(mesh.points),
        "elements": len(quality),
        "kinds": {b.type: len(b.data) for b in blocks},
        "groups": groups,
        "quality": {
            "min": float(quality.min()),
            "mean": float(quality.mean()),
            "bins": [
                {"lo": lo, "hi": hi, "count": int(c)}
                for lo, hi, c in zip(BIN_EDGES[:-1], BIN_EDGES[1:], counts)
            ],
        },
        "sample": [
            {
                "element": i,
                "kind": kinds[i],
                "measure": measures[i],
                "vtk": float(raw[i]),
                "quality": float(quality[i]),
            }
            for i in sample
        ],
    }


def main():
    EXPECTED.mkdir(parents=True, exist_ok=True)
    for path in sorted(MESHES.glob("*.su2")):
        ref = reference(path)
        out = EXPECTED / (path.stem + ".json")
        out.write_text(json.dumps(ref, indent=1) + "\n")
        q = ref["quality"]
        print(f"{out.relative_to(ROOT)}: {ref['elements']} elements, min {q['min']:.6f}, mean {q['mean']:.6f}")


if __name__ == "__main__":
    main()
