"""Mesh of the paper's section 4.1 case: a rectangle inside a fixed square.

The paper gives no dimensions. We take a 16 x 16 square (the fixed outer
boundary, group `outer`) with a 4 x 2 rectangle (group `body`) at its
centre, so the body can move at most 7 units vertically before touching the
outer wall. Triangles are graded from size h at the body to 4h at distance 6
(Gmsh Distance + Threshold fields), and h is chosen per node count so that
the meshes have close to the paper's Table 2 node counts.

Usage: python3 rectangle.py NODES OUT.msh   (NODES one of the keys of SIZES)
       python3 rectangle.py --size H OUT.msh (any h, to explore)
"""

import sys

import gmsh

import meshing

# Target node count (paper, Table 2) -> size h at the body.
SIZES = {298: 0.44388, 1035: 0.22298, 3055: 0.12621, 8081: 0.07601, 21376: 0.04625}


def build(h, out):
    gmsh.initialize(["-noenv"])
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("rectangle")
    occ = gmsh.model.occ
    outer = occ.addRectangle(-8, -8, 0, 16, 16)
    body = occ.addRectangle(-2, -1, 0, 4, 2)
    domain, _ = occ.cut([(2, outer)], [(2, body)])
    occ.synchronize()
    curves = gmsh.model.getBoundary(domain, oriented=False)
    body_curves, outer_curves = [], []
    for _, c in curves:
        x0, y0, _, x1, y1, _ = gmsh.model.getBoundingBox(1, c)
        inside = max(abs(x0), abs(x1)) <= 2.01 and max(abs(y0), abs(y1)) <= 1.01
        (body_curves if inside else outer_curves).append(c)
    gmsh.model.addPhysicalGroup(1, body_curves, name="body")
    gmsh.model.addPhysicalGroup(1, outer_curves, name="outer")
    fluid = gmsh.model.addPhysicalGroup(2, [domain[0][1]], name="fluid")
    f = gmsh.model.mesh.field
    thr = meshing.graded("CurvesList", body_curves, h, 4 * h, 0, 6, sampling=200)
    f.setAsBackgroundMesh(thr)
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    meshing.finish(out, 2, fluid, h)


def main():
    if len(sys.argv) == 4 and sys.argv[1] == "--size":
        build(float(sys.argv[2]), sys.argv[3])
    elif len(sys.argv) == 3 and sys.argv[1].isdigit() and int(sys.argv[1]) in SIZES:
        build(SIZES[int(sys.argv[1])], sys.argv[2])
    else:
        sys.exit(f"usage: rectangle.py NODES OUT.msh (NODES in {sorted(SIZES)}) | --size H OUT.msh")


if __name__ == "__main__":
    main()
