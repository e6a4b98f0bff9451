"""Structured RANS C-grid around the NACA0012 airfoil (chord 1, leading edge
at the origin), all quadrilaterals, built from Gmsh transfinite blocks the
way the classic 113x33 / 257x65 C-grids are laid out.

The C wraps around the airfoil and closes along a wake cut from the
trailing edge straight downstream to the outflow. Each half (upper, lower)
has four blocks: the nose (leading edge to x = 0.3, where the surface
normal is vertical), the aft part (x = 0.3 to the trailing edge) and two
wake blocks (trailing edge to x = 6, then to the outflow at x = 16). The
upper and lower wake blocks share the wake cut's curves, so its nodes are
shared and the mesh is conforming. Every wall-normal (j) line has the same
node count and a first cell of `--first` (default 1e-5 chord), also
normal to the wake cut: the wake cells far downstream are about 1e-5 high
and 1.4 chord long (aspect ratio about 1.4e5). The outer boundary is a
semicircle of radius 15 about the trailing edge, two straight lines to x = 16
and the outflow line.

`--blunt T` cuts the section where it is T thick and scales it back to
chord 1 (as rans_blunt.py): a flat trailing-edge base of thickness T. The
base gets its own blocks: a strip of 16 cells across, leaving the base
(first cell `--first` normal to it), narrowing linearly to 16 x `--first`
at x = 6 and running at that width to the outflow; the upper and lower
wake blocks sit on its edges.

`--ni` counts the nodes of one i-line around the C (lower wake, lower
surface, upper surface, upper wake: the trailing edge's nodes once for a
sharp trailing edge), `--nj` the nodes of a j-line from the wall to the
outer boundary. The split between the wake and the airfoil follows from
the spacings (leading edge 0.15/m, trailing edge 0.25/m with m cells a
surface; wake cells growing from the trailing edge's to 1.4 chord).

Groups: `airfoil` (the wall, with the base when blunt), `farfield` (the
whole outer boundary, outflow included), `fluid`.

Usage: python3 cgrid.py [--ni NI] [--nj NJ] [--first H] [--blunt T] OUT.msh
  cgrid-113x33.msh:        --ni 113 --nj 33
  cgrid-257x65.msh:        --ni 257 --nj 65
  cgrid-blunt-257x65.msh:  --ni 257 --nj 65 --blunt 0.003
"""

import argparse
import math

import gmsh

import naca
import rans_blunt
import structured as st

R = 15.0            # radius of the C about the trailing edge
X_SPLIT = 0.3       # surface station between the nose and aft blocks
X_NEAR = 6.0        # end of the near-wake blocks
X_OUT = 16.0        # outflow
FAR_CELLS = 7       # uniform wake cells from X_NEAR to X_OUT (1.43 chord)
BASE_CELLS = 16     # cells across a blunt trailing-edge base
BASE_BUMP = 0.05    # Gmsh "Bump": base cells about 10x smaller at the corners


def near_cells(first, target):
    """Cells of the near wake (length X_NEAR - 1) growing from `first` whose
    last cell is closest to `target`."""
    return min(range(4, 200),
               key=lambda n: abs(math.log(st.last(first, X_NEAR - 1, n) / target)))


def split(cells, d_le, d_te, len_nose, len_aft):
    """Cells of the nose block (the rest go to the aft block) such that the
    two progressions (from the leading edge, from the trailing edge) meet
    with the closest cell sizes at X_SPLIT."""
    return min(range(3, cells - 2),
               key=lambda n: abs(math.log(st.last(d_le, len_nose, n)
                                          / st.last(d_te, len_aft, cells - n))))


def build(ni, nj, first, blunt, out):
    gmsh.initialize(["-noenv"])
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("cgrid")
    geo = gmsh.model.geo

    if blunt > 0:
        upper, _ = rans_blunt.blunt_section("0012", 2000, blunt)
    else:
        upper, _ = naca.section("0012", 2000)
    k1 = min(range(len(upper)), key=lambda k: abs(upper[k][0] - X_SPLIT))
    nose = st.resample(upper[:k1 + 1], 120)
    aft = st.resample(upper[k1:], 150)
    len_nose, len_aft = st.length(nose), st.length(aft)
    y_te = upper[-1][1]                  # half the base (0 when sharp)
    strip = BASE_CELLS * first / 2       # half the strip downstream of X_NEAR

    # The i-direction: wake cells per branch, then the surface's share.
    far = (X_OUT - X_NEAR) / FAR_CELLS
    trial = 0.25 / ((ni - 1) / 2 - 30)
    for _ in range(5):                   # the spacings depend on the split
        wake0 = first if blunt > 0 else trial
        n_near = near_cells(wake0, far)
        surface = (ni - 1 - 2 * (n_near + FAR_CELLS)) // 2
        trial = 0.25 / surface
    d_le, d_te = 0.15 / surface, 0.25 / surface
    n_nose = split(surface, d_le, d_te, len_nose, len_aft)
    n_aft = surface - n_nose

    centre = geo.addPoint(1, 0, 0)
    le = geo.addPoint(0, 0, 0)
    o_le = geo.addPoint(1 - R, 0, 0)
    j_le = geo.addLine(le, o_le)
    st.progression(j_le, nj, first, R - 1)
    if blunt == 0:
        te = centre
        w_near = geo.addPoint(X_NEAR, 0, 0)
        w_out = geo.addPoint(X_OUT, 0, 0)
        cut_near = geo.addLine(te, w_near)
        cut_far = geo.addLine(w_near, w_out)
        wake_ratio = st.ratio(wake0, X_NEAR - 1, n_near)
        geo.mesh.setTransfiniteCurve(cut_near, n_near + 1, "Progression", wake_ratio)
        geo.mesh.setTransfiniteCurve(cut_far, FAR_CELLS + 1)
    wall, outer, surfaces = [], [], []

    def half(sign):
        """The four blocks of the upper (sign 1) or lower (-1) half; returns
        the points and curves the base strip needs when blunt."""
        pts = [geo.addPoint(x, sign * y, 0) for x, y in nose[1:-1]]
        p1 = geo.addPoint(nose[-1][0], sign * nose[-1][1], 0)
        s_nose = geo.addSpline([le] + pts + [p1])
        if blunt == 0:
            te_h = te
        else:
            te_h = geo.addPoint(1, sign * y_te, 0)
        pts = [geo.addPoint(x, sign * y, 0) for x, y in reversed(aft[1:-1])]
        s_aft = geo.addSpline([te_h] + pts + [p1])          # from the trailing edge
        wall.extend([s_nose, s_aft])
        st.progression(s_nose, n_nose + 1, d_le, len_nose)
        st.progression(s_aft, n_aft + 1, d_te, len_aft)

        x1 = nose[-1][0]
        o1 = geo.addPoint(x1, sign * math.sqrt(R**2 - (1 - x1) ** 2), 0)
        o_te = geo.addPoint(1, sign * R, 0)
        o_near = geo.addPoint(X_NEAR, sign * R, 0)
        o_out = geo.addPoint(X_OUT, sign * R, 0)
        arc_nose = geo.addCircleArc(o_le, centre, o1)
        arc_aft = geo.addCircleArc(o1, centre, o_te)
        top_near = geo.addLine(o_te, o_near)
        top_far = geo.addLine(o_near, o_out)
        geo.mesh.setTransfiniteCurve(arc_nose, n_nose + 1)
        geo.mesh.setTransfiniteCurve(arc_aft, n_aft + 1)
        geo.mesh.setTransfiniteCurve(top_near, n_near + 1, "Progression",
                                     st.ratio(wake0, X_NEAR - 1, n_near))
        geo.mesh.setTransfiniteCurve(top_far, FAR_CELLS + 1)

        if blunt == 0:
            w_n, w_o, c_near, c_far = w_near, w_out, cut_near, cut_far
            y_n = y_o = 0.0
        else:
            # The strip's edge: straight from the base's corner, narrowing to `strip`.
            w_n = geo.addPoint(X_NEAR, sign * strip, 0)
            w_o = geo.addPoint(X_OUT, sign * strip, 0)
            c_near = geo.addLine(te_h, w_n)
            geo.mesh.setTransfiniteCurve(c_near, n_near + 1, "Progression",
                                         st.ratio(wake0, math.dist((1, y_te), (X_NEAR, strip)), n_near))
            c_far = geo.addLine(w_n, w_o)
            geo.mesh.setTransfiniteCurve(c_far, FAR_CELLS + 1)
            y_n = y_o = strip

        j1 = geo.addLine(p1, o1)
        j_te = geo.addLine(te_h, o_te)
        j_near = geo.addLine(w_n, o_near)
        j_out = geo.addLine(w_o, o_out)
        st.progression(j1, nj, first, math.dist(nose[-1], (x1, math.sqrt(R**2 - (1 - x1) ** 2))))
        st.progression(j_te, nj, first, R - y_te)
        st.progression(j_near, nj, first, R - y_n)
        st.progression(j_out, nj, first, R - y_o)
        outer.extend([arc_nose, arc_aft, top_near, top_far, j_out])

        loops = [
            ([s_nose, j1, -arc_nose, -j_le], [le, p1, o1, o_le]),
            ([-s_aft, j_te, -arc_aft, -j1], [p1, te_h, o_te, o1]),
            ([c_near, j_near, -top_near, -j_te], [te_h, w_n, o_near, o_te]),
            ([c_far, j_out, -top_far, -j_near], [w_n, w_o, o_out, o_near]),
        ]
        for curves, corners in loops:
            if sign < 0:            # mirrored: reverse the loop to keep it counter-clockwise
                curves = [-c for c in reversed(curves)]
                corners = list(reversed(corners))
            surfaces.append(st.block(curves, corners))
        return te_h, w_n, w_o, c_near, c_far

    te_u, wn_u, wo_u, cn_u, cf_u = half(1)
    te_l, wn_l, wo_l, cn_l, cf_l = half(-1)
    if blunt > 0:
        base = geo.addLine(te_u, te_l)
        across = geo.addLine(wn_l, wn_u)
        out_strip = geo.addLine(wo_l, wo_u)
        geo.mesh.setTransfiniteCurve(base, BASE_CELLS + 1, "Bump", BASE_BUMP)
        geo.mesh.setTransfiniteCurve(across, BASE_CELLS + 1)
        geo.mesh.setTransfiniteCurve(out_strip, BASE_CELLS + 1)
        surfaces.append(st.block([cn_l, across, -cn_u, base], [te_l, wn_l, wn_u, te_u]))
        surfaces.append(st.block([cf_l, out_strip, -cf_u, -across], [wn_l, wo_l, wo_u, wn_u]))
        wall.append(base)
        outer.append(out_strip)

    print(f"i: {n_near + FAR_CELLS} wake cells a branch, {n_nose} + {n_aft} cells a surface; "
          f"j: {nj} nodes")
    st.write(out, wall, outer, surfaces)


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--ni", type=int, default=257)
    ap.add_argument("--nj", type=int, default=65)
    ap.add_argument("--first", type=float, default=1e-5)
    ap.add_argument("--blunt", type=float, default=0.0)
    ap.add_argument("out")
    a = ap.parse_args()
    build(a.ni, a.nj, a.first, a.blunt, a.out)
