"""Mesh of the paper's section 5.3 case: a wing-body combination (half
model) whose wing bends.

The paper shows a wing-body but gives no dimensions. We take a half model
cut by the symmetry plane y = 0 (group `symmetry`, fixed):
- fuselage (group `body`, fixed): an ellipsoid with semi-axes 2, 0.25, 0.25
  about the origin;
- wing (group `wing`, moving): NACA 0012 sections lofted from a root chord
  of 0.8 (leading edge at (-0.4, 0, 0), inside the fuselage) to a tip chord
  of 0.32 (leading edge at (-0.1, 2.25, 0)); it leaves the fuselage at
  y = 0.25, so its span is L = 2;
- far field (group `farfield`, fixed): the box [-3, 5] x [0, 4] x [-3, 3].
Tetrahedra of size h on the wing and fuselage grow to 20h at distance 3;
h is chosen for a node count close to the paper's 106,755 nodes (610,252
tetrahedra). Gmsh's parallel HXT algorithm meshes the volume.

Usage: python3 bending_wing.py OUT.msh | --size H OUT.msh
"""

import gmsh

import meshing

import naca

SIZE = 0.016


def section_wire(occ, chord, le, y, h):
    """A closed NACA 0012 wire of `chord` in the plane y = `y`, leading edge at x = le."""
    upper, lower = naca.section("0012", 60)
    pts_u = [occ.addPoint(le + chord * x, y, chord * z, h) for x, z in upper]
    pts_l = [pts_u[0]] + [occ.addPoint(le + chord * x, y, chord * z, h) for x, z in lower[1:-1]] + [pts_u[-1]]
    return occ.addWire([occ.addSpline(pts_u), occ.addSpline(pts_l)])


def build(h, out):
    gmsh.initialize(["-noenv"])
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("bending-wing")
    occ = gmsh.model.occ
    box = occ.addBox(-3, 0, -3, 8, 4, 6)
    fuselage = occ.addSphere(0, 0, 0, 1)
    occ.dilate([(3, fuselage)], 0, 0, 0, 2, 0.25, 0.25)
    root = section_wire(occ, 0.8, -0.4, 0.0, h)
    tip = section_wire(occ, 0.32, -0.1, 2.25, h)
    wing = [t for d, t in occ.addThruSections([root, tip], makeSolid=True, makeRuled=True) if d == 3]
    body, _ = occ.fuse([(3, fuselage)], [(3, w) for w in wing])
    volume, _ = occ.cut([(3, box)], body)
    occ.synchronize()
    surfaces = [s for _, s in gmsh.model.getBoundary(volume, oriented=False)]
    groups = {"wing": [], "body": [], "symmetry": [], "farfield": []}
    for s in surfaces:
        x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(2, s)
        if x1 - x0 > 7 or z1 - z0 > 5 or y0 > 3.9:
            groups["symmetry" if y1 < 1e-3 else "farfield"].append(s)
        elif y1 > 0.5:
            groups["wing"].append(s)
        else:
            groups["body"].append(s)
    for name, tags in groups.items():
        gmsh.model.addPhysicalGroup(2, tags, name=name)
    fluid = gmsh.model.addPhysicalGroup(3, [volume[0][1]], name="fluid")
    f = gmsh.model.mesh.field
    thr = meshing.graded("SurfacesList", groups["wing"] + groups["body"], h, 20 * h, 0, 3)
    f.setAsBackgroundMesh(thr)
    gmsh.option.setNumber("Mesh.Algorithm3D", 10)
    meshing.finish(out, 3, fluid, h)


if __name__ == "__main__":
    meshing.command_line(build, "bending_wing.py", SIZE)
