#!/usr/bin/env python3
"""verbss against OpenFOAM's moveDynamicMesh on the sphere-in-a-cube series.

    python3 bench/compare.py [--sizes 1.4,0.7,0.45,0.32,0.22] [--work DIR]
                             [--threads 1,2] [--variants defaults,REF:ACCEL:PREDICTOR,…]
                             [--json OUT] [--no-openfoam] [--foam-apps moveDynamicMesh,…]
    python3 bench/compare.py --report A.json B.json  # the tables of earlier runs, merged by mesh
    python3 bench/compare.py --series-2d  # the paper's 2D rectangles instead
    python3 bench/compare.py --smoke      # seconds: a tiny mesh, 2 steps

Per mesh (bench/sphere_cube.py: a sphere of radius 5 in the cube
[-70, 70]^3, element size growing from --h-sphere on the sphere to
12 x that at distance 65, the walls), the sphere moves 16 units along x in
16 steps:

* verbss (crates/verbss/examples/motion_bench.rs, the stepper of
  `verbss deform`), per variant: `defaults`, the command line's defaults
  (`verbss deform MESH --moving sphere --translate 16,0,0 --steps 16` and
  nothing else: VerBSS with the near-wall treatments, the blended rigid
  motion and the escalating solve; `motion_bench --defaults`), or the
  paper's method (eq.-8 tolerance 1e-6 relative) as a triple — reference `updated` (paper option 1, the default) or `fixed`
  (option 2, `--reference initial`), acceleration `none` or `amg`, and the
  initial guess `previous` (the previous step's solution, the default) or
  `linear` (extrapolated from the two previous steps, `--predictor linear`)
  — and thread count: wall and CPU seconds per step, sweeps (or
  GMRES iterations) per step, seconds per sweep, bytes per node, the peak
  memory of the steps (`VmHWM` read after them, `peak_rss_bytes`) and of
  the whole process (/usr/bin/time -v, `peak_rss_time_v`), the true error
  of steps 1 and 16 (one-thread runs; results do not depend on the
  threads; its definitions, one for the paper's method and one for the
  defaults, in motion_bench.rs) and the final mesh's minimum quality and
  inverted count (`verbss quality`);
* OpenFOAM (when `moveDynamicMesh` is installed; Debian package `openfoam`):
  the mesh imported with gmshToFoam from MSH 2.2, displacementLaplacian with
  inverseDistance diffusivity on the sphere, GAMG to 1e-6, the sphere's
  pointDisplacement a table reaching (16 0 0) at time 16; moveDynamicMesh
  (which runs a full mesh check after every step) and moveMesh (the motion
  solver alone), each timed per step (wall: when each step's ExecutionTime
  line appears; CPU: the ExecutionTime values), peak memory, and the final
  mesh exported by foamToVTK and measured by `verbss quality`.

Prints a Markdown table (and, when `defaults` ran, a second one: the
defaults against moveDynamicMesh per mesh) and writes every number to
--json (rewritten after each mesh, so an interrupted run keeps the meshes
it finished). --no-openfoam runs the verbss rows alone; --report merges the
--json files of several runs by mesh (node and cell counts), so verbss rows
of one run and OpenFOAM rows of another make one table. The 16 units
are the VerBSS paper's §5.1 motion; in the paper's cube of half width 25
the finer meshes' elements between the sphere and the wall (compressed
from 20 to 4 units) invert, and in a cube of half width 50 (45 → 29 units)
the large elements next to the wall ahead of the sphere of the 2.1M-tet
mesh invert at step 13 (updated reference) or 15 (fixed), hence 70.
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
STEPS = 16
TRAVEL = 16.0
# The cube's half width: the sphere (radius 5) moves 16 units towards the
# wall at x = BOX; the element size grows from h on the sphere to 12 h at
# the walls.
BOX = 70


def run(cmd, **kw):
    return subprocess.run(cmd, check=True, text=True, capture_output=True, **kw)


def peak_rss(time_v_stderr):
    """The peak RSS in bytes that /usr/bin/time -v wrote, or None."""
    peak = re.search(r"Maximum resident set size \(kbytes\): (\d+)", time_v_stderr)
    return int(peak.group(1)) * 1024 if peak else None


def timed(cmd, **kw):
    """Runs cmd under /usr/bin/time -v; returns (stdout, peak RSS bytes)."""
    r = run(["/usr/bin/time", "-v"] + cmd, **kw)
    return r.stdout, peak_rss(r.stderr)


def mesh_for(work, h):
    path = work / f"sphere_h{h}.msh"
    if not path.exists():
        run([sys.executable, str(ROOT / "bench" / "sphere_cube.py"), str(path),
             "--h-sphere", str(h), "--h-far", str(12 * h), "--box", str(BOX),
             "--dist-max", str(BOX - 5)])
    return path


# The paper's §4.1 series (its Table 2 node counts; cases/meshes/rectangle.py)
# and the body's upward travel over the 16 steps: 0.1 a step, the paper's
# step, for 1.6 units (the paper's full 4 units invert the finer meshes'
# body-adjacent triangles, see cases/rectangle-*.toml).
RECTANGLES = (298, 1035, 3055, 8081, 21376)
RECTANGLE_TRAVEL = 1.6


def rectangle_mesh(n):
    path = ROOT / "cases" / "meshes" / f"rectangle-{n}.msh"
    if not path.exists():
        run([sys.executable, str(ROOT / "cases" / "meshes" / "rectangle.py"), str(n),
             str(path)])
    return path


def quality(verbss, path):
    q = json.loads(run([verbss, "quality", str(path), "--json"]).stdout)
    return q["quality"]["min"], q["inverted"], q["elements"]


DEFAULTS = "defaults"


def variants(spec):
    """`defaults` or `REFERENCE:ACCEL:PREDICTOR` (reference updated|fixed,
    accel none|amg, predictor previous|linear), comma-separated, as a list
    of DEFAULTS and triples."""
    out = []
    for v in spec.split(","):
        if v == DEFAULTS:
            out.append(DEFAULTS)
            continue
        reference, accel, predictor = v.split(":")
        assert reference in ("updated", "fixed") and accel in ("none", "amg") \
            and predictor in ("previous", "linear"), v
        out.append((reference, accel, predictor))
    return out


def label(r):
    if r.get("defaults"):
        return "verbss defaults"
    return (f"verbss {r.get('reference', 'updated')} {r['accel']} "
            f"{r.get('predictor', 'previous')}")


def verbss_runs(bins, mesh, work, threads, runs, steps, motion=None):
    """motion: (group, displacement) — default the sphere's 16 units along x."""
    group, move = motion or ("sphere", f"{TRAVEL * steps / STEPS},0,0")
    out = []
    for variant in runs:
        name = variant if variant == DEFAULTS else "_".join(variant)
        for t in threads:
            final = work / f"{mesh.stem}_{name}_final.vtu"
            cmd = [bins["motion_bench"], str(mesh), "--moving", group,
                   "--translate", move, "--steps", str(steps), "--threads", str(t)]
            if variant == DEFAULTS:
                cmd.append("--defaults")
            else:
                reference, accel, predictor = variant
                cmd += ["--accel", accel, "--predictor", predictor]
                if reference == "fixed":
                    cmd.append("--fixed-reference")
            if t == threads[0]:
                cmd += ["--error-steps", f"1,{steps}", "--output", str(final)]
            stdout, peak = timed(cmd)
            r = json.loads(stdout)
            r["peak_rss_time_v"] = peak
            if r["failure"] is None and t == threads[0]:
                r["final_min_quality"], r["final_inverted"], _ = quality(bins["verbss"], final)
            out.append(r)
            print(f"  {label(r)} {t} thread(s): {summary(r)}", file=sys.stderr)
    return out


def summary(r):
    n = len(r["seconds"])
    if n == 0:
        return f"failed: {r['failure']}"
    return (f"{sum(r['seconds']) / n:.3f} s/step, {sum(r['iterations']) / n:.1f} "
            f"iterations/step, error {r['true_error']}")


FOAM_HEADER = "FoamFile { version 2.0; format ascii; class %s; object %s; }\n"


def foam_case(case, msh22, steps):
    """Writes the OpenFOAM case for `steps` steps of 1 unit each."""
    for d in ("system", "constant", "0"):
        (case / d).mkdir(parents=True, exist_ok=True)
    files = {
        "system/controlDict": ("dictionary", "controlDict", f"""
application moveDynamicMesh;
startFrom startTime; startTime 0; stopAt endTime; endTime {steps}; deltaT 1;
writeControl timeStep; writeInterval {steps}; purgeWrite 0; writeFormat binary;
writePrecision 17; writeCompression off; timeFormat general; timePrecision 6;
runTimeModifiable false;
"""),
        "system/fvSchemes": ("dictionary", "fvSchemes", """
ddtSchemes { default Euler; }
gradSchemes { default Gauss linear; }
divSchemes { default none; }
laplacianSchemes { default Gauss linear corrected; }
interpolationSchemes { default linear; }
snGradSchemes { default corrected; }
"""),
        "system/fvSolution": ("dictionary", "fvSolution", """
solvers
{
    "cellDisplacement.*" { solver GAMG; smoother GaussSeidel; tolerance 1e-6; relTol 0; }
}
"""),
        "constant/dynamicMeshDict": ("dictionary", "dynamicMeshDict", """
dynamicFvMesh dynamicMotionSolverFvMesh;
motionSolverLibs (fvMotionSolvers);
motionSolver displacementLaplacian;
displacementLaplacianCoeffs { diffusivity inverseDistance (sphere); }
"""),
        "0/pointDisplacement": ("pointVectorField", "pointDisplacement", f"""
dimensions [0 1 0 0 0 0 0];
internalField uniform (0 0 0);
boundaryField
{{
    sphere {{ type uniformFixedValue; uniformValue table ((0 (0 0 0)) ({steps} ({steps} 0 0))); }}
    farfield {{ type fixedValue; value uniform (0 0 0); }}
}}
"""),
        "0/cellDisplacement": ("volVectorField", "cellDisplacement", """
dimensions [0 1 0 0 0 0 0];
internalField uniform (0 0 0);
boundaryField
{
    sphere { type cellMotion; value uniform (0 0 0); }
    farfield { type cellMotion; value uniform (0 0 0); }
}
"""),
    }
    for name, (cls, obj, body) in files.items():
        (case / name).write_text(FOAM_HEADER % (cls, obj) + body)
    r = run(["gmshToFoam", str(msh22)], cwd=case, env=foam_env())
    (case / "log.gmshToFoam").write_text(r.stdout + r.stderr)


def foam_env():
    env = dict(os.environ)
    env.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
    return env


def foam_timed(app, case):
    """Runs an OpenFOAM application, timestamping each step's end; returns
    per-step wall seconds, per-step CPU seconds, GAMG iterations per step
    (x, y, z summed) and peak RSS."""
    proc = subprocess.Popen(["/usr/bin/time", "-v", app], cwd=case, env=foam_env(),
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    wall, cpu, iters, log = [], [], [], []
    start = None
    current = 0
    for line in proc.stdout:
        now = time.monotonic()
        log.append(line)
        if line.startswith("Time = ") and start is None:
            start = now
        m = re.match(r"GAMG:\s+Solving for cellDisplacement\w, .* No Iterations (\d+)", line)
        if m:
            current += int(m.group(1))
        m = re.match(r"ExecutionTime = ([\d.e+-]+) s", line)
        if m:
            wall.append(now - start)
            start = now
            cpu.append(float(m.group(1)))
            iters.append(current)
            current = 0
    err = proc.stderr.read()
    proc.wait()
    (Path(case) / f"log.{app}").write_text("".join(log) + err)
    if proc.returncode != 0:
        raise RuntimeError(f"{app} failed in {case}: {err[-2000:]}")
    # ExecutionTime is the process's CPU time since it started: the first
    # step's value includes reading the mesh, so the first step has none.
    cpu = [float("nan")] + [b - a for a, b in zip(cpu[:-1], cpu[1:])]
    return wall, cpu, iters, peak_rss(err)


def openfoam_run(bins, mesh, work, steps, apps):
    msh22 = work / f"{mesh.stem}_22.msh"
    run([bins["verbss"], "convert", str(mesh), str(msh22), "--msh-version", "2.2",
         "--ascii"])
    out = {}
    for app in apps:
        case = work / f"{mesh.stem}_{app}"
        shutil.rmtree(case, ignore_errors=True)
        foam_case(case, msh22, steps)
        wall, cpu, iters, peak = foam_timed(app, case)
        r = {"seconds": wall, "cpu_seconds": cpu, "gamg_iterations": iters,
             "peak_rss_time_v": peak}
        if app == "moveDynamicMesh":
            run(["foamToVTK", "-latestTime", "-no-boundary", "-no-point-data",
                 "-fields", "()"], cwd=case, env=foam_env())
            vtu = case / "VTK" / f"{case.name}_{steps}" / "internal.vtu"
            r["final_min_quality"], r["final_inverted"], r["final_elements"] = \
                quality(bins["verbss"], vtu)
        out[app] = r
        n = len(wall)
        print(f"  OpenFOAM {app}: {sum(wall) / n:.3f} s/step wall, {later(cpu):.3f} "
              f"CPU, {sum(iters) / n:.1f} GAMG iterations/step", file=sys.stderr)
    return out


def build(debug, bin_dir=None):
    """The binaries: built here (release, or debug for --smoke), or those
    already in `bin_dir` (a cargo profile folder such as target/debug)."""
    if bin_dir is None:
        profile = [] if debug else ["--release"]
        subprocess.run([os.environ.get("CARGO", "cargo"), "build", "-q"] + profile
                       + ["-p", "verbss", "--example", "motion_bench", "-p", "verbss-cli",
                          "--bin", "verbss"],
                       check=True, cwd=ROOT)
        bin_dir = ROOT / "target" / ("debug" if debug else "release")
    bins = {"motion_bench": Path(bin_dir) / "examples" / "motion_bench",
            "verbss": Path(bin_dir) / "verbss"}
    for name, path in bins.items():
        if not path.is_file():
            sys.exit(f"compare.py: {name} not found at {path} (build it, or leave out --bin-dir)")
    return {name: str(path) for name, path in bins.items()}


def mean(x):
    return sum(x) / len(x) if x else float("nan")


def later(x):
    """The mean over steps 2, 3, …: the first step of OpenFOAM's CPU times
    includes reading the mesh."""
    return mean(x[1:])


def table(results):
    print("| tets | nodes | who | threads | s/step (wall) | s/step (CPU, steps 2–) | solve s/step "
          "| iterations/step | s/sweep | bytes/node | peak MB | error step 1 | error last step "
          "| min quality | inverted | moveDynamicMesh / this (wall) | (CPU, steps 2–) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for m in results:
        foam = m.get("openfoam", {}).get("moveDynamicMesh")
        rows = []
        for r in m["verbss"]:
            ok = len(r["seconds"]) == r["steps_total"]
            per = mean(r["seconds"])
            cpu = later(r["cpu_seconds"])
            sweeps = mean(r["iterations"])
            err = errors(r)
            rows.append([label(r), r["threads"], f"{per:.3f}" if ok else
                         f"failed at step {len(r['seconds']) + 1}",
                         f"{cpu:.3f}",
                         f"{mean(r['solve_seconds']):.3f}", f"{sweeps:.1f}",
                         f"{mean(r['solve_seconds']) / sweeps:.2e}" if sweeps else "",
                         f"{r['bytes_per_node']:.0f}", f"{r['peak_rss_bytes'] / 1e6:.0f}",
                         f"{err.get(1, float('nan')):.1e}" if err else "",
                         f"{err.get(r['steps_total'], float('nan')):.1e}" if err else "",
                         f"{r['final_min_quality']:.4f}" if "final_min_quality" in r else "",
                         r.get("final_inverted", ""),
                         f"{mean(foam['seconds']) / per:.1f}x" if foam and ok else "",
                         f"{later(foam['cpu_seconds']) / cpu:.1f}x" if foam and ok and cpu > 0
                         else ""])
        for app, f in m.get("openfoam", {}).items():
            rows.append([f"OpenFOAM {app}", 1, f"{mean(f['seconds']):.3f}",
                         f"{later(f['cpu_seconds']):.3f}", "",
                         f"{mean(f['gamg_iterations']):.1f} (GAMG)", "", "",
                         f"{f['peak_rss_time_v'] / 1e6:.0f}", "", "",
                         f"{f['final_min_quality']:.4f}" if "final_min_quality" in f else "",
                         f.get("final_inverted", ""), "", ""])
        for row in rows:
            print(f"| {m['cells']:,} | {m['nodes']:,} | " + " | ".join(map(str, row)) + " |")


def errors(r):
    """The run's true error by step (none when its tight run failed: then
    `true_error` is the failure's message)."""
    e = r["true_error"]
    return {} if isinstance(e, str) else dict((s, x) for s, x in e)


def defaults_table(results):
    """Per mesh, the defaults (one thread) against moveDynamicMesh: wall
    seconds per step (mean of all steps) and their ratio, CPU seconds per
    step (mean of steps 2 on) and their ratio, the peak memory per
    node (the defaults: the steps' VmHWM; OpenFOAM: the process's peak,
    /usr/bin/time -v; bracketed: the whole motion_bench process's), the
    defaults' true error at step 1 and the last step, and both final
    meshes' minimum quality. One row per mesh: where several --report
    files hold a one-thread defaults run of it, the last one given counts."""
    rows = []
    for m in results:
        foam = m.get("openfoam", {}).get("moveDynamicMesh")
        runs = [r for r in m["verbss"] if r.get("defaults") and r["threads"] == 1]
        for r in runs[-1:]:
            ok = len(r["seconds"]) == r["steps_total"]
            per = mean(r["seconds"])
            cpu = later(r["cpu_seconds"])
            foam_cpu = later(foam["cpu_seconds"]) if foam else float("nan")
            err = errors(r)
            n = m["nodes"]
            whole = r.get("peak_rss_time_v")
            rows.append([
                f"{m['cells']:,}", f"{n:,}",
                f"{per:.3f}" if ok else f"failed at step {len(r['seconds']) + 1}",
                f"{mean(foam['seconds']):.3f}" if foam else "",
                f"{mean(foam['seconds']) / per:.1f}x" if foam and ok else "",
                f"{cpu:.3f}", f"{foam_cpu:.3f}" if foam else "",
                f"{foam_cpu / cpu:.1f}x" if foam and ok and cpu > 0 else "",
                f"{r['peak_rss_bytes'] / n:,.0f}" + (f" ({whole / n:,.0f})" if whole else ""),
                f"{foam['peak_rss_time_v'] / n:,.0f}" if foam else "",
                f"{err.get(1, float('nan')):.1e}" if err else r["true_error"],
                f"{err.get(r['steps_total'], float('nan')):.1e}" if err else "",
                f"{r['final_min_quality']:.3g}" if "final_min_quality" in r else "",
                f"{foam['final_min_quality']:.3g}" if foam and "final_min_quality" in foam
                else ""])
    if rows:
        print("\n| tets | nodes | defaults s/step | moveDynamicMesh s/step | ratio "
              "| defaults CPU s/step (2–) | moveDynamicMesh CPU s/step (2–) | ratio (CPU) "
              "| defaults bytes/node (whole process) | moveDynamicMesh bytes/node "
              "| true error step 1 | true error last step | min quality defaults "
              "| min quality moveDynamicMesh |")
        print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
        for row in rows:
            print("| " + " | ".join(row) + " |")


def merged(files):
    """The meshes of several --json files, one entry per mesh (same node and
    cell counts): their verbss runs together, their OpenFOAM runs merged
    (a later file's run of the same application counts)."""
    by_mesh = {}
    for f in files:
        for m in json.loads(Path(f).read_text()):
            key = (m["nodes"], m["cells"])
            if key not in by_mesh:
                by_mesh[key] = dict(m, verbss=list(m["verbss"]),
                                    openfoam=dict(m.get("openfoam", {})))
                continue
            into = by_mesh[key]
            into["verbss"] += m["verbss"]
            into["openfoam"].update(m.get("openfoam", {}))
    return sorted(by_mesh.values(), key=lambda m: m["nodes"])


def fits(results):
    """Log-log slopes against unknown nodes of the one-thread runs: seconds
    per step, sweeps (iterations) per step and seconds per sweep. One point
    per mesh and run: where several --report files hold the same, the last
    file given counts."""
    rows = []
    for key in sorted({label(r) for m in results for r in m["verbss"]}):
        by_mesh = {}
        for m in results:
            for r in m["verbss"]:
                if label(r) == key and r["threads"] == 1 \
                        and len(r["seconds"]) == r["steps_total"] and mean(r["iterations"]) > 0:
                    sweeps = mean(r["iterations"])
                    by_mesh[r["unknown_nodes"]] = (r["unknown_nodes"], mean(r["seconds"]), sweeps,
                                                   mean(r["solve_seconds"]) / sweeps)
        pts = list(by_mesh.values())
        if len(pts) < 2:
            continue
        x = [math.log(p[0]) for p in pts]
        slope = []
        for k in (1, 2, 3):
            y = [math.log(p[k]) for p in pts]
            xm, ym = mean(x), mean(y)
            slope.append(sum((a - xm) * (b - ym) for a, b in zip(x, y))
                         / sum((a - xm) ** 2 for a in x))
        rows.append(f"| {key}, 1 thread | {slope[0]:.2f} | {slope[1]:.2f} | "
                    f"{slope[2]:.2f} | {len(pts)} |")
    if rows:
        print("\n| run | slope of s/step | slope of iterations/step | slope of s/sweep | meshes |")
        print("|---|---|---|---|---|")
        print("\n".join(rows))


def plot(results, path):
    """Seconds per step against unknown nodes, log-log, one line per run."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4.5))
    lines = {}
    for m in results:
        for r in m["verbss"]:
            if len(r["seconds"]) == r["steps_total"]:
                key = f"{label(r)}, {r['threads']} thread(s)"
                lines.setdefault(key, []).append((r["unknown_nodes"], mean(r["seconds"])))
        for app, f in m.get("openfoam", {}).items():
            lines.setdefault(f"OpenFOAM {app}", []).append(
                (m["verbss"][0]["unknown_nodes"], mean(f["seconds"])))
    for key, pts in sorted(lines.items()):
        pts.sort()
        ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", label=key)
    ax.set_xlabel("unknown nodes")
    ax.set_ylabel("wall seconds per step")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes", default="1.4,0.7,0.45,0.32,0.22")
    ap.add_argument("--work", default="/tmp/verbss-bench")
    ap.add_argument("--bin-dir", default=None,
                    help="use the verbss and examples/motion_bench binaries in this cargo "
                         "profile folder (e.g. target/debug) instead of building them")
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--variants",
                    default="defaults,updated:none:previous,updated:none:linear,"
                            "updated:amg:linear,fixed:none:linear",
                    help="verbss runs: defaults (the command line's defaults) or "
                         "REFERENCE:ACCEL:PREDICTOR (updated|fixed, none|amg, previous|linear), "
                         "comma-separated")
    ap.add_argument("--series-2d", action="store_true",
                    help="instead: the paper's 2D rectangles (no OpenFOAM)")
    ap.add_argument("--json", default=None)
    ap.add_argument("--no-openfoam", action="store_true")
    ap.add_argument("--foam-apps", default="moveDynamicMesh,moveMesh",
                    help="the OpenFOAM applications to time")
    ap.add_argument("--report", nargs="+", default=None, metavar="JSON",
                    help="print the tables of earlier runs' --json files, merged by mesh "
                         "(and --plot)")
    ap.add_argument("--plot", default=None, help="with --report: a log-log PNG here")
    ap.add_argument("--smoke", action="store_true",
                    help="a tiny mesh (h 2.5), 2 steps, debug build: checks that it all runs")
    a = ap.parse_args()
    if a.report:
        results = merged(a.report)
        table(results)
        defaults_table(results)
        fits(results)
        if a.plot:
            plot(results, a.plot)
        return
    work = Path(a.work)
    work.mkdir(parents=True, exist_ok=True)
    sizes = [2.5] if a.smoke else [float(h) for h in a.sizes.split(",")]
    steps = 2 if a.smoke else STEPS
    bins = build(a.smoke, a.bin_dir)
    if a.series_2d:
        meshes = [(rectangle_mesh(n), None) for n in RECTANGLES[:1 if a.smoke else None]]
        motion = ("body", f"0,{RECTANGLE_TRAVEL * steps / STEPS}")
    else:
        meshes = [(mesh_for(work, h), h) for h in sizes]
        motion = None
    have_foam = shutil.which("moveDynamicMesh") is not None and not a.no_openfoam \
        and not a.series_2d
    if not have_foam:
        print("OpenFOAM: skipped (moveDynamicMesh not installed or --no-openfoam)",
              file=sys.stderr)
    print(f"load average at start: {os.getloadavg()}", file=sys.stderr)
    results = []
    for mesh, h in meshes:
        print(f"{mesh}:", file=sys.stderr)
        runs = verbss_runs(bins, mesh, work, [int(t) for t in a.threads.split(",")],
                           variants(a.variants), steps, motion)
        for r in runs:
            r["steps_total"] = steps
        m = {"h_sphere": h, "mesh": str(mesh), "nodes": runs[0]["nodes"],
             "cells": runs[0]["cells"], "verbss": runs, "load_average": os.getloadavg()}
        if have_foam:
            m["openfoam"] = openfoam_run(bins, mesh, work, steps, a.foam_apps.split(","))
        results.append(m)
        if a.json:
            Path(a.json).write_text(json.dumps(results, indent=1))
    print(f"load average at end: {os.getloadavg()}", file=sys.stderr)
    table(results)
    defaults_table(results)
    fits(results)
    if a.smoke:
        for m in results:
            for r in m["verbss"]:
                assert r["failure"] is None and len(r["seconds"]) == steps, r
                if r["threads"] == 1:
                    assert sorted(errors(r)) == [1, steps], r
                    assert not r.get("defaults") or len(r["paper_distance"]) == 2, r
            if have_foam:
                for f in m["openfoam"].values():
                    assert len(f["seconds"]) == steps, f


if __name__ == "__main__":
    main()
