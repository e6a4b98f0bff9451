"""Mesh of the paper's section 5.1 case: a sphere of radius 5 (group
`sphere`) at the centre of a 50 x 50 x 50 cube (group `cube`, fixed).

Tetrahedra of size h on the sphere grow to 5h at distance 20 (Gmsh
Distance + Threshold fields); h is chosen for a node count close to the
paper's 2,058 nodes (9,496 elements).

Usage: python3 sphere_cube.py OUT.msh | --size H OUT.msh
"""

import sys

import gmsh

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
    dist = f.add("Distance")
    f.setNumbers(dist, "SurfacesList", on_sphere)
    thr = f.add("Threshold")
    f.setNumber(thr, "InField", dist)
    f.setNumber(thr, "SizeMin", h)
    f.setNumber(thr, "SizeMax", 5 * h)
    f.setNumber(thr, "DistMin", 0)
    f.setNumber(thr, "DistMax", 20)
    f.setAsBackgroundMesh(thr)
    for key in ("MeshSizeExtendFromBoundary", "MeshSizeFromPoints", "MeshSizeFromCurvature"):
        gmsh.option.setNumber("Mesh." + key, 0)
    gmsh.option.setNumber("Mesh.OptimizeNetgen", 1)
    gmsh.model.mesh.generate(3)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.option.setNumber("Mesh.Binary", 1)
    nodes = len(gmsh.model.mesh.getNodesForPhysicalGroup(3, fluid)[0])
    gmsh.write(out)
    gmsh.finalize()
    print(f"{out}: {nodes} nodes (h = {h})")


def main():
    if len(sys.argv) == 4 and sys.argv[1] == "--size":
        build(float(sys.argv[2]), sys.argv[3])
    elif len(sys.argv) == 2:
        build(SIZE, sys.argv[1])
    else:
        sys.exit("usage: sphere_cube.py OUT.msh | --size H OUT.msh")


if __name__ == "__main__":
    main()
