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

import gmsh

import meshing

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
    thr = meshing.graded("CurvesList", [c for cs in curves.values() for c in cs], h, 1.5, 0, 8, sampling=400)
    ethr = meshing.graded("PointsList", edge_points, h / 4, 1.5, 0.01, 0.3)
    both = f.add("Min")
    f.setNumbers(both, "FieldsList", [thr, ethr])
    f.setAsBackgroundMesh(both)
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    meshing.finish(out, 2, fluid, h)


if __name__ == "__main__":
    meshing.command_line(build, "three_element.py", SIZE)
