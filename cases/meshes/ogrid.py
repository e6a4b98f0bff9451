"""Structured RANS O-grid around the NACA0012 airfoil (chord 1, leading edge
at the origin), all quadrilaterals, built from Gmsh transfinite blocks.

The section has a blunt trailing edge of thickness 0.3% chord (cut and
scaled back to chord 1, as rans_blunt.py), so that the O wraps around it
without a cusp: the i-lines run around the airfoil and its base, the
j-lines from the wall to a circular far field of radius 20 about the
mid-chord. Five blocks: the base (its j-lines leave the two corners at 30
degrees from the chord line), the aft parts (corner to x = 0.3, where the
surface normal is vertical) and the noses (x = 0.3 to the leading edge,
whose j-line runs straight upstream). Every j-line has `--nj` nodes and a
first cell of `--first` (default 1e-5 chord); along the surface the cells
grow from 0.9/m at the leading edge and 2e-4 at the corners (m cells a
surface), the base has 24 cells, smallest at its corners.

Groups: `airfoil` (the wall and the base), `farfield`, `fluid`.

Usage: python3 ogrid.py [--ni NI] [--nj NJ] [--first H] OUT.msh
  ogrid.msh: the defaults, --ni 352 --nj 93 (32,736 nodes)

`--ni` counts the nodes of one (closed) i-line around the airfoil and its
base, `--nj` the nodes of a j-line.
"""

import argparse
import math

import gmsh

import rans_blunt
import structured as st

TE = 0.003          # base thickness
R = 20.0            # far-field radius about (0.5, 0)
X_SPLIT = 0.3       # surface station between the nose and aft blocks
CORNER_DEG = 30.0   # direction of the j-lines from the base's corners
BASE_CELLS = 24
BASE_BUMP = 0.1     # Gmsh "Bump": base cells about 7x smaller at the corners
D_CORNER = 2e-4     # surface cells at the trailing-edge corners


def build(ni, nj, first, out):
    gmsh.initialize(["-noenv"])
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("ogrid")
    geo = gmsh.model.geo

    upper, _ = rans_blunt.blunt_section("0012", 2000, TE)
    k1 = min(range(len(upper)), key=lambda k: abs(upper[k][0] - X_SPLIT))
    nose = st.resample(upper[:k1 + 1], 120)
    aft = st.resample(upper[k1:], 150)
    len_nose, len_aft = st.length(nose), st.length(aft)
    y_te = upper[-1][1]

    surface = (ni - BASE_CELLS) // 2              # cells a surface
    d_le = 0.15 / surface
    n_nose = min(range(3, surface - 2),
                 key=lambda n: abs(math.log(st.last(d_le, len_nose, n)
                                            / st.last(D_CORNER, len_aft, surface - n))))
    n_aft = surface - n_nose

    cx = 0.5
    centre = geo.addPoint(cx, 0, 0)
    le = geo.addPoint(0, 0, 0)
    o_le = geo.addPoint(cx - R, 0, 0)
    j_le = geo.addLine(le, o_le)
    st.progression(j_le, nj, first, R - cx)
    a = math.radians(CORNER_DEG)
    wall, outer, surfaces = [], [], []

    def half(sign):
        pts = [geo.addPoint(x, sign * y, 0) for x, y in nose[1:-1]]
        p1 = geo.addPoint(nose[-1][0], sign * nose[-1][1], 0)
        s_nose = geo.addSpline([le] + pts + [p1])
        corner = geo.addPoint(1, sign * y_te, 0)
        pts = [geo.addPoint(x, sign * y, 0) for x, y in reversed(aft[1:-1])]
        s_aft = geo.addSpline([corner] + pts + [p1])         # from the corner
        wall.extend([s_nose, s_aft])
        st.progression(s_nose, n_nose + 1, d_le, len_nose)
        st.progression(s_aft, n_aft + 1, D_CORNER, len_aft)

        x1, y1 = nose[-1]
        o1 = (x1, math.sqrt(R**2 - (cx - x1) ** 2))
        oc = (cx + R * math.cos(a), R * math.sin(a))
        p_o1 = geo.addPoint(o1[0], sign * o1[1], 0)
        p_oc = geo.addPoint(oc[0], sign * oc[1], 0)
        arc_nose = geo.addCircleArc(o_le, centre, p_o1)
        arc_aft = geo.addCircleArc(p_o1, centre, p_oc)
        geo.mesh.setTransfiniteCurve(arc_nose, n_nose + 1)
        geo.mesh.setTransfiniteCurve(arc_aft, n_aft + 1)
        j1 = geo.addLine(p1, p_o1)
        jc = geo.addLine(corner, p_oc)
        st.progression(j1, nj, first, math.dist((x1, y1), o1))
        st.progression(jc, nj, first, math.dist((1, y_te), oc))
        outer.extend([arc_nose, arc_aft])
        loops = [
            ([s_nose, j1, -arc_nose, -j_le], [le, p1, p_o1, o_le]),
            ([-s_aft, jc, -arc_aft, -j1], [p1, corner, p_oc, p_o1]),
        ]
        for curves, corners in loops:
            if sign < 0:            # mirrored: reverse the loop to keep it counter-clockwise
                curves = [-c for c in reversed(curves)]
                corners = list(reversed(corners))
            surfaces.append(st.block(curves, corners))
        return corner, p_oc, jc

    c_u, oc_u, jc_u = half(1)
    c_l, oc_l, jc_l = half(-1)
    base = geo.addLine(c_l, c_u)
    arc_base = geo.addCircleArc(oc_l, centre, oc_u)
    geo.mesh.setTransfiniteCurve(base, BASE_CELLS + 1, "Bump", BASE_BUMP)
    geo.mesh.setTransfiniteCurve(arc_base, BASE_CELLS + 1)
    surfaces.append(st.block([jc_l, arc_base, -jc_u, -base], [c_l, oc_l, oc_u, c_u]))
    wall.append(base)
    outer.append(arc_base)

    print(f"i: {2 * surface + BASE_CELLS} cells around ({n_nose} + {n_aft} a surface, "
          f"{BASE_CELLS} on the base); j: {nj} nodes")
    st.write(out, wall, outer, surfaces)


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--ni", type=int, default=352)
    ap.add_argument("--nj", type=int, default=93)
    ap.add_argument("--first", type=float, default=1e-5)
    ap.add_argument("out")
    a = ap.parse_args()
    build(a.ni, a.nj, a.first, a.out)
