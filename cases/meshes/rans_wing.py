"""RANS-type mesh of a straight NACA0012 wing: chord 1 (leading edge on the
y axis), half span 2 from a root on the symmetry plane y = 0 to a flat
closed tip at y = 2, blunt trailing edge of thickness 0.3% chord (as in
rans_naca0012.py). The wing's surface mesh is extruded along the span (so
that the normals at the root lie in the symmetry plane); a layer of prisms
(first cell 1e-5 chord, growth 1.2, 15 cells, 0.00072 chord in all) is
extruded from its triangles along the surface normals; tetrahedra fill the
rest of the box x in [-10, 11], y in [0, 10], z in [-10, 10], graded from h
at the wing (h/3 along the leading and trailing edges) to 2.

Groups: `wing` (the surface, the trailing edge and the tip), `symmetry` (the
plane y = 0 with the layer's root faces), `farfield` (the other five box
faces), `fluid`.

Usage: python3 rans_wing.py OUT.msh | --size H OUT.msh
"""

import math

import gmsh

import meshing

import rans_blunt

SIZE = 0.04
TE = 0.003
SPAN = 2.0
FIRST = 1e-5
RATIO = 1.2
LAYERS = 15
BOX = ((-10.0, 11.0), (0.0, 10.0), (-10.0, 10.0))


def box_faces(geo, hole):
    """The six faces of BOX; the face y = 0 has the curve loop `hole` cut out.
    Returns (the face y = 0, the other five)."""
    (x0, x1), (y0, y1), (z0, z1) = BOX
    p = {(i, j, k): geo.addPoint((x0, x1)[i], (y0, y1)[j], (z0, z1)[k])
         for i in (0, 1) for j in (0, 1) for k in (0, 1)}

    lines = {}

    def line(u, v):
        if (v, u) in lines:
            return -lines[(v, u)]
        if (u, v) not in lines:
            lines[(u, v)] = geo.addLine(p[u], p[v])
        return lines[(u, v)]

    def face(a, b, c, d):
        return geo.addCurveLoop([line(u, v) for u, v in ((a, b), (b, c), (c, d), (d, a))])

    sym = geo.addPlaneSurface([face((0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1)), hole])
    others = [geo.addPlaneSurface([face(*q)]) for q in (
        ((0, 1, 0), (1, 1, 0), (1, 1, 1), (0, 1, 1)),
        ((0, 0, 0), (0, 1, 0), (0, 1, 1), (0, 0, 1)),
        ((1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 0, 1)),
        ((0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)),
        ((0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)),
    )]
    return sym, others


def build(h, out):
    gmsh.initialize(["-noenv"])
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("rans-wing")
    geo = gmsh.model.geo
    upper, lower = rans_blunt.blunt_section("0012", 80, TE)
    _, root, _ = rans_blunt.add_loop(geo, upper, lower)
    geo.rotate([(1, c) for c in root], 0, 0, 0, 1, 0, 0, math.pi / 2)
    tip_curves, wing, spanwise = [], [], []
    for c in root:
        ext = geo.extrude([(1, c)], 0, SPAN, 0, [round(SPAN / h)])
        tip_curves.append(ext[0][1])
        wing.append(ext[1][1])
        spanwise += [abs(t) for _, t in ext[2:]]
    spanwise.append(geo.addLine(geo.addPoint(0, 0, 0), geo.addPoint(0, SPAN, 0)))
    wing.append(geo.addPlaneSurface([geo.addCurveLoop(tip_curves)]))
    heights = [FIRST * (RATIO ** (k + 1) - 1) / (RATIO - 1) for k in range(LAYERS)]
    # These surfaces' normals point into the wing: negative heights extrude into the fluid.
    layer = geo.extrudeBoundaryLayer([(2, s) for s in wing], [1] * LAYERS, [-x for x in heights], True)
    # The result lists, per surface, its top surface and then its layer volume.
    top = [layer[k - 1] for k in range(1, len(layer)) if layer[k][0] == 3]
    cells = [t for d, t in layer if d == 3]
    geo.synchronize()
    rim = [t for _, t in gmsh.model.getBoundary(top)]
    sym, far = box_faces(geo, geo.addCurveLoop(rim))
    outer = geo.addVolume([geo.addSurfaceLoop([sym] + far + [t for _, t in top])])
    geo.synchronize()
    sides = [t for d, t in layer if d == 2 and (d, t) not in top]
    roots = [t for t in sides if sides.count(t) == 1]
    gmsh.model.addPhysicalGroup(2, wing, name="wing")
    gmsh.model.addPhysicalGroup(2, [sym] + roots, name="symmetry")
    gmsh.model.addPhysicalGroup(2, far, name="farfield")
    fluid = gmsh.model.addPhysicalGroup(3, cells + [outer], name="fluid")
    f = gmsh.model.mesh.field
    thr = meshing.graded("SurfacesList", wing, h, 2.0, 0.02, 8, sampling=100)
    edges = meshing.graded("CurvesList", spanwise, h / 3, 2.0, 0.01, 0.3, sampling=200)
    both = f.add("Min")
    f.setNumbers(both, "FieldsList", [thr, edges])
    f.setAsBackgroundMesh(both)
    meshing.finish(out, 3, fluid, h)


if __name__ == "__main__":
    meshing.command_line(build, "rans_wing.py", SIZE)
