"""RANS-type mesh of the paper's three-element airfoil: the slat, main
element and flap of three_element.py (same sections, chords and placement),
each with a blunt trailing edge of thickness 0.3% of its own chord, and a
boundary layer of quadrilaterals on all three (first cell 1e-5 of the main
chord, growth 1.2, total 0.008: 28 cells, so that two layers and a few
triangles fit the narrowest slot, 0.028) with a fan of cells at every
trailing-edge corner. Triangles outside, graded from the wall sizes to 1.5
at a circular far field of radius 10 about (0.5, 0).

Groups: `slat`, `main`, `flap` (each wall with its trailing edge),
`farfield`, `fluid`.

Usage: python3 rans_three_element.py OUT.msh | --size H OUT.msh
(H: the wall size on the main element; the slat's is H/2, the flap's 0.6 H)
"""

import gmsh

import meshing

import rans_blunt

import three_element

SIZE = 0.007
TE = 0.003
FIRST = 1e-5
RATIO = 1.2
THICKNESS = 0.008
WALL = {"slat": 0.5, "main": 1.0, "flap": 0.6}


def build(h, out):
    gmsh.initialize(["-noenv"])
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("rans-three-element")
    occ = gmsh.model.occ
    loops, curves, corners, noses = [], {}, {}, {}
    for name, (code, chord, angle, origin) in three_element.ELEMENTS.items():
        upper, lower = rans_blunt.placed(code, 150, TE, chord, angle, origin)
        loop, cs, pts = rans_blunt.add_loop(occ, upper, lower)
        loops.append(loop)
        curves[name] = cs
        corners[name] = pts
        noses[name] = occ.addPoint(*upper[0], 0)
    far = occ.addCircle(0.5, 0, 0, 10)
    far_loop = occ.addCurveLoop([far])
    surface = occ.addPlaneSurface([far_loop] + loops)
    occ.synchronize()
    for name, cs in curves.items():
        gmsh.model.addPhysicalGroup(1, cs, name=name)
    gmsh.model.addPhysicalGroup(1, [far], name="farfield")
    fluid = gmsh.model.addPhysicalGroup(2, [surface], name="fluid")
    f = gmsh.model.mesh.field
    sizes = []
    for name, (_, chord, _, _) in three_element.ELEMENTS.items():
        hw = WALL[name] * h
        sizes.append(meshing.graded("CurvesList", curves[name], hw, 1.5, 0.01, 8, sampling=400))
        te_size = max(TE * chord / 2, hw / 10)
        sizes.append(meshing.graded("PointsList", corners[name], te_size, 1.5, 0.002, 0.5))
        sizes.append(meshing.graded("PointsList", [noses[name]], hw / 4, 1.5, 0.005, 0.5))
    both = f.add("Min")
    f.setNumbers(both, "FieldsList", sizes)
    f.setAsBackgroundMesh(both)
    walls = [c for cs in curves.values() for c in cs]
    fans = [p for ps in corners.values() for p in ps]
    rans_blunt.boundary_layer(walls, fans, FIRST, RATIO, THICKNESS, 10)
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    meshing.finish(out, 2, fluid, h)


if __name__ == "__main__":
    meshing.command_line(build, "rans_three_element.py", SIZE)
