"""A quarter domain cut by two symmetry planes that meet in a line: the
box [0, 20] x [0, 6] x [0, 6] with symmetry planes y = 0 (group
`symmetry_y`) and z = 0 (`symmetry_z`), meeting along the x axis, and a
body [8, 10] x [0, 2] x [0, 2] (group `body`) resting on both. Below
z = 2 the floor's triangles are extruded in 4 layers of prisms; above,
tetrahedra, with pyramids on the body's top face (quadrangles). The other
walls: `inlet` (x = 0), `outlet` (x = 20), `side` (y = 6), `top` (z = 6).

Moving the body along x moves it along the line where the symmetry planes
meet: the nodes on that line must slide along it.

Usage: python3 symmetry_slice.py OUT.msh | --size H OUT.msh
"""

import gmsh

import meshing

SIZE = 0.6


def build(h, out):
    gmsh.initialize(["-noenv"])
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("symmetry-slice")
    geo = gmsh.model.geo
    corners = [(0, 0), (8, 0), (8, 2), (10, 2), (10, 0), (20, 0), (20, 6), (0, 6)]
    points = [geo.addPoint(x, y, 0) for x, y in corners]
    lines = [geo.addLine(points[i], points[(i + 1) % 8]) for i in range(8)]
    floor = geo.addPlaneSurface([geo.addCurveLoop(lines)])
    lower = geo.extrude([(2, floor)], 0, 0, 2, numElements=[4], recombine=True)
    geo.synchronize()

    def inside(dim, low, high):
        e = 1e-6
        box = [v - e for v in low] + [v + e for v in high]
        return [t for _, t in gmsh.model.getEntitiesInBoundingBox(*box, dim)]

    (front,) = inside(0, (10, 0, 2), (10, 0, 2))
    (back,) = inside(0, (8, 0, 2), (8, 0, 2))
    edges = [inside(1, a, b)[0] for a, b in [((8, 0, 2), (8, 2, 2)), ((8, 2, 2), (10, 2, 2)), ((10, 0, 2), (10, 2, 2))]]
    lid = geo.addPlaneSurface([geo.addCurveLoop(edges + [geo.addLine(front, back)], reorient=True)])
    geo.extrude([(2, lower[0][1]), (2, lid)], 0, 0, 4)
    geo.mesh.setRecombine(2, lid)
    geo.synchronize()
    groups = {
        "symmetry_y": inside(2, (0, 0, 0), (20, 0, 6)),
        "symmetry_z": inside(2, (0, 0, 0), (20, 6, 0)),
        "body": inside(2, (8, 0, 0), (10, 2, 2)),
        "inlet": inside(2, (0, 0, 0), (0, 6, 6)),
        "outlet": inside(2, (20, 0, 0), (20, 6, 6)),
        "side": inside(2, (0, 6, 0), (20, 6, 6)),
        "top": inside(2, (0, 0, 6), (20, 6, 6)),
    }
    for name, surfaces in groups.items():
        gmsh.model.addPhysicalGroup(2, surfaces, name=name)
    volumes = [t for _, t in gmsh.model.getEntities(3)]
    fluid = gmsh.model.addPhysicalGroup(3, volumes, name="fluid")
    field = meshing.graded("SurfacesList", groups["body"], h, 2.5 * h, 0, 8)
    gmsh.model.mesh.field.setAsBackgroundMesh(field)
    meshing.finish(out, 3, fluid, h)


if __name__ == "__main__":
    meshing.command_line(build, "symmetry_slice.py", SIZE)
