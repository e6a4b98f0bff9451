"""Mesh of the paper's section 4.2 case: the NACA0012 airfoil (chord 1,
leading edge at the origin, group `airfoil`) in a circular far field of
radius 10 chords about the quarter chord (group `farfield`).

The paper's mesh has 8,664 triangles and 4,485 nodes; its far-field
distance is not given. Triangles are graded from size h at the airfoil
(h/4 within 0.02 of the leading and trailing edges) to 1.5 at the far
field; h is chosen for a node count close to the paper's.

Usage: python3 naca0012.py OUT.msh | --size H OUT.msh
"""

import gmsh

import meshing

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
    thr = meshing.graded("CurvesList", airfoil, h, 1.5, 0, 8, sampling=400)
    ethr = meshing.graded("PointsList", [1, 101], h / 4, 1.5, 0.02, 0.3)
    both = f.add("Min")
    f.setNumbers(both, "FieldsList", [thr, ethr])
    f.setAsBackgroundMesh(both)
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    meshing.finish(out, 2, fluid, h)


if __name__ == "__main__":
    meshing.command_line(build, "naca0012.py", SIZE)
