"""Hybrid boundary-layer mesh of a circular cylinder (diameter 1, centre at
the origin) in a channel x in [-5, 15], y in [-3, 3]: a layer of
quadrilaterals on the cylinder from Gmsh's BoundaryLayer field (first cell
1e-3 diameter, growth 1.2, 15 cells: 0.072 in all), triangles outside,
graded from h on the cylinder to 10h at distance 3 and beyond (meshing.graded).

Groups: `cylinder`, `inlet` (x = -5), `outlet` (x = 15), `walls` (both
channel walls y = -3 and y = 3: two parallel planes), `fluid`.

Usage: python3 cylinder_channel.py OUT.msh | --size H OUT.msh
"""

import gmsh

import meshing

import rans_blunt

SIZE = 0.02
FIRST = 1e-3
RATIO = 1.2
LAYERS = 15


def build(h, out):
    gmsh.initialize(["-noenv"])
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("cylinder-channel")
    occ = gmsh.model.occ
    corners = [occ.addPoint(x, y, 0) for x, y in ((-5, -3), (15, -3), (15, 3), (-5, 3))]
    bottom, outlet, top, inlet = (occ.addLine(corners[k], corners[(k + 1) % 4]) for k in range(4))
    circle = occ.addCircle(0, 0, 0, 0.5)
    surface = occ.addPlaneSurface([occ.addCurveLoop([bottom, outlet, top, inlet]),
                                   occ.addCurveLoop([circle])])
    occ.synchronize()
    gmsh.model.addPhysicalGroup(1, [circle], name="cylinder")
    gmsh.model.addPhysicalGroup(1, [inlet], name="inlet")
    gmsh.model.addPhysicalGroup(1, [outlet], name="outlet")
    gmsh.model.addPhysicalGroup(1, [bottom, top], name="walls")
    fluid = gmsh.model.addPhysicalGroup(2, [surface], name="fluid")
    thr = meshing.graded("CurvesList", [circle], h, 10 * h, 0.1, 3, sampling=200)
    gmsh.model.mesh.field.setAsBackgroundMesh(thr)
    thickness = FIRST * (RATIO**LAYERS - 1) / (RATIO - 1)
    rans_blunt.boundary_layer([circle], [], FIRST, RATIO, thickness * 1.0001, 0)
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    meshing.finish(out, 2, fluid, h)


if __name__ == "__main__":
    meshing.command_line(build, "cylinder_channel.py", SIZE)
