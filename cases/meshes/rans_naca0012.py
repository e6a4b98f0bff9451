"""RANS-type mesh of the NACA0012 airfoil: chord 1 (leading edge at the
origin), blunt trailing edge of thickness 0.3% chord (the section is cut
where it is that thick and scaled back to chord 1), a boundary layer of
quadrilaterals (first cell 1e-5 chord, growth 1.2, total 0.05 chord: 38
cells) with a fan of cells at both trailing-edge corners, triangles
outside, graded from h at the airfoil to 2 at a circular far field of radius
20 about the quarter chord.

Groups: `airfoil` (the wall and the trailing edge), `farfield`, `fluid`.

Usage: python3 rans_naca0012.py OUT.msh | --size H OUT.msh
"""

import gmsh

import meshing

import rans_blunt

SIZE = 0.006
TE = 0.003
FIRST = 1e-5
RATIO = 1.2
THICKNESS = 0.05


def build(h, out):
    gmsh.initialize(["-noenv"])
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("rans-naca0012")
    occ = gmsh.model.occ
    upper, lower = rans_blunt.blunt_section("0012", 150, TE)
    loop, airfoil, corners = rans_blunt.add_loop(occ, upper, lower)
    le = occ.addPoint(0, 0, 0)
    far = occ.addCircle(0.25, 0, 0, 20)
    far_loop = occ.addCurveLoop([far])
    surface = occ.addPlaneSurface([far_loop, loop])
    occ.synchronize()
    gmsh.model.addPhysicalGroup(1, airfoil, name="airfoil")
    gmsh.model.addPhysicalGroup(1, [far], name="farfield")
    fluid = gmsh.model.addPhysicalGroup(2, [surface], name="fluid")
    f = gmsh.model.mesh.field
    thr = meshing.graded("CurvesList", airfoil, h, 2.0, 0.02, 12, sampling=400)
    ethr = meshing.graded("PointsList", corners + [le], h / 5, 2.0, 0.01, 0.5)
    both = f.add("Min")
    f.setNumbers(both, "FieldsList", [thr, ethr])
    f.setAsBackgroundMesh(both)
    rans_blunt.boundary_layer(airfoil, corners, FIRST, RATIO, THICKNESS, 12)
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    meshing.finish(out, 2, fluid, h)


if __name__ == "__main__":
    meshing.command_line(build, "rans_naca0012.py", SIZE)
