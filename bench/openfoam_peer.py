#!/usr/bin/env python3
"""OpenFOAM's mesh motion on verbss's own test meshes, side by side with verbss.

    python3 bench/openfoam_peer.py sphere-toward-wall
    python3 bench/openfoam_peer.py sphere-diagonal cgrid-pitch --variants laplacian,rigid
    python3 bench/openfoam_peer.py --list        (and --help for the options)

Needs moveDynamicMesh and gmshToFoam on the PATH (Debian: `apt-get install
openfoam`, v1912; WM_PROJECT_DIR defaults to /usr/share/openfoam) and
target/release/verbss (`cargo build --release -p verbss-cli`; --verbss PATH).

Cases (the motions of cases/robust/*.toml, one time unit a step):
  sphere-toward-wall  cases/meshes/sphere-cube.msh (tetrahedra; sphere of radius
                      5 in a +-25 cube) moved (-16, 0, 0) in 16 steps (paper 5.1)
  sphere-diagonal     the same, moved (8, 4, 0) in 20 steps
  cgrid-pitch         cases/meshes/cgrid-113x33.msh (2D, extruded one cell 0.1
                      thick, front and back `empty`) pitched 60 degrees about
                      (0.25, 0) in 1-degree steps
--mesh M runs a case on another mesh with the same groups (e.g. a finer
`python3 cases/meshes/sphere_cube.py --size H M`).

The mesh goes to gmshToFoam as MSH 2.2; moveDynamicMesh writes every step.
OpenFOAM variants (--variants):
  laplacian  displacementLaplacian, diffusivity inverseDistance (body); the
             body's pointDisplacement is the exact rigid motion
             (solidBodyMotionDisplacement); PCG (DIC) to an absolute 1e-20
             (--tolerance). The inverse-distance coefficients of the faces on
             the body are huge and the residual OpenFOAM normalises by them
             meets the usual 1e-6..1e-8 after one iteration, far from the
             solution (on sphere-toward-wall GAMG to 1e-8 leaves nodes up to
             0.9 units from the converged answer).
  rigid      rigidBodyMotion: the mesh moves with the body within --inner and
             is blended (cosine) to rest at --outer (defaults per case). The
             body gets a prescribed constant joint velocity: `test` mode (no
             fluid forces), no gravity or restraints, initial qDot = the motion
             per step (a revolute Rz joint at the centre, or Px Py Pz).
verbss (--verbss-methods): `default` runs a copy of the case file as it is,
another name a copy with [solver] method = NAME.

A step counts as inverted when moveDynamicMesh's own check after it
(polyMesh::checkMesh) reports a zero or negative cell volume or wrongly
oriented face pyramids; as a cross-check every step's tetrahedron volumes or
2D cell areas (signed) are compared with step 0's. Min quality: `verbss
quality` of each step before the first inversion. s/step: OpenFOAM, the
differences of ExecutionTime (CPU, mesh check included; step 1, which also
reads the mesh, left out); verbss, report.json's per-step seconds (wall, one
thread). Process CPU s/step: the whole process (user + system) over its steps.
"""
import argparse
import json
import os
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import meshio
import numpy as np

ROOT = Path(__file__).resolve().parent.parent
CASES = {
    "sphere-toward-wall": dict(
        mesh="cases/meshes/sphere-cube.msh", body="sphere", steps=16,
        translate=(-16.0, 0.0, 0.0), toml="cases/robust/sphere-box-toward-wall.toml",
        inner=1.0, outer=15.0),
    "sphere-diagonal": dict(
        mesh="cases/meshes/sphere-cube.msh", body="sphere", steps=20,
        translate=(8.0, 4.0, 0.0), toml="cases/robust/sphere-box-diagonal.toml",
        inner=1.0, outer=15.0),
    "cgrid-pitch": dict(
        mesh="cases/meshes/cgrid-113x33.msh", body="airfoil", steps=60,
        rotate=((0.25, 0.0, 0.0), 60.0), toml="cases/robust/cgrid-113x33-pitch.toml",
        inner=0.3, outer=3.0),
}
THICKNESS = 0.1  # of the extruded 2D meshes
SOLID = {"tetra", "hexahedron", "wedge"}
GMSH_TYPE = {"line": 1, "triangle": 2, "quad": 3, "tetra": 4, "hexahedron": 5, "wedge": 6}
FOAM_HEADER = "FoamFile { version 2.0; format ascii; class %s; object %s; }\n"


def foam_env(cwd):
    env = dict(os.environ, PWD=str(cwd))
    env.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
    return env


def run(cmd, cwd=None, env=None, check=True):
    r = subprocess.run(cmd, cwd=cwd, env=env, text=True, capture_output=True)
    if check and r.returncode != 0:
        raise RuntimeError(f"{' '.join(map(str, cmd))} failed:\n{r.stdout[-3000:]}{r.stderr[-3000:]}")
    return r


# ---------------------------------------------------------------- the mesh

def read_mesh(path):
    """(points, dim, [(type, nodes, physical tag)], {name: tag})."""
    m = meshio.read(path)
    names = {str(n): int(v[0]) for n, v in m.field_data.items()}
    dim = 3 if any(c.type in SOLID for c in m.cells) else 2
    cells = [(c.type, c.data, tags) for c, tags in zip(m.cells, m.cell_data["gmsh:physical"])]
    return m.points, dim, cells, names


def extrude(points, cells, names):
    """A 2D mesh (z = 0) extruded THICKNESS in z: quads to hexahedra,
    triangles to prisms, lines to boundary quads; front and back become the
    group frontAndBack. Node i of the 2D mesh is nodes i and i + n here."""
    n = len(points)
    top = points + [0.0, 0.0, THICKNESS]
    out, caps = [], []
    front = max(names.values()) + 1
    for kind, nodes, tags in cells:
        if kind == "line":
            out.append(("quad", np.c_[nodes, nodes[:, ::-1] + n], tags))
            continue
        # orient every face counter-clockwise seen from +z
        p = points[nodes][:, :3, :2]
        cross = (p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1]) \
            - (p[:, 1, 1] - p[:, 0, 1]) * (p[:, 2, 0] - p[:, 0, 0])
        nodes = np.where(cross[:, None] < 0, nodes[:, ::-1], nodes)
        out.append(({"quad": "hexahedron", "triangle": "wedge"}[kind], np.c_[nodes, nodes + n], tags))
        caps += [(kind, nodes[:, ::-1], np.full(len(nodes), front)),
                 (kind, nodes + n, np.full(len(nodes), front))]
    return np.vstack([points, top]), out + caps, dict(names, frontAndBack=front)


def write_msh22(path, points, cells, names):
    """Gmsh MSH 2.2 (ASCII), which gmshToFoam reads: one physical group per
    element (elementary tag = physical tag)."""
    lines = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat", "$PhysicalNames", str(len(names))]
    for name, tag in names.items():
        used = [k for k, _, t in cells if len(t) and t[0] == tag]
        lines.append(f'{3 if used and used[0] in SOLID else 2} {tag} "{name}"')
    lines += ["$EndPhysicalNames", "$Nodes", str(len(points))]
    lines += [f"{i + 1} {x:.17g} {y:.17g} {z:.17g}" for i, (x, y, z) in enumerate(points)]
    lines += ["$EndNodes", "$Elements"]
    body, k = [], 0
    for kind, nodes, tags in cells:
        for row, tag in zip(nodes, tags):
            k += 1
            body.append(f"{k} {GMSH_TYPE[kind]} 2 {tag} {tag} " + " ".join(str(v + 1) for v in row))
    lines += [str(k)] + body + ["$EndElements"]
    Path(path).write_text("\n".join(lines) + "\n")


def read_foam_points(path):
    """An ASCII polyMesh/points file."""
    text = Path(path).read_text()
    start = text.index("(", text.index("}"))
    vals = re.findall(r"\(([^()]*)\)", text[start + 1:])
    return np.array([[float(v) for v in s.split()] for s in vals])


def signed_measures(points, cells, dim):
    """Signed volume of every tetrahedron, signed area (shoelace) of every
    triangle and quadrilateral of the original mesh on `points`."""
    out = []
    for kind, c, _ in cells:
        p = points[c]
        if kind == "tetra":
            out.append(np.einsum("ij,ij->i", np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]),
                                 p[:, 3] - p[:, 0]))
        elif dim == 2 and kind in ("triangle", "quad"):
            q = np.roll(p, -1, axis=1)
            out.append((p[:, :, 0] * q[:, :, 1] - q[:, :, 0] * p[:, :, 1]).sum(1))
    return np.concatenate(out)


# -------------------------------------------------------------- the case

def motion_velocity(case):
    """The body's motion per time unit (one step): ('linear', v) or
    ('rotating', origin, omega in rad)."""
    n = case["steps"]
    if "translate" in case:
        return ("linear", [d / n for d in case["translate"]])
    origin, degrees = case["rotate"]
    return ("rotating", origin, np.radians(degrees) / n)


def vec(v):
    return "(" + " ".join(f"{x:.17g}" for x in v) + ")"


def foam_dicts(case, variant, patches, tolerance, diffusivity=None, slip=(), constraints=None):
    """The case's dictionaries; `diffusivity` replaces laplacian's
    `inverseDistance (body)`, the patches in `slip` slip instead of
    staying fixed, and `constraints` ({patch: type}, e.g. wedge) are
    constraint patches besides frontAndBack."""
    body, steps = case["body"], case["steps"]
    constraints = dict({"frontAndBack": "empty"} if "frontAndBack" in patches else {},
                       **(constraints or {}))
    others = [p for p in patches if p != body and p not in constraints]
    motion = motion_velocity(case)
    files = {"system/controlDict": ("dictionary", f"""
application moveDynamicMesh; startFrom startTime; startTime 0; stopAt endTime;
endTime {steps}; deltaT 1; writeControl timeStep; writeInterval 1; purgeWrite 0;
writeFormat ascii; writePrecision 17; writeCompression off; timeFormat general;
timePrecision 6; runTimeModifiable false;
"""), "system/fvSchemes": ("dictionary", """
ddtSchemes { default Euler; } gradSchemes { default Gauss linear; }
divSchemes { default none; } laplacianSchemes { default Gauss linear corrected; }
interpolationSchemes { default linear; } snGradSchemes { default corrected; }
"""), "system/fvSolution": ("dictionary", f"""
solvers {{ "cellDisplacement.*" {{ solver PCG; preconditioner DIC; tolerance {tolerance:g};
    relTol 0; maxIter 5000; }} }}
""")}
    empty = " ".join(f"{p} {{ type {t}; }}" for p, t in constraints.items())
    fixed = " ".join(f"{p} {{ type slip; }}" if p in slip else
                     f"{p} {{ type fixedValue; value uniform (0 0 0); }}" for p in others)
    if variant == "laplacian":
        if motion[0] == "linear":
            fn = f"linearMotion; linearMotionCoeffs {{ velocity {vec(motion[1])}; }}"
        else:
            fn = (f"rotatingMotion; rotatingMotionCoeffs {{ origin {vec(motion[1])}; "
                  f"axis (0 0 1); omega constant {motion[2]:.17g}; }}")
        files["constant/dynamicMeshDict"] = ("dictionary", f"""
dynamicFvMesh dynamicMotionSolverFvMesh; motionSolverLibs (fvMotionSolvers);
motionSolver displacementLaplacian;
displacementLaplacianCoeffs {{ diffusivity {diffusivity or f"inverseDistance ({body})"}; }}
""")
        files["0/pointDisplacement"] = ("pointVectorField", f"""
dimensions [0 1 0 0 0 0 0]; internalField uniform (0 0 0);
boundaryField {{ {body} {{ type solidBodyMotionDisplacement; solidBodyMotionFunction {fn}
value uniform (0 0 0); }} {fixed} {empty} }}
""")
        cell = " ".join(f"{p} {{ type slip; }}" if p in slip else
                        f"{p} {{ type cellMotion; value uniform (0 0 0); }}" for p in [body] + others)
        files["0/cellDisplacement"] = ("volVectorField", f"""
dimensions [0 1 0 0 0 0 0]; internalField uniform (0 0 0);
boundaryField {{ {cell} {empty} }}
""")
    else:
        if motion[0] == "linear":
            joint, origin, qdot = "composite; joints ({type Px;} {type Py;} {type Pz;})", \
                (0, 0, 0), motion[1]
        else:
            joint, origin, qdot = "Rz", motion[1], [motion[2]]
        files["constant/dynamicMeshDict"] = ("dictionary", f"""
dynamicFvMesh dynamicMotionSolverFvMesh; motionSolverLibs (rigidBodyMeshMotion);
motionSolver rigidBodyMotion;
rigidBodyMotionCoeffs
{{
    report on; test yes; nIter 1; solver {{ type symplectic; }}
    qDot ({" ".join(f"{v:.17g}" for v in qdot)});
    bodies {{ {body} {{ type rigidBody; parent root; mass 1; centreOfMass (0 0 0);
        inertia (1 0 0 1 0 1); transform (1 0 0 0 1 0 0 0 1) {vec(origin)};
        joint {{ type {joint}; }} patches ({body});
        innerDistance {case['inner']}; outerDistance {case['outer']}; }} }}
}}
""")
        files["0/pointDisplacement"] = ("pointVectorField", f"""
dimensions [0 1 0 0 0 0 0]; internalField uniform (0 0 0);
boundaryField {{ {body} {{ type calculated; value uniform (0 0 0); }} {fixed} {empty} }}
""")
    return files


def build_case(case, variant, work, tolerance):
    points, dim, cells, names = read_mesh(ROOT / case["mesh"])
    if dim == 2:
        points, cells, names = extrude(points, cells, names)
    patches = [n for n, tag in names.items()
               if any(k not in SOLID and len(t) and t[0] == tag for k, _, t in cells)]
    for d in ("system", "constant", "0"):
        (work / d).mkdir(parents=True, exist_ok=True)
    for name, (cls, body) in foam_dicts(case, variant, patches, tolerance).items():
        (work / name).write_text(FOAM_HEADER % (cls, Path(name).name) + body)
    msh = work / "mesh.msh"
    write_msh22(msh, points, cells, names)
    log = run(["gmshToFoam", str(msh)], cwd=work, env=foam_env(work))
    (work / "log.gmshToFoam").write_text(log.stdout + log.stderr)
    if "frontAndBack" in patches:
        boundary = work / "constant/polyMesh/boundary"
        boundary.write_text(re.sub(r"(frontAndBack\s*\{\s*type\s+)\w+", r"\1empty",
                                   boundary.read_text()))
    foam_points = read_foam_points(work / "constant/polyMesh/points")
    if foam_points.shape != points.shape or np.abs(foam_points - points).max() > 1e-9:
        raise RuntimeError("gmshToFoam reordered the points; cannot map them back")
    return points, dim, cells


def run_foam(case, variant, work, verbss, tolerance):
    points, dim, cells = build_case(case, variant, work, tolerance)
    t0, c0 = time.monotonic(), child_cpu()
    r = run(["moveDynamicMesh"], cwd=work, env=foam_env(work), check=False)
    wall, cpu_all = time.monotonic() - t0, child_cpu() - c0
    (work / "log.moveDynamicMesh").write_text(r.stdout + r.stderr)
    steps = foam_steps(r.stdout)
    # the written points on the original cells: sign flips against step 0,
    # and verbss quality (which measures each cell against its own orientation,
    # so only for steps without a flip)
    flat = read_mesh(ROOT / case["mesh"])[2] if dim == 2 else cells
    n = len(points) // (2 if dim == 2 else 1)
    sign0 = np.sign(signed_measures(points[:n], flat, dim))
    for s in steps:
        moved = read_foam_points(work / f"{s['step']:g}" / "polyMesh" / "points")[:n]
        s["sign_flips"] = int((np.sign(signed_measures(moved, flat, dim)) != sign0).sum())
        if verbss and not s["sign_flips"] and not s["openfoam_failed_checks"]:
            meshio.Mesh(moved, [(k, c) for k, c, _ in flat]).write(work / "step.vtu")
            q = json.loads(run([verbss, "quality", str(work / "step.vtu"), "--json"]).stdout)
            s["verbss_min_quality"] = q["quality"]["min"]
    first_bad = next((s["step"] for s in steps if s["openfoam_failed_checks"]), None)
    first_flip = next((s["step"] for s in steps if s["sign_flips"]), None)
    reached = min([x - 1 for x in (first_bad, first_flip) if x] or [len(steps)])
    valid = [s for s in steps if s["step"] <= reached]
    later = [s["cpu_s"] for s in steps[1:]] or [s["cpu_s"] for s in steps]
    if variant == "rigid":
        variant = f"rigid (inner {case['inner']:g}, outer {case['outer']:g})"
    return {"tool": "OpenFOAM v1912 moveDynamicMesh", "variant": variant,
            "steps_total": case["steps"], "steps_run": len(steps), "steps_reached": reached,
            "first_inverted_step": first_bad, "first_sign_flip_step": first_flip,
            "exit_code": r.returncode,
            "min_quality": min((s["verbss_min_quality"] for s in valid
                                if "verbss_min_quality" in s), default=None),
            "cpu_s_per_step": sum(later) / len(later) if later else None,
            "wall_s": wall, "process_cpu_s_per_step": cpu_all / max(len(steps), 1),
            "per_step": steps}


def foam_steps(log, unit=1.0):
    """Per step of a moveDynamicMesh log (time / `unit` = the step): CPU
    seconds, solver iterations and the failed mesh checks."""
    steps, last = [], 0.0
    for block in re.split(r"^Time = ", log, flags=re.M)[1:]:
        m = re.search(r"^ExecutionTime = ([\d.e+-]+) s", block, re.M)
        if not m:
            break
        t = float(block.split()[0])
        bad = [c for c in ("Zero or negative cell volume", "Error in face pyramids")
               if c in block]
        iters = sum(int(i) for i in re.findall(r"No Iterations (\d+)", block))
        steps.append({"step": int(round(t / unit)), "time": block.split()[0],
                      "cpu_s": float(m.group(1)) - last,
                      "solver_iterations": iters, "openfoam_failed_checks": bad})
        last = float(m.group(1))
    return steps


def child_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run_verbss(case, method, verbss, work):
    """`verbss run` on a copy of the case file with the mesh's full path (and
    with [solver] method = METHOD unless method is None: the default)."""
    text = re.sub(r"^mesh = .*$", f'mesh = "{(ROOT / case["mesh"]).as_posix()}"',
                  (ROOT / case["toml"]).read_text(), flags=re.M)
    toml = work / f"{Path(case['toml']).stem}-{method or 'default'}.toml"
    if method and re.search(r"^\[solver\]$", text, flags=re.M):
        text = re.sub(r"^\[solver\]$", f'[solver]\nmethod = "{method}"', text, count=1, flags=re.M)
    elif method:
        text += f'\n[solver]\nmethod = "{method}"\n'
    toml.write_text(text)
    out = work / f"verbss-{method or 'default'}"
    c0 = child_cpu()
    r = run([verbss, "run", str(toml), "--out", str(out), "--quiet"], check=False)
    cpu = child_cpu() - c0
    report = json.loads((out / "report.json").read_text())
    steps = [s for s in report["steps"] if s["step"] > 0]
    first_bad = next((s["step"] for s in steps if s["inverted"]), None)
    done = [s for s in steps if not s["inverted"]]
    reached = done[-1]["step"] if done else 0
    return {"tool": "verbss " + report["verbss"], "variant": method or "default",
            "settings": report["settings"], "outcome": report["outcome"],
            "exit_code": r.returncode, "steps_total": case["steps"],
            "steps_run": len(steps), "steps_reached": reached,
            "first_inverted_step": first_bad,
            "min_quality": min((s["min_quality"] for s in done), default=None),
            "s_per_step": sum(s["seconds"] for s in steps) / len(steps) if steps else None,
            "process_cpu_s_per_step": cpu / max(len(steps), 1)}


def fmt(x, spec):
    return "–" if x is None else format(x, spec)


def table(rows):
    out = ["| case | tool, settings | steps reached | first inverted step | min quality "
           "| s/step | process CPU s/step |", "|---|---|---|---|---|---|---|"]
    for r in rows:
        per_step = r.get("cpu_s_per_step", r.get("s_per_step"))
        out.append(f"| {r['case']}{' (' + Path(r['mesh']).name + ')' if r.get('mesh') else ''} | {r['tool']} {r['variant']} | {r['steps_reached']}/"
                   f"{r['steps_total']} | {fmt(r['first_inverted_step'], 'd')} | "
                   f"{fmt(r['min_quality'], '.4f')} | {fmt(per_step, '.4f')} | "
                   f"{fmt(r['process_cpu_s_per_step'], '.4f')} |")
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("cases", nargs="*", help=", ".join(CASES))
    ap.add_argument("--list", action="store_true")
    ap.add_argument("--variants", default="laplacian", help="laplacian,rigid")
    ap.add_argument("--verbss", default=str(ROOT / "target/release/verbss"))
    ap.add_argument("--verbss-methods", default="default,verbss",
                    help="verbss runs: default (the case file as it is) and/or methods")
    ap.add_argument("--no-verbss", action="store_true")
    ap.add_argument("--tolerance", type=float, default=1e-20,
                    help="cellDisplacement PCG tolerance (laplacian), default 1e-20")
    ap.add_argument("--inner", type=float, help="rigid's inner distance")
    ap.add_argument("--outer", type=float, help="rigid's outer distance")
    ap.add_argument("--mesh", help="another mesh for the cases (same groups)")
    ap.add_argument("--keep", help="keep the case directories in this folder")
    ap.add_argument("--json")
    a = ap.parse_args()
    if a.list or not a.cases:
        print("\n".join(f"{k}: {v['mesh']}, {v['steps']} steps" for k, v in CASES.items()))
        return
    unknown = [c for c in a.cases if c not in CASES]
    if unknown:
        sys.exit(f"unknown case(s) {unknown}; known: {', '.join(CASES)}")
    if not shutil.which("moveDynamicMesh"):
        sys.exit("moveDynamicMesh not found (Debian: apt-get install openfoam)")
    verbss = None if a.no_verbss else a.verbss
    if verbss and not Path(verbss).is_file():
        sys.exit(f"{verbss} not found: cargo build --release -p verbss-cli, or --no-verbss")
    top = Path(a.keep) if a.keep else Path(tempfile.mkdtemp(prefix="openfoam-peer-"))
    rows = []
    for name in a.cases:
        case = dict(CASES[name], **{k: v for k, v in
                                    (("inner", a.inner), ("outer", a.outer),
                                     ("mesh", a.mesh and str(Path(a.mesh).resolve())))
                                    if v is not None})
        for variant in a.variants.split(","):
            work = top / f"{name}-{variant}"
            shutil.rmtree(work, ignore_errors=True)
            r = run_foam(case, variant, work, verbss, a.tolerance)
            rows.append(dict(r, case=name, mesh=a.mesh))
            print(table(rows[-1:]).splitlines()[-1], file=sys.stderr)
        for method in (a.verbss_methods.split(",") if verbss else []):
            work = top / f"{name}-verbss"
            work.mkdir(parents=True, exist_ok=True)
            r = run_verbss(case, None if method == "default" else method, verbss, work)
            rows.append(dict(r, case=name, mesh=a.mesh))
            print(table(rows[-1:]).splitlines()[-1], file=sys.stderr)
    print(table(rows))
    if a.json:
        Path(a.json).write_text(json.dumps(rows, indent=1))
    if not a.keep:
        shutil.rmtree(top)


if __name__ == "__main__":
    main()
