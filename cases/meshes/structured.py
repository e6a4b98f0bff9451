"""What the structured (transfinite) mesh scripts share: node distributions
along a curve (a geometric progression with a given first cell), a polyline
length, and transfinite quadrilateral blocks in the Gmsh geo kernel.

Gmsh's "Progression" law with n nodes and ratio r makes cells proportional
to 1, r, r^2, ... from the curve's start, by arc length.
"""

import math

import gmsh


def length(points):
    """Length of the polyline through `points` (x, y)."""
    return sum(math.dist(a, b) for a, b in zip(points, points[1:]))


def resample(points, n):
    """`n` points evenly spaced by arc length along the polyline `points`
    (the first and last kept): Gmsh splines through them are parametrised
    nearly by arc length, which the progressions below assume."""
    d = [0.0]
    for a, b in zip(points, points[1:]):
        d.append(d[-1] + math.dist(a, b))
    out, k = [], 0
    for i in range(n):
        s = d[-1] * i / (n - 1)
        while k < len(d) - 2 and d[k + 1] < s:
            k += 1
        t = (s - d[k]) / (d[k + 1] - d[k])
        a, b = points[k], points[k + 1]
        out.append((a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])))
    out[0], out[-1] = points[0], points[-1]
    return out


def ratio(first, total, cells):
    """Growth ratio r of `cells` cells whose first is `first` and whose sum is
    `total` (r = 1 when `first * cells` is `total`; r < 1 when larger)."""
    if abs(first * cells - total) <= 1e-12 * total:
        return 1.0

    def s(r):
        return first * cells if r == 1.0 else first * (r**cells - 1) / (r - 1)

    lo, hi = (1.0, 2.0) if first * cells < total else (0.5, 1.0)
    while s(hi) < total and first * cells < total:
        hi *= 2
    while s(lo) > total and first * cells > total:
        lo /= 2
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if s(mid) < total:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def last(first, total, cells):
    """The last cell of that progression."""
    return first * ratio(first, total, cells) ** (cells - 1)


def progression(curve, nodes, first, total):
    """Discretise `curve` (length `total`) with `nodes` nodes, the first cell
    (at the curve's start) `first`, growing geometrically."""
    gmsh.model.geo.mesh.setTransfiniteCurve(curve, nodes, "Progression",
                                            ratio(first, total, nodes - 1))


def block(curves, corners):
    """A transfinite, recombined (quadrilateral) block bounded by the closed
    loop of signed curve tags `curves`, with the four `corners` (point tags).
    Returns the surface tag."""
    geo = gmsh.model.geo
    s = geo.addPlaneSurface([geo.addCurveLoop(curves)])
    geo.mesh.setTransfiniteSurface(s, "Left", corners)
    geo.mesh.setRecombine(2, s)
    return s


def write(out, wall, outer, surfaces):
    """Names the groups `airfoil` (curves `wall`), `farfield` (`outer`) and
    `fluid` (`surfaces`), meshes in 2D, writes `out` (MSH 4.1 binary) and
    reports the fluid's counts."""
    gmsh.model.geo.synchronize()
    gmsh.model.addPhysicalGroup(1, wall, name="airfoil")
    gmsh.model.addPhysicalGroup(1, outer, name="farfield")
    fluid_tag = gmsh.model.addPhysicalGroup(2, surfaces, name="fluid")
    gmsh.model.mesh.generate(2)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.option.setNumber("Mesh.Binary", 1)
    nodes = len(gmsh.model.mesh.getNodesForPhysicalGroup(2, fluid_tag)[0])
    cells = sum(len(t) for t in gmsh.model.mesh.getElements(2)[1])
    gmsh.write(out)
    gmsh.finalize()
    print(f"{out}: {nodes} nodes, {cells} quadrilaterals")
