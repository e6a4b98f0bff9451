"""What the scripts of cases/gaps share: their options (--json OUT, --verbss
PATH, --work DIR), verbss's four runs of a case and OpenFOAM's
displacementLaplacian runs on an OpenFOAM case folder, each as one row:

    case, mesh, nodes, run, steps_done, steps, min_quality, amplification,
    s_per_step, min_quality_per_step

`run` is "default", "verbss", "laplacian", "default --blend off" or
"OpenFOAM <solver> <diffusivity>". steps_done: the steps before the first
inverted one; min_quality: verbss's measure, the least over those steps;
min_quality_per_step: each of those steps' own (None where a step was not
measured); amplification: the largest per step (verbss: report.json's; OpenFOAM:
the largest step move of a point on no moving or fixed patch over the largest
of a moving patch's point); s_per_step: verbss's wall seconds (report.json),
OpenFOAM's CPU seconds (ExecutionTime; step 1, which reads the mesh, left out).
Import it from a script beside it (`sys.path` holds the script's folder).
"""

import argparse
import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent.parent
sys.path.insert(0, str(ROOT / "bench"))
import openfoam_peer as peer  # noqa: E402

VERBSS_RUNS = [("default", []), ("verbss", ["--method", "verbss"]),
               ("laplacian", ["--method", "laplacian"]),
               ("default --blend off", ["--blend", "off"])]
DIFFUSIVITIES = [("inverseDistance", "inverseDistance ({body})"),
                 ("quadratic inverseDistance", "quadratic inverseDistance ({body})"),
                 ("inverseVolume", "inverseVolume ({body})")]


def options(doc):
    """The parser every script takes: --json, --verbss, --work."""
    parser = argparse.ArgumentParser(description=doc.splitlines()[0])
    parser.add_argument("--json", help="write the rows here")
    parser.add_argument("--verbss", default=str(ROOT / "target/release/verbss"))
    parser.add_argument("--work", help="keep meshes and runs in this folder (default: a temporary one)")
    return parser


def write_json(path, rows):
    if path:
        Path(path).write_text(json.dumps(rows, indent=1))


def print_rows(rows):
    print("| case | mesh | nodes | run | steps | min quality | amplification | s/step |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['case']} | {r['mesh']} | {r['nodes']:,} | {r['run']} | "
              f"{r['steps_done']}/{r['steps']} | {fmt(r['min_quality'], '.4f')} | "
              f"{fmt(r['amplification'], '.3f')} | {fmt(r['s_per_step'], '.4f')} |")
    sys.stdout.flush()


def fmt(x, spec):
    return "–" if x is None else format(x, spec)


def row(case, mesh, nodes, run, steps, done, qualities, amplification, seconds):
    """One row; `qualities` the min quality of steps 1.. (None: not measured)."""
    measured = [q for q in qualities[:done] if q is not None]
    return {"case": case, "mesh": mesh, "nodes": nodes, "run": run, "steps_done": done,
            "steps": steps, "min_quality": min(measured, default=None),
            "amplification": amplification, "s_per_step": seconds,
            "min_quality_per_step": list(qualities[:done])}


def verbss_run(verbss, mesh, out, report, steps, motion, extra):
    """`verbss deform MESH -o OUT MOTION --steps N EXTRA` on one thread; the
    report's step records (step 0 left out)."""
    report.unlink(missing_ok=True)
    subprocess.run([verbss, "deform", str(mesh), "-o", str(out), *motion, "--steps", str(steps),
                    "--threads", "1", "--report", str(report), "--quiet", *extra],
                   capture_output=True, text=True)
    records = json.loads(report.read_text())["steps"] if report.exists() else []
    return [r for r in records if r["step"] > 0]


def verbss_rows(verbss, case, mesh_name, nodes, make_input, steps, motion, work, runs=VERBSS_RUNS):
    """verbss's runs of a case. `make_input(name)` gives (input, output) paths
    for one run (a fresh copy where the output goes into the input case)."""
    rows = []
    for run, extra in runs:
        slug = run.replace(" ", "").replace("-", "")
        mesh, out = make_input(slug)
        records = verbss_run(verbss, mesh, out, work / f"{slug}.json", steps, motion, extra)
        done = 0
        for r in records:
            if r["inverted"] or r["step"] != done + 1:
                break
            done += 1
        by_step = {r["step"]: r["min_quality"] for r in records}
        rows.append(row(case, mesh_name, nodes, run, steps, done,
                        [by_step.get(k) for k in range(1, steps + 1)],
                        max((r["amplification"] for r in records), default=None),
                        sum(r["seconds"] for r in records) / len(records) if records else None))
    return rows


def patches(case_dir):
    """{patch: (startFace, nFaces)} of constant/polyMesh/boundary."""
    text = (case_dir / "constant/polyMesh/boundary").read_text()
    out = {}
    for name, body in re.findall(r"^\s*(\w+)\s*\{([^}]*)\}", text, re.M):
        start = re.search(r"startFace\s+(\d+)", body)
        count = re.search(r"nFaces\s+(\d+)", body)
        if start and count:
            out[name] = (int(start.group(1)), int(count.group(1)))
    return out


def patch_points(case_dir, names):
    """The points of the named patches (an ASCII faces file)."""
    text = (case_dir / "constant/polyMesh/faces").read_text()
    text = text[text.index("(", text.index("}")) + 1:]
    faces = re.findall(r"\d+\(([^()]*)\)", text)
    ranges = patches(case_dir)
    found = set()
    for name in names:
        start, count = ranges[name]
        for f in faces[start:start + count]:
            found.update(int(v) for v in f.split())
    return np.array(sorted(found), dtype=int)


def quality(verbss, case_dir, points_file, scratch):
    """verbss's min quality of `case_dir`'s mesh on the points in `points_file`."""
    shutil.rmtree(scratch, ignore_errors=True)
    shutil.copytree(case_dir / "constant/polyMesh", scratch / "constant/polyMesh")
    shutil.copytree(case_dir / "system", scratch / "system")
    shutil.copy(points_file, scratch / "constant/polyMesh/points")
    r = subprocess.run([verbss, "quality", "--json", str(scratch)], capture_output=True, text=True)
    if r.returncode:
        return None
    q = json.loads(r.stdout)
    return None if q["inverted"] else q["quality"]["min"]


def held_and_free(base, moving, fixed):
    """The points of the `moving` patches and those on no moving or fixed patch."""
    moved = patch_points(base, moving)
    held = np.union1d(moved, patch_points(base, fixed)) if fixed else moved
    count = len(peer.read_foam_points(base / "constant/polyMesh/points"))
    return moved, np.setdiff1d(np.arange(count), held)


def foam_row(verbss, case, mesh_name, nodes, run, base, run_dir, log, steps, moved, free, work,
             unit=1.0):
    """The row of a moveDynamicMesh run in `run_dir` (its `log`), steps at
    times k·`unit`: a step counts until OpenFOAM's check fails or verbss finds
    an inverted cell; steps not written are not measured."""
    records = peer.foam_steps(log, unit)
    previous = peer.read_foam_points(base / "constant/polyMesh/points")
    qualities, amplification, done = [], 0.0, 0
    for s in records:
        if s["openfoam_failed_checks"]:
            break
        points_file = run_dir / s["time"] / "polyMesh/points"
        q = None
        if points_file.exists():
            q = quality(verbss, run_dir, points_file, work / "quality")
            if q is None:
                break
            current = peer.read_foam_points(points_file)
            move = np.linalg.norm(current - previous, axis=1)
            if move[moved].max() > 0:
                amplification = max(amplification, move[free].max() / move[moved].max())
            previous = current
        qualities.append(q)
        done += 1
    later = [s["cpu_s"] for s in records[1:]] or [s["cpu_s"] for s in records]
    return row(case, mesh_name, nodes, run, steps, done, qualities + [None] * (steps - done),
               amplification, sum(later) / len(later) if later else None)


def openfoam_rows(verbss, case, mesh_name, nodes, base, body_case, slip, fixed, work,
                  diffusivities=DIFFUSIVITIES, tolerance=1e-20, constraints=None):
    """displacementLaplacian (PCG to an absolute `tolerance`, see
    bench/openfoam_peer.py) on copies of the OpenFOAM case folder `base`
    (ASCII polyMesh), once per diffusivity. `body_case` is openfoam_peer's case
    dict (body, steps, translate or rotate); `slip` the patches that slip
    (pointDisplacement and cellDisplacement `slip`), `fixed` those that stay,
    `constraints` the constraint patches ({patch: type}: wedge, empty)."""
    names = list(patches(base))
    moved, free = held_and_free(base, [body_case["body"]], fixed)
    rows = []
    for label, diffusivity in diffusivities:
        run_dir = work / f"openfoam-{label.replace(' ', '-')}-{body_case['steps']}"
        shutil.rmtree(run_dir, ignore_errors=True)
        shutil.copytree(base, run_dir, ignore=shutil.ignore_patterns("[1-9]*", "0.*"))
        for d in ("0", "system", "constant"):
            (run_dir / d).mkdir(exist_ok=True)
        dicts = peer.foam_dicts(body_case, "laplacian", names, tolerance,
                                diffusivity=diffusivity.format(body=body_case["body"]), slip=slip,
                                constraints=constraints)
        for name, (cls, text) in dicts.items():
            (run_dir / name).write_text(peer.FOAM_HEADER % (cls, Path(name).name) + text)
        r = peer.run(["moveDynamicMesh"], cwd=run_dir, env=peer.foam_env(run_dir), check=False)
        (run_dir / "log.moveDynamicMesh").write_text(r.stdout + r.stderr)
        rows.append(foam_row(verbss, case, mesh_name, nodes,
                             f"OpenFOAM displacementLaplacian {label}", base, run_dir, r.stdout,
                             body_case["steps"], moved, free, work))
    return rows
