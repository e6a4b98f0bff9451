"""The aft 40% of a NACA4412 boundary-layer mesh drooped through `--positions`
(docs/robustness.md, "Squeezed gaps"): one Markdown table on standard output,
per method the steps reached, the minimum quality, the largest per-step
amplification (report.json), the amplification of the whole motion (the
largest move of a node off the wall over the largest of a wall node), how
far the wake nodes 6.5-7 chords behind the trailing edge moved and the
seconds per step, and the rows of cases/gaps/gaps_common.py (--json).

    cargo build --release -p verbss-cli
    python3 cases/gaps/droop.py [--json OUT] [--verbss PATH] [--work DIR] [--size H] [--steps N]

The mesh (Gmsh): chord 1 from (0, 0), blunt trailing edge 0.3% chord thick, a
quadrilateral boundary layer (first cell 1e-4 chord, growth 1.2, 0.04 chord
thick, fans at the trailing-edge corners), triangles of size H at the wall, a
wake of size 4H (at x = 1) to 12H (at x = 11) along y = 0, growing to 2
at distance 2 from it and at the circular
far field of radius 20 about the quarter chord. Groups `airfoil`,
`farfield`, `fluid`.

The droop: behind the hinge x = 0.6 on the camber line the section is bent
about a centre below the hinge, with the curvature that moves its farthest
node (the lower trailing-edge corner) by 0.15 chord: a point at chord
station h + s and height y above the hinge goes to
`centre + (R + y) (sin(s/R), cos(s/R))`, `centre = (h, y_h - R)`; a
cylindrical bending, so every cell of the layer keeps its orientation. The
rest of the wall stays.
"""

import argparse
import contextlib
import io
import json
import math
import sys
import tempfile
from pathlib import Path

import gmsh
import meshio

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "meshes"))
import meshing  # noqa: E402
import rans_blunt  # noqa: E402

import gaps_common as common  # noqa: E402

HINGE = 0.6
DROOP = 0.15
FAR_WAKE = (7.5, 8.0)  # x of the nodes 6.5-7 chords behind the trailing edge


def build_mesh(h, out):
    gmsh.initialize(["-noenv"])
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("droop")
    occ = gmsh.model.occ
    upper, lower = rans_blunt.blunt_section("4412", 100, 0.003)
    loop, airfoil, corners = rans_blunt.add_loop(occ, upper, lower)
    far = occ.addCircle(0.25, 0, 0, 20)
    surface = occ.addPlaneSurface([occ.addCurveLoop([far]), loop])
    wake_start = occ.addPoint(1, 0, 0)
    wake_end = occ.addPoint(11, 0, 0)
    wake = occ.addLine(wake_start, wake_end)
    occ.synchronize()
    gmsh.model.addPhysicalGroup(1, airfoil, name="airfoil")
    gmsh.model.addPhysicalGroup(1, [far], name="farfield")
    fluid = gmsh.model.addPhysicalGroup(2, [surface], name="fluid")
    f = gmsh.model.mesh.field
    wall = meshing.graded("CurvesList", airfoil, h, 2.0, 0.02, 12, sampling=300)
    te = meshing.graded("PointsList", corners, h / 4, 2.0, 0.005, 0.5)
    # The wake: size 4h at the trailing edge to 12h at x = 11 within 0.1 of
    # y = 0, growing to 2 at distance 2.
    along = f.add("MathEval")
    f.setString(along, "F", f"{4 * h} + {0.8 * h} * (x - 1)")
    near = f.add("Distance")
    f.setNumbers(near, "CurvesList", [wake])
    f.setNumber(near, "Sampling", 400)
    band = f.add("Threshold")
    f.setNumber(band, "InField", near)
    f.setNumber(band, "SizeMin", 0.0)
    f.setNumber(band, "SizeMax", 2.0)
    f.setNumber(band, "DistMin", 0.1)
    f.setNumber(band, "DistMax", 2.0)
    wake_size = f.add("Max")
    f.setNumbers(wake_size, "FieldsList", [along, band])
    smallest = f.add("Min")
    f.setNumbers(smallest, "FieldsList", [wall, te, wake_size])
    f.setAsBackgroundMesh(smallest)
    # The wake line only shapes the size field: it is not embedded.
    rans_blunt.boundary_layer(airfoil, corners, 1e-4, 1.2, 0.04, 8)
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    meshing.finish(str(out), 2, fluid, h)


def read(path):
    """The mesh at `path` (meshio prints a blank line while reading Gmsh files)."""
    with contextlib.redirect_stdout(io.StringIO()):
        return meshio.read(path)


def camber_y(x):
    """NACA4412's camber line at chord station x (chord 1)."""
    m, p = 0.04, 0.4
    return m / p**2 * (2 * p * x - x * x) if x < p else m / (1 - p) ** 2 * (1 - 2 * p + 2 * p * x - x * x)


def bent(point, radius):
    """`point` bent about the hinge with bending radius `radius`."""
    x, y = point
    if x <= HINGE:
        return x, y
    yh = camber_y(HINGE)
    s, above = x - HINGE, y - yh
    a = s / radius
    return HINGE + (radius + above) * math.sin(a), yh - radius + (radius + above) * math.cos(a)


def positions(mesh, path):
    """Writes the drooped airfoil's positions (`id x y`, 0-based in the mesh
    file's order) to `path`; returns the bending radius."""
    nodes = airfoil_nodes(mesh)
    points = [tuple(mesh.points[i, :2]) for i in nodes]

    def largest(radius):
        return max(math.dist(p, bent(p, radius)) for p in points)

    lo, hi = 0.05, 100.0  # the displacement falls as the radius grows
    for _ in range(100):
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if largest(mid) > DROOP else (lo, mid)
    radius = hi
    with open(path, "w") as out:
        for i, p in zip(nodes, points):
            x, y = bent(p, radius)
            out.write(f"{i} {x:.17g} {y:.17g}\n")
    return radius


def airfoil_nodes(mesh):
    """The 0-based indices of the nodes of group `airfoil`."""
    nodes = set()
    for block, tags in zip(mesh.cells, mesh.cell_sets["airfoil"]):
        if len(tags):
            nodes.update(int(i) for i in block.data[tags].ravel())
    return sorted(nodes)


def moves(before, after_path, wall):
    """The whole motion's amplification (largest move of a node off the wall
    over the largest of a wall node) and the largest move of a node with x
    in FAR_WAKE."""
    after = read(after_path).points[:, :2]
    d = ((after - before[:, :2]) ** 2).sum(axis=1) ** 0.5
    on_wall = set(wall)
    off = max(d[i] for i in range(len(d)) if i not in on_wall)
    wall_move = max(d[i] for i in wall)
    x = before[:, 0]
    far = d[(x >= FAR_WAKE[0]) & (x <= FAR_WAKE[1])].max()
    return off / wall_move, far


def main():
    parser = common.options(__doc__)
    parser.add_argument("--size", type=float, default=0.01)
    parser.add_argument("--steps", type=int, default=10)
    args = parser.parse_args()
    verbss = str(Path(args.verbss).resolve())
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(args.work or tmp).resolve()
        root.mkdir(parents=True, exist_ok=True)
        mesh_path = root / "naca4412-droop.msh"
        build_mesh(args.size, mesh_path)
        mesh = read(mesh_path)
        wall = airfoil_nodes(mesh)
        positions_path = root / "droop.dat"
        radius = positions(mesh, positions_path)
        print(f"{len(mesh.points)} nodes, bending radius {radius:.4f}, "
              f"largest wall displacement {DROOP}, {args.steps} steps\n")
        motion = ["--moving", "airfoil", "--positions", str(positions_path)]
        rows = common.verbss_rows(verbss, "droop", f"Gmsh NACA4412, H = {args.size:g}",
                                  len(mesh.points), lambda slug: (mesh_path, root / f"{slug}.msh"),
                                  args.steps, motion, root)
        common.print_rows(rows)
        print("\n| run | steps | min quality | largest step amplification "
              "| whole-motion amplification | far-wake move (x 7.5-8) | s/step |")
        print("|---|---|---|---|---|---|---|")
        for r in rows:
            moved = root / f"{r['run'].replace(' ', '').replace('-', '')}.msh"
            complete = r["steps_done"] == r["steps"] and moved.exists()
            whole, far = moves(mesh.points, moved, wall) if complete else (None, None)
            print(f"| {r['run']} | {r['steps_done']}/{r['steps']} | {common.fmt(r['min_quality'], '.4f')} "
                  f"| {common.fmt(r['amplification'], '.3f')} | {common.fmt(whole, '.3f')} "
                  f"| {common.fmt(far, '.4f')} | {common.fmt(r['s_per_step'], '.3f')} |")
        common.write_json(args.json, rows)


if __name__ == "__main__":
    main()
