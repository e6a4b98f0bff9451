"""Mesh of the paper's section 5.2 case: two fish side by side in a box.

The paper shows the fish but gives neither their shape nor the domain. We
take two identical bodies of length 1 along +x, heads at x = 0, their axes
0.5 apart (y = +0.25: group `fish1`, y = -0.25: group `fish2`), z = 0. Each
body is a smooth, laterally flattened ellipsoid: semi-axes 0.5 along the
body, 0.06 across (y) and 0.12 up (z). (A first version lofted NACA 0012
sections closed by small flat end caps; the eq. 11 shear of its thin tail
inverted a tetrahedron whose four nodes all lie on the body, at the same
step for every method: a boundary that inverts by itself.)
The box (group `box`, fixed) spans [-1, 3] x [-1.5, 1.5] x [-1, 1].
Tetrahedra of size h on the bodies grow to 12h at distance 1.2; h is chosen
for a node count close to the paper's 20,840 nodes (108,322 tetrahedra).

Usage: python3 two_fish.py OUT.msh | --size H OUT.msh
"""

import gmsh

import meshing

SIZE = 0.0176


def fish(occ, y0):
    """An ellipsoid of semi-axes 0.5 (along x), 0.06 (y) and 0.12 (z) from
    x = 0 to x = 1, its axis at (y0, 0); returns its volume tag."""
    body = occ.addSphere(0.5, y0, 0, 1)
    occ.dilate([(3, body)], 0.5, y0, 0, 0.5, 0.06, 0.12)
    return body


def build(h, out):
    gmsh.initialize(["-noenv"])
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("two-fish")
    occ = gmsh.model.occ
    box = occ.addBox(-1, -1.5, -1, 4, 3, 2)
    f1 = fish(occ, 0.25)
    f2 = fish(occ, -0.25)
    volume, _ = occ.cut([(3, box)], [(3, f1), (3, f2)])
    occ.synchronize()
    surfaces = [s for _, s in gmsh.model.getBoundary(volume, oriented=False)]
    groups = {"fish1": [], "fish2": [], "box": []}
    for s in surfaces:
        x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(2, s)
        if x1 - x0 > 3.5 or y1 - y0 > 2.5 or z1 - z0 > 1.5:
            groups["box"].append(s)
        else:
            groups["fish1" if y0 + y1 > 0 else "fish2"].append(s)
    for name, tags in groups.items():
        gmsh.model.addPhysicalGroup(2, tags, name=name)
    fluid = gmsh.model.addPhysicalGroup(3, [volume[0][1]], name="fluid")
    f = gmsh.model.mesh.field
    thr = meshing.graded("SurfacesList", groups["fish1"] + groups["fish2"], h, 12 * h, 0, 1.2)
    f.setAsBackgroundMesh(thr)
    gmsh.option.setNumber("Mesh.Algorithm", 1)  # MeshAdapt: the scaled spheres defeat the default
    gmsh.option.setNumber("Mesh.OptimizeNetgen", 1)
    meshing.finish(out, 3, fluid, h)


if __name__ == "__main__":
    meshing.command_line(build, "two_fish.py", SIZE)
