"""Every case of cases/gaps in one command (docs/robustness.md, "Squeezed
gaps"): runs each case script with `--json OUT --verbss PATH --work DIR`,
collects their rows (cases/gaps/gaps_common.py), checks per case (a case is
one case, mesh and number of steps)

1. the default completes at least as many steps as the best OpenFOAM run
   (most steps, then the higher min quality), and at every step it completes
   its min quality is at least the best of the OpenFOAM runs that complete it
   (compared as printed, to four decimals);
2. the default completes wherever `verbss`, `laplacian` or `default --blend
   off` completes, with a min quality at least 0.9 x the best of theirs that do,

prints which hold and which fail with the numbers, and one Markdown table of
every row; `--write-docs` also writes the table into docs/robustness.md
between the markers `<!-- gaps:table -->` and `<!-- /gaps:table -->`. A
script that is missing or fails is reported, not fatal.

    cargo build --release -p verbss-cli
    python3 cases/gaps/run_all.py [--verbss PATH] [--work DIR] [--only NAME,...] [--write-docs]
    python3 cases/gaps/run_all.py --rows DIR/rows.json    (check and print the rows of an earlier run)

Needs what the scripts need: OpenFOAM v1912 (its bashrc sourced), gmsh, meshio, numpy.
"""

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
DOCS = ROOT / "docs/robustness.md"
BEGIN, END = "<!-- gaps:table -->", "<!-- /gaps:table -->"
SCRIPTS = ["moving_cone", "two_cylinders", "droop", "piston", "flap", "sphere_wall", "two_bodies"]
NOT_CASES = {"run_all", "gaps_common"}
CHALLENGERS = ("verbss", "laplacian", "default --blend off")


def fmt(x, spec):
    return "–" if x is None else format(x, spec)


def run_scripts(names, verbss, work):
    rows, status = [], {}
    for name in names:
        script = HERE / f"{name}.py"
        if not script.exists():
            status[name] = "missing"
            continue
        out, folder = work / f"{name}.json", work / name
        folder.mkdir(parents=True, exist_ok=True)
        t0 = time.monotonic()
        r = subprocess.run([sys.executable, str(script), "--json", str(out), "--verbss", verbss,
                            "--work", str(folder)], capture_output=True, text=True)
        took = time.monotonic() - t0
        if r.returncode or not out.exists():
            tail = (r.stderr or r.stdout).strip().splitlines()[-1:] or [""]
            status[name] = f"failed (exit {r.returncode}): {tail[0][:200]}"
            continue
        got = json.loads(out.read_text())
        rows += got
        status[name] = f"{len(got)} rows, {took:.0f} s"
        print(f"{name}: {status[name]}", file=sys.stderr)
    return rows, status


def groups(rows):
    out = {}
    for r in rows:
        out.setdefault((r["case"], r["mesh"], r["steps"]), []).append(r)
    return out


def check(rows):
    """(requirement, case label, holds (True/False/None for not applicable), words)."""
    results = []
    for (case, mesh, steps), g in groups(rows).items():
        label = f"{case}, {mesh}, {steps} steps"
        default = next((r for r in g if r["run"] == "default"), None)
        if default is None:
            continue
        foam = [r for r in g if r["run"].startswith("OpenFOAM")]
        if foam:
            best = max(foam, key=lambda r: (r["steps_done"], r["min_quality"] or 0))
            worse = []
            for k, d in enumerate(default["min_quality_per_step"]):
                theirs = [r["min_quality_per_step"][k] for r in foam
                          if k < r["steps_done"] and r["min_quality_per_step"][k] is not None]
                if d is not None and theirs and round(d, 4) < round(max(theirs), 4):
                    worse.append((k + 1, d, max(theirs)))
            holds = default["steps_done"] >= best["steps_done"] and not worse
            words = (f"default {default['steps_done']}/{steps}, best OpenFOAM ({best['run']}) "
                     f"{best['steps_done']}/{steps}")
            if worse:
                k, d, o = min(worse, key=lambda w: w[1] - w[2])
                words += (f"; below OpenFOAM's best min quality at {len(worse)} steps "
                          f"({worse[0][0]}-{worse[-1][0]}), most at step {k}: {d:.4f} < {o:.4f}")
            results.append((1, label, holds, words))
        else:
            results.append((1, label, None, "no OpenFOAM row"))
        done = [r for r in g if r["run"] in CHALLENGERS and r["steps_done"] == steps]
        if done:
            best = max(done, key=lambda r: r["min_quality"] or 0)
            completes = default["steps_done"] == steps
            q, b = default["min_quality"], best["min_quality"]
            holds = completes and q is not None and b is not None and q >= 0.9 * b
            words = (f"default {default['steps_done']}/{steps}, {fmt(q, '.4f')}; "
                     f"{', '.join(r['run'] for r in done)} complete, best {best['run']} {fmt(b, '.4f')}"
                     f" (0.9 x = {fmt(b and 0.9 * b, '.4f')})")
            results.append((2, label, holds, words))
        else:
            results.append((2, label, None, "no other verbss run completes"))
    return results


def table(rows):
    lines = ["| case | mesh | nodes | run | steps | min quality | amplification | s/step |",
             "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        run = f"**{r['run']}**" if r["run"] == "default" else r["run"]
        lines.append(f"| {r['case']} | {r['mesh']} | {r['nodes']:,} | {run} | "
                     f"{r['steps_done']}/{r['steps']} | {fmt(r['min_quality'], '.4f')} | "
                     f"{fmt(r['amplification'], '.3f')} | {fmt(r['s_per_step'], '.4f')} |")
    return "\n".join(lines)


def write_docs(text):
    doc = DOCS.read_text()
    if BEGIN not in doc or END not in doc:
        sys.exit(f"{DOCS} has no {BEGIN} ... {END} markers")
    head, rest = doc.split(BEGIN, 1)
    DOCS.write_text(head + BEGIN + "\n" + text + "\n" + END + rest.split(END, 1)[1])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--verbss", default=str(ROOT / "target/release/verbss"))
    ap.add_argument("--work", help="keep every script's folder and JSON (and rows.json) here")
    ap.add_argument("--only", help="these scripts only, comma separated (names without .py)")
    ap.add_argument("--rows", help="check and print the rows of this JSON instead of running")
    ap.add_argument("--write-docs", action="store_true")
    a = ap.parse_args()
    verbss = str(Path(a.verbss).resolve())
    found = sorted(p.stem for p in HERE.glob("*.py") if p.stem not in NOT_CASES)
    names = a.only.split(",") if a.only else SCRIPTS + [n for n in found if n not in SCRIPTS]
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(a.work or tmp).resolve()
        work.mkdir(parents=True, exist_ok=True)
        if a.rows:
            rows, status = json.loads(Path(a.rows).read_text()), {}
        else:
            rows, status = run_scripts(names, verbss, work)
            (work / "rows.json").write_text(json.dumps(rows, indent=1))
    print("Scripts:")
    for name, words in status.items():
        print(f"* {name}: {words}")
    print("\nRequirements:")
    for req, label, holds, words in check(rows):
        mark = {True: "holds", False: "FAILS", None: "n/a"}[holds]
        print(f"* {req} {mark}: {label}: {words}")
    text = table(rows)
    print("\n" + text)
    if a.write_docs:
        write_docs(text)


if __name__ == "__main__":
    main()
