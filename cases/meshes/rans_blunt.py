"""What the RANS-type mesh scripts share: NACA sections with a blunt
trailing edge, their Gmsh curves, and the boundary-layer field.

A blunt section is the closed-trailing-edge NACA section of naca.py cut at
the chord station x_c where its thickness is `te` x_c, then scaled by 1/x_c:
chord 1 again, and a flat trailing edge of thickness `te` (a fraction of the
chord) with two sharp corners.
"""

import math

import gmsh

import naca


def _interp(points, x):
    """y on the polyline `points` (x increasing) at abscissa x."""
    for (x0, y0), (x1, y1) in zip(points, points[1:]):
        if x0 <= x <= x1:
            return y0 + (y1 - y0) * (x - x0) / (x1 - x0)
    raise ValueError(f"x = {x} outside the section")


def blunt_section(code, n, te):
    """NACA `code` with chord 1 and a flat trailing edge of thickness `te`.
    Returns (upper, lower), both from the leading edge (0, 0) to the
    trailing-edge corners (1, y_upper) and (1, y_lower)."""
    upper, lower = naca.section(code, n)
    lo, hi = 0.5, 1.0
    for _ in range(60):
        x = 0.5 * (lo + hi)
        if _interp(upper, x) - _interp(lower, x) > te * x:
            lo = x
        else:
            hi = x
    xc = lo

    def cut(points):
        kept = [p for p in points if p[0] < xc]
        kept.append((xc, _interp(points, xc)))
        return [(px / xc, py / xc) for px, py in kept]

    return cut(upper), cut(lower)


def placed(code, n, te, chord, angle_deg, origin):
    """The blunt section scaled to `chord`, turned clockwise by `angle_deg`
    about its leading edge and moved so that the leading edge is at `origin`
    (the placement of naca.placed)."""
    a = math.radians(angle_deg)
    c, s = math.cos(a), math.sin(a)

    def tr(p):
        x, y = chord * p[0], chord * p[1]
        return (origin[0] + c * x + s * y, origin[1] - s * x + c * y)

    upper, lower = blunt_section(code, n, te)
    return [tr(p) for p in upper], [tr(p) for p in lower]


def add_loop(occ, upper, lower):
    """A closed loop: one spline from the upper trailing-edge corner over the
    leading edge to the lower corner, and the straight trailing edge.
    Returns (loop tag, [spline, trailing edge], [upper corner, lower corner])."""
    path = list(reversed(upper)) + lower[1:]
    pts = [occ.addPoint(x, y, 0) for x, y in path]
    wall = occ.addSpline(pts)
    te = occ.addLine(pts[-1], pts[0])
    return occ.addCurveLoop([wall, te]), [wall, te], [pts[0], pts[-1]]


def layers(first, ratio, thickness):
    """Number of cells of a geometric layer (first cell `first`, growth
    `ratio`) whose total height first reaches `thickness`."""
    return math.ceil(math.log(1 + thickness * (ratio - 1) / first) / math.log(ratio))


def boundary_layer(curves, fan_points, first, ratio, thickness, fan_cells):
    """A 2D boundary-layer field on `curves`: first cell `first`, growth
    `ratio`, total `thickness`, quadrilaterals, a fan of `fan_cells` cells at
    each of `fan_points` (sharp corners)."""
    f = gmsh.model.mesh.field
    bl = f.add("BoundaryLayer")
    f.setNumbers(bl, "CurvesList", curves)
    f.setNumber(bl, "Size", first)
    f.setNumber(bl, "Ratio", ratio)
    f.setNumber(bl, "Thickness", thickness)
    f.setNumber(bl, "Quads", 1)
    f.setNumbers(bl, "FanPointsList", fan_points)
    f.setNumbers(bl, "FanPointsSizesList", [fan_cells] * len(fan_points))
    f.setAsBoundaryLayer(bl)
    return bl
