"""Mesh of the paper's section 4.2 case: the NACA0012 airfoil (chord 1,
leading edge at the origin, group `airfoil`) in a circular far field of
radius 10 chords about the quarter chord (group `farfield`).

The paper's mesh has 8,664 triangles and 4,485 nodes; its far-field
distance is not given. Triangles are graded from size h at the airfoil
(h/4 within 0.02 of the leading and trailing edges) to 1.5 at the far
field; h is chosen for a node count close to the paper's.

Usage: python3 naca0012.py OUT.msh | --size H OUT.msh
"""

import sys

import gmsh

import naca

SIZE = 0.00605


def build(h, out):
    gmsh.initialize(["-noenv"])
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("naca0012")
    occ = gmsh.model.occ
    upper, lower = naca.section("0012", 100)
    loop, airfoil = naca.add_curve_loop(occ, upper, lower, h)
    far = occ.addCircle(0.25, 0, 0, 10)
    far_loop = occ.addCurveLoop([far])
    surface = occ.addPlaneSurface([far_loop, loop])
    occ.synchronize()
    gmsh.model.addPhysicalGroup(1, airfoil, name="airfoil")
    gmsh.model.addPhysicalGroup(1, [far], name="farfield")
    fluid = gmsh.model.addPhysicalGroup(2, [surface], name="fluid")
    f = gmsh.model.mesh.field
    dist = f.add("Distance")
    f.setNumbers(dist, "CurvesList", airfoil)
    f.setNumber(dist, "Sampling", 400)
    thr = f.add("Threshold")
    f.setNumber(thr, "InField", dist)
    f.setNumber(thr, "SizeMin", h)
    f.setNumber(thr, "SizeMax", 1.5)
    f.setNumber(thr, "DistMin", 0)
    f.setNumber(thr, "DistMax", 8)
    edges = f.add("Distance")
    f.setNumbers(edges, "PointsList", [1, 101])
    ethr = f.add("Threshold")
    f.setNumber(ethr, "InField", edges)
    f.setNumber(ethr, "SizeMin", h / 4)
    f.setNumber(ethr, "SizeMax", 1.5)
    f.setNumber(ethr, "DistMin", 0.02)
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
        sys.exit("usage: naca0012.py OUT.msh | --size H OUT.msh")


if __name__ == "__main__":
    main()
