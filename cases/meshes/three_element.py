"""Mesh of the paper's section 4.3 case: a three-element airfoil (slat,
main element, flap) in a circular far field of radius 10 about (0.5, 0).

The paper gives neither the sections nor the slot geometry. We take:
- main element (group `main`): NACA 2412, chord 1, leading edge at the origin;
- slat (group `slat`): NACA 4412, chord 0.153, leading edge at
  (-0.11, -0.02), trailing edge up by 31.6 degrees, so that it sits above
  the main element's nose with a slot of 0.028 (narrowest gap);
- flap (group `flap`): NACA 4412, chord 0.3, leading edge at (0.96, -0.05),
  deflected 30 degrees (trailing edge down), a slot of 0.043 (narrowest) under the
  main element's trailing edge;
- far field (group `farfield`).
Triangles are graded from size h at the elements (h/4 within 0.01 of each
leading and trailing edge) to 1.5 at the far field; h is chosen for a node
count close to the paper's 11,372.

Usage: python3 three_element.py OUT.msh | --size H OUT.msh
"""

import sys

import gmsh

import naca

SIZE = 0.00305

ELEMENTS = {
    "slat": ("4412", 0.153, -31.6, (-0.11, -0.02)),
    "main": ("2412", 1.0, 0.0, (0.0, 0.0)),
    "flap": ("4412", 0.3, 30.0, (0.96, -0.05)),
}


def build(h, out):
    gmsh.initialize(["-noenv"])
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("three-element")
    occ = gmsh.model.occ
    loops, curves, edge_points = [], {}, []
    for name, (code, chord, angle, origin) in ELEMENTS.items():
        upper, lower = naca.placed(code, 100, chord, angle, origin)
        loop, cs = naca.add_curve_loop(occ, upper, lower, h)
        loops.append(loop)
        curves[name] = cs
        for x, y in (upper[0], upper[-1]):
            edge_points.append(occ.addPoint(x, y, 0))
    far = occ.addCircle(0.5, 0, 0, 10)
    far_loop = occ.addCurveLoop([far])
    surface = occ.addPlaneSurface([far_loop] + loops)
    occ.synchronize()
    for name, cs in curves.items():
        gmsh.model.addPhysicalGroup(1, cs, name=name)
    gmsh.model.addPhysicalGroup(1, [far], name="farfield")
    fluid = gmsh.model.addPhysicalGroup(2, [surface], name="fluid")
    f = gmsh.model.mesh.field
    dist = f.add("Distance")
    f.setNumbers(dist, "CurvesList", [c for cs in curves.values() for c in cs])
    f.setNumber(dist, "Sampling", 400)
    thr = f.add("Threshold")
    f.setNumber(thr, "InField", dist)
    f.setNumber(thr, "SizeMin", h)
    f.setNumber(thr, "SizeMax", 1.5)
    f.setNumber(thr, "DistMin", 0)
    f.setNumber(thr, "DistMax", 8)
    edges = f.add("Distance")
    f.setNumbers(edges, "PointsList", edge_points)
    ethr = f.add("Threshold")
    f.setNumber(ethr, "InField", edges)
    f.setNumber(ethr, "SizeMin", h / 4)
    f.setNumber(ethr, "SizeMax", 1.5)
    f.setNumber(ethr, "DistMin", 0.01)
    f.setNumber(ethr, "DistMax", 0.3)
    both = f.add("Min")
    f.setNumbers(both, "FieldsList", [thr, ethr])
    f.setAsBackgroundMesh(both)
    for key in ("MeshSizeExtendFromBoundary", "MeshSizeFromPoints", "MeshSizeFromCurvature"):
        gmsh.option.setNumber("Mesh." + key, 0)
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    gmsh.model.mesh.generate(2)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.option.setNumber("Mesh.Binary", 1)
    nodes = len(gmsh.model.mesh.getNodesForPhysicalGroup(2, fluid)[0])
    gmsh.write(out)
    gmsh.finalize()
    print(f"{out}: {nodes} nodes (h = {h})")


def main():
    if len(sys.argv) == 4 and sys.argv[1] == "--size":
        build(float(sys.argv[2]), sys.argv[3])
    elif len(sys.argv) == 2:
        build(SIZE, sys.argv[1])
    else:
        sys.exit("usage: three_element.py OUT.msh | --size H OUT.msh")


if __name__ == "__main__":
    main()
