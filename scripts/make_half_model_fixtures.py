"""Generate the partitioned half-model fixture in assets/meshes/gmsh/ with Gmsh.

Run from the repository root:

    python3 scripts/make_half_model_fixtures.py

The model: a sphere of radius 0.2 centred at (0.5, 0, 0.5) in the box
[0, 1] x [0, 0.5] x [0, 1], cut in half by its symmetry plane y = 0;
tetrahedra of size 0.08 (0.03 on the sphere). Physical groups: `sphere`
(the half sphere's surface), `symmetry` (the plane y = 0, the sphere's
cut disc excluded) and `farfield` (the five other faces of the box). It
writes

* half_sphere_v41_ascii.msh: the whole model;
* half_sphere_part3_v41_ascii.msh: the same mesh in 3 partitions, as
  `gmsh -part 3 -format msh41` writes it (METIS, with partition entities).
"""

import os
import sys

import gmsh

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "assets", "meshes", "gmsh")


def half_sphere():
    """The half sphere in the half box, meshed."""
    gmsh.model.add("half_sphere")
    occ = gmsh.model.occ
    box = occ.addBox(0, 0, 0, 1, 0.5, 1)
    ball = occ.addSphere(0.5, 0, 0.5, 0.2)
    occ.cut([(3, box)], [(3, ball)])
    occ.synchronize()
    volumes = gmsh.model.getEntities(3)
    sphere, symmetry, farfield = [], [], []
    for dim, tag in gmsh.model.getEntities(2):
        x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(dim, tag)
        if abs(y0) < 1e-6 and abs(y1) < 1e-6:
            symmetry.append(tag)
        elif x0 > 0.25 and x1 < 0.75 and z0 > 0.25 and z1 < 0.75:
            sphere.append(tag)
        else:
            farfield.append(tag)
    gmsh.model.addPhysicalGroup(3, [t for _, t in volumes], name="fluid")
    gmsh.model.addPhysicalGroup(2, sphere, name="sphere")
    gmsh.model.addPhysicalGroup(2, symmetry, name="symmetry")
    gmsh.model.addPhysicalGroup(2, farfield, name="farfield")
    gmsh.option.setNumber("Mesh.MeshSizeMax", 0.08)
    points = gmsh.model.getBoundary([(2, t) for t in sphere], combined=False, recursive=True)
    gmsh.model.mesh.setSize(points, 0.03)
    gmsh.model.mesh.generate(3)


def main():
    gmsh.initialize(sys.argv[:1])
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.option.setNumber("Mesh.Binary", 0)
    half_sphere()
    gmsh.write(os.path.join(OUT, "half_sphere_v41_ascii.msh"))
    gmsh.model.mesh.partition(3)
    gmsh.write(os.path.join(OUT, "half_sphere_part3_v41_ascii.msh"))
    gmsh.finalize()


if __name__ == "__main__":
    main()
