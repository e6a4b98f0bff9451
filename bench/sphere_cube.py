#!/usr/bin/env python3
"""A sphere of radius 5 inside the cube [-25, 25]^3 (the VerBSS paper's §5.1),
meshed with tetrahedra by Gmsh and written as MSH 4.1 binary.

    python3 bench/sphere_cube.py OUT.msh --h-sphere 0.8 [--h-far 5.0] [--box 25 --dist-max 20]

Physical groups: "sphere" (the sphere's surface), "farfield" (the six cube
faces), "domain" (the tetrahedra). The element size grows linearly from
--h-sphere on the sphere to --h-far at distance --dist-max from it; halving
both multiplies the tetrahedra by about 8. --box sets the cube's half width
(the motion benchmark, bench/compare.py, uses a larger cube so that the
sphere can travel 16 units).
"""
import argparse
import sys

import gmsh


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out")
    ap.add_argument("--h-sphere", type=float, required=True)
    ap.add_argument("--h-far", type=float, default=None)
    ap.add_argument("--box", type=float, default=25.0)
    ap.add_argument("--dist-max", type=float, default=20.0)
    ap.add_argument("--threads", type=int, default=1)
    a = ap.parse_args()
    h_far = a.h_far if a.h_far is not None else 6.0 * a.h_sphere
    gmsh.initialize(["", "-v", "2"])
    gmsh.option.setNumber("General.NumThreads", a.threads)
    gmsh.model.add("sphere_cube")
    box = gmsh.model.occ.addBox(-a.box, -a.box, -a.box, 2 * a.box, 2 * a.box, 2 * a.box)
    ball = gmsh.model.occ.addSphere(0, 0, 0, 5)
    out, _ = gmsh.model.occ.cut([(3, box)], [(3, ball)])
    gmsh.model.occ.synchronize()
    volume = out[0][1]
    faces = [t for (d, t) in gmsh.model.getBoundary(out, oriented=False) if d == 2]
    sphere = [f for f in faces if abs(gmsh.model.occ.getMass(2, f) - 4 * 3.141592653589793 * 25) < 1.0]
    farfield = [f for f in faces if f not in sphere]
    gmsh.model.addPhysicalGroup(2, sphere, name="sphere")
    gmsh.model.addPhysicalGroup(2, farfield, name="farfield")
    gmsh.model.addPhysicalGroup(3, [volume], name="domain")
    dist = gmsh.model.mesh.field.add("Distance")
    gmsh.model.mesh.field.setNumbers(dist, "SurfacesList", sphere)
    size = gmsh.model.mesh.field.add("Threshold")
    gmsh.model.mesh.field.setNumber(size, "InField", dist)
    gmsh.model.mesh.field.setNumber(size, "SizeMin", a.h_sphere)
    gmsh.model.mesh.field.setNumber(size, "SizeMax", h_far)
    gmsh.model.mesh.field.setNumber(size, "DistMin", 0.0)
    gmsh.model.mesh.field.setNumber(size, "DistMax", a.dist_max)
    gmsh.model.mesh.field.setAsBackgroundMesh(size)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
    gmsh.option.setNumber("Mesh.Algorithm3D", 10 if a.threads > 1 else 1)
    gmsh.model.mesh.generate(3)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.option.setNumber("Mesh.Binary", 1)
    gmsh.write(a.out)
    nodes = len(gmsh.model.mesh.getNodes()[0])
    types, tags, _ = gmsh.model.mesh.getElements(3)
    tets = sum(len(t) for t in tags)
    print(f"{a.out}: {nodes} nodes, {tets} tetrahedra", file=sys.stderr)
    gmsh.finalize()


if __name__ == "__main__":
    main()
