"""A plate closing onto a wall (2D; docs/robustness.md, "Squeezed gaps"), by
verbss and by OpenFOAM's displacementLaplacian.

The plate [0, 1] x [0.30, 0.34] (group `plate`) is hinged at (0, 0.32), above
the wall y = 0 (group `wall`) of the box [-1, 3] x [0, 2] (the rest of its
sides `farfield`, fixed), and turns 15 degrees down in 20 steps: its trailing
corner's gap to the wall closes from 0.30 to 0.042. Gmsh triangles of size
0.01 at the plate and on the wall under it, growing to 0.15 at distance 0.8.

    python3 cases/gaps/flap.py [--json OUT] [--verbss PATH] [--work DIR]
    verbss deform flap.msh -o out.vtu --moving plate --rotate -15 --center 0,0.32 --steps 20

OpenFOAM: the mesh extruded one cell (bench/openfoam_peer.py), the plate
solidBodyMotionDisplacement (rotatingMotion), `wall` and `farfield` fixed.
"""

import tempfile
from pathlib import Path

import gmsh

import gaps_common as common

STEPS, ANGLE, HINGE = 20, -15.0, (0.0, 0.32)
MOTION = ["--moving", "plate", "--rotate", f"{ANGLE:g}", "--center", f"{HINGE[0]},{HINGE[1]}"]


def build_mesh(path):
    gmsh.initialize(["-noenv"])
    gmsh.option.setNumber("General.Terminal", 0)
    occ = gmsh.model.occ
    box = occ.addRectangle(-1, 0, 0, 4, 2)
    plate = occ.addRectangle(0, 0.30, 0, 1, 0.04)
    out, _ = occ.cut([(2, box)], [(2, plate)])
    occ.synchronize()
    groups = {"plate": [], "wall": [], "farfield": []}
    under = []
    for _, c in gmsh.model.getBoundary(out, oriented=False):
        x, y, _ = occ.getCenterOfMass(1, c)
        name = "plate" if 0.2 < y < 0.4 and -0.1 < x < 1.1 else "wall" if y < 1e-9 else "farfield"
        groups[name].append(c)
    for name, curves in groups.items():
        gmsh.model.addPhysicalGroup(1, curves, name=name)
    gmsh.model.addPhysicalGroup(2, [out[0][1]], name="fluid")
    f = gmsh.model.mesh.field
    under = occ.addLine(occ.addPoint(-0.1, 0, 0), occ.addPoint(1.1, 0, 0))
    occ.synchronize()
    d = f.add("Distance")
    f.setNumbers(d, "CurvesList", groups["plate"])
    f.setNumber(d, "Sampling", 200)
    d2 = f.add("Distance")
    f.setNumbers(d2, "CurvesList", [under])
    f.setNumber(d2, "Sampling", 200)
    m = f.add("Min")
    f.setNumbers(m, "FieldsList", [d, d2])
    t = f.add("Threshold")
    f.setNumber(t, "InField", m)
    f.setNumber(t, "SizeMin", 0.01)
    f.setNumber(t, "SizeMax", 0.15)
    f.setNumber(t, "DistMin", 0.02)
    f.setNumber(t, "DistMax", 0.8)
    f.setAsBackgroundMesh(t)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.model.mesh.generate(2)
    gmsh.option.setNumber("Mesh.MshFileVersion", 2.2)
    gmsh.write(str(path))
    nodes = len(gmsh.model.mesh.getNodes()[0])
    gmsh.finalize()
    return nodes


def main():
    args = common.options(__doc__).parse_args()
    verbss = str(Path(args.verbss).resolve())
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(args.work or tmp).resolve()
        work.mkdir(parents=True, exist_ok=True)
        msh = work / "flap.msh"
        nodes = build_mesh(msh)
        name = "Gmsh triangles 0.01-0.15"
        rows = common.verbss_rows(verbss, "flap", name, nodes,
                                  lambda slug: (msh, work / f"flap-{slug}.vtu"), STEPS, MOTION, work)
        body = dict(mesh=str(msh), body="plate", steps=STEPS, rotate=((*HINGE, 0.0), ANGLE))
        case = work / "foam"
        common.peer.build_case(body, "laplacian", case, 1e-20)
        rows += common.openfoam_rows(verbss, "flap", name, nodes, case, body, [], ["wall", "farfield"], work)
        common.print_rows(rows)
        common.write_json(args.json, rows)


if __name__ == "__main__":
    main()
