"""Mesh of the paper's section 5.1 case: a sphere of radius 5 (group
`sphere`) at the centre of a 50 x 50 x 50 cube (group `cube`, fixed).

Tetrahedra of size h on the sphere grow to 5h at distance 20 (Gmsh
Distance + Threshold fields); h is chosen for a node count close to the
paper's 2,058 nodes (9,496 elements).

Usage: python3 sphere_cube.py OUT.msh | --size H OUT.msh
"""

import gmsh

import meshing

SIZE = 1.16717


def build(h, out):
    gmsh.initialize(["-noenv"])
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("sphere-cube")
    occ = gmsh.model.occ
    cube = occ.addBox(-25, -25, -25, 50, 50, 50)
    sphere = occ.addSphere(0, 0, 0, 5)
    volume, _ = occ.cut([(3, cube)], [(3, sphere)])
    occ.synchronize()
    surfaces = [s for _, s in gmsh.model.getBoundary(volume, oriented=False)]
    on_sphere = [s for s in surfaces if max(abs(v) for v in gmsh.model.getBoundingBox(2, s)) < 6]
    gmsh.model.addPhysicalGroup(2, on_sphere, name="sphere")
    gmsh.model.addPhysicalGroup(2, [s for s in surfaces if s not in on_sphere], name="cube")
    fluid = gmsh.model.addPhysicalGroup(3, [volume[0][1]], name="fluid")
    f = gmsh.model.mesh.field
    thr = meshing.graded("SurfacesList", on_sphere, h, 5 * h, 0, 20)
    f.setAsBackgroundMesh(thr)
    gmsh.option.setNumber("Mesh.OptimizeNetgen", 1)
    meshing.finish(out, 3, fluid, h)


if __name__ == "__main__":
    meshing.command_line(build, "sphere_cube.py", SIZE)
