"""NACA four-digit sections, shared by the airfoil, three-element and wing scripts.

The thickness uses the closed-trailing-edge coefficient -0.1036 (instead of
-0.1015), so that the upper and lower surfaces meet at one point.
"""

import math


def section(code, n):
    """Points of NACA `code` (e.g. "0012", "4412") with chord 1 from (0, 0) to
    (1, 0): the upper surface from the trailing edge to the leading edge, then
    the lower surface back, `n` cosine-spaced stations per surface, the
    trailing edge not repeated. Returns (upper, lower) lists of (x, y), both
    running from the leading edge to the trailing edge."""
    m = int(code[0]) / 100
    p = int(code[1]) / 10
    t = int(code[2:]) / 100
    upper, lower = [], []
    for k in range(n + 1):
        x = 0.5 * (1 - math.cos(math.pi * k / n))
        yt = 5 * t * (0.2969 * math.sqrt(x) - 0.1260 * x - 0.3516 * x**2
                      + 0.2843 * x**3 - 0.1036 * x**4)
        if m == 0:
            yc, dyc = 0.0, 0.0
        elif x < p:
            yc = m / p**2 * (2 * p * x - x**2)
            dyc = 2 * m / p**2 * (p - x)
        else:
            yc = m / (1 - p) ** 2 * (1 - 2 * p + 2 * p * x - x**2)
            dyc = 2 * m / (1 - p) ** 2 * (p - x)
        th = math.atan(dyc)
        upper.append((x - yt * math.sin(th), yc + yt * math.cos(th)))
        lower.append((x + yt * math.sin(th), yc - yt * math.cos(th)))
    return upper, lower


def placed(code, n, chord, angle_deg, origin):
    """The section scaled to `chord`, turned clockwise by `angle_deg` about
    its leading edge (positive: trailing edge down, as a deflected flap) and
    moved so that its leading edge is at `origin`."""
    a = math.radians(angle_deg)
    c, s = math.cos(a), math.sin(a)

    def tr(p):
        x, y = chord * p[0], chord * p[1]
        return (origin[0] + c * x + s * y, origin[1] - s * x + c * y)

    upper, lower = section(code, n)
    return [tr(p) for p in upper], [tr(p) for p in lower]


def add_curve_loop(occ, upper, lower, size):
    """A closed loop of two splines (upper and lower surface) through the
    points, joined at the leading and trailing edges. Returns the loop tag and
    the two curve tags."""
    pts_u = [occ.addPoint(x, y, 0, size) for x, y in upper]
    pts_l = [pts_u[0]] + [occ.addPoint(x, y, 0, size) for x, y in lower[1:-1]] + [pts_u[-1]]
    cu = occ.addSpline(pts_u)
    cl = occ.addSpline(pts_l)
    return occ.addCurveLoop([cu, -cl]), [cu, cl]
