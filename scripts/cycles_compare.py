#!/usr/bin/env python3
"""scripts/cycles-compare's body: the oracle beside Blender Cycles (see scripts/cycles-compare).

Per case (an image size and Cycles' sample counts):
  1. `shadow-oracle view` writes view.json (what Blender builds the scene from) and gbuffer.exr
     (the surface point of every pixel, at which the closed form is evaluated);
  2. Cycles renders panel.V at each sample count (render_shadows.py: the shadowed and the
     unshadowed render, V = their ratio), timed as the whole Blender process and, from its
     render_times.json, the renders alone;
  3. `shadow-oracle trace` over a ladder of adaptive targets (0.08 down by sqrt(2) per step) until
     its penumbra error is below the smallest of Cycles', each target timed --reps times, with
     and without previews, interleaved; medians;
  4. bench_closed_form_error measures every image's penumbra error against Lambert's closed form;
  5. at each Cycles error, the oracle's times are interpolated between the two ladder runs around
     it (log time against log error), and set against Cycles' times.
Writes OUT/summary.json, OUT/tables.md and, unless --no-docs, the same tables between the
markers in docs/benchmarks.md.
"""
import argparse
import datetime
import json
import math
import os
import pathlib
import platform
import shutil
import statistics
import subprocess
import sys
import time
from doc_markers import write_between_markers

ROOT = pathlib.Path(__file__).resolve().parent.parent
SCENE = ROOT / "scenes" / "penumbra_square.scene.json"
RENDER = ROOT / "examples" / "blender" / "render_shadows.py"
DOCS = ROOT / "docs" / "benchmarks.md"
LADDER_START = 0.08
LADDER_FLOOR = 1e-4  # trace's smallest --target-error
GOAL = 100.0  # issue 32: the oracle at Cycles' 1,024-spp error at least this many times faster


def skip(why):
    print("SKIPPED: " + why)
    sys.stdout.flush()
    sys.exit(0)


def fail(why):
    sys.stderr.write("cycles-compare: error: %s\n" % why)
    sys.exit(1)


def last_line(text, marker=None):
    lines = [ln for ln in text.splitlines() if ln.strip()]
    if marker:
        for ln in lines:
            if marker in ln:
                return ln
    return lines[-1] if lines else "(no output)"


def run(cmd, log=None, env=None):
    """Runs cmd, returns (completed process, wall seconds of the whole process)."""
    cmd = [str(c) for c in cmd]
    t0 = time.perf_counter()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)
    seconds = time.perf_counter() - t0
    if log:
        pathlib.Path(log).write_text(" ".join(cmd) + "\n" + p.stdout)
    return p, seconds


def parse_case(text):
    try:
        size, spps = text.split(":")
        case = (int(size), [int(s) for s in spps.split(",")])
    except ValueError:
        raise argparse.ArgumentTypeError("%r is not SIZE:SPP[,SPP...]" % text)
    if not 16 <= case[0] <= 4096 or not case[1] or min(case[1]) < 1:
        raise argparse.ArgumentTypeError("%r: SIZE in 16..4096, each SPP >= 1" % text)
    return case


def blender_env():
    """Debian's Blender takes its Python home from the first python3.X on PATH. pyenv (while it
    runs this script) and virtualenvs put their own first, which has no numpy for Blender's glTF
    importer: Blender gets PATH without the folder of the interpreter running this script, unless
    that is the system's."""
    own = os.path.dirname(os.path.realpath(sys.executable))
    if own in ("/usr/bin", "/bin"):
        return None
    env = dict(os.environ)
    env["PATH"] = os.pathsep.join(d for d in env.get("PATH", "").split(os.pathsep)
                                  if d and os.path.realpath(d) != own)
    return env


BLENDER_ENV = blender_env()


def probe_blender(blender):
    """Blender's version, or SKIPPED where it cannot run Cycles with its glTF importer."""
    try:
        p, _ = run([blender, "-b", "--factory-startup", "--python-exit-code", "1",
                    "--python-expr", "import bpy, numpy; print('so-probe', bpy.app.version_string)"],
                   env=BLENDER_ENV)
    except OSError as e:
        skip("%s cannot start: %s" % (blender, e))
    if p.returncode != 0 or "so-probe" not in p.stdout:
        skip("%s cannot run here (its glTF importer needs numpy: apt-get install python3-numpy): %s"
             % (blender, last_line(p.stdout, "Error")))
    return last_line(p.stdout, "so-probe").split()[-1]


class Context:
    def __init__(self, args):
        self.args = args
        self.build = pathlib.Path(args.build).resolve()
        self.oracle = self.build / "cli" / "shadow-oracle"
        self.evaluator = self.build / "bench" / "bench_closed_form_error"
        for exe in (self.oracle, self.evaluator):
            if not os.access(exe, os.X_OK):
                fail("%s is missing: build it (cmake --build %s --target %s)"
                     % (exe, args.build, exe.name))
        self.out = pathlib.Path(args.out).resolve()
        self.blender = os.environ.get("BLENDER") or "blender"
        self.threads = args.threads


def make_view(ctx, size, where):
    p, _ = run([ctx.oracle, "view", SCENE, "--out", where, "--width", size, "--height", size,
                "--threads", ctx.threads, "--quiet"], log=str(where) + ".log")
    if p.returncode != 0:
        fail("shadow-oracle view: " + last_line(p.stdout))
    view = json.loads((where / "view.json").read_text())
    return where / "view.json", where / "gbuffer.exr", view["lights"][0]["name"]


def render_cycles(ctx, view, light, spp, where):
    shutil.rmtree(where, ignore_errors=True)
    p, wall = run([ctx.blender, "-b", "--factory-startup", "--python-exit-code", "1", "-P", RENDER,
                   "--", view, "--out", where, "--engine", "cycles", "--samples", spp,
                   "--threads", ctx.threads], log=str(where) + ".log", env=BLENDER_ENV)
    if p.returncode == 3:  # render_shadows.py: Blender's glTF importer cannot run
        skip(last_line(p.stdout, "render_shadows.py: error"))
    if p.returncode != 0:
        fail("Cycles at %d spp: %s (log: %s.log)"
             % (spp, last_line(p.stdout, "render_shadows.py: error"), where))
    times = json.loads((where / "render_times.json").read_text())["lights"][light]
    return {"spp": spp, "exr": str(where / "shadows.exr"), "whole_s": wall,
            "shadowed_s": times["shadowed_ms"] / 1000.0,
            "unshadowed_s": times["unshadowed_ms"] / 1000.0}


def evaluate(ctx, gbuffer, images):
    p = subprocess.run([str(ctx.evaluator), str(SCENE), "--geometry", str(gbuffer)] +
                       [str(i) for i in images], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                       text=True)
    if p.returncode != 0:
        fail("bench_closed_form_error: " + last_line(p.stderr))
    return json.loads(p.stdout)


# The oracle's two methods for a rect light (docs/oracle.md): RQMC sampling with stated intervals
# (every area light), and the exact pass over the pixels the sampled pass finds in a penumbra
# (polygonal lights). Each runs over a ladder of adaptive targets from LADDER_START down.
METHODS = {
    "sampled": {"flags": ["--penumbra", "sampled"], "step": 2.0 ** -0.5, "floor": 1e-4,
                "name": "sampled (RQMC)"},
    "exact": {"flags": ["--penumbra", "exact"], "step": 0.5, "floor": 0.0025,
              "name": "exact (`--penumbra exact`)"},
}


def trace(ctx, size, method, target, previews, where):
    cmd = [ctx.oracle, "trace", SCENE, "--width", size, "--height", size, "--target-error",
           "%.6g" % target, "--threads", ctx.threads, "--quiet", "--out", where]
    cmd += METHODS[method]["flags"] + ([] if previews else ["--no-previews"])
    p, wall = run(cmd)
    if p.returncode != 0:
        fail("shadow-oracle trace: " + last_line(p.stdout))
    return wall, json.loads((where / "oracle.json").read_text())


def rep(ctx, size, entry):
    """One timed run of a ladder target with previews, and one without."""
    for previews, suffix in ((True, ""), (False, "_no_previews")):
        wall, j = trace(ctx, size, entry["method"], entry["target"], previews,
                        pathlib.Path(entry["dir"] + suffix))
        light = j["lights"][0]
        # phases_seconds.shadow holds the sampled and the exact pass (format_version 10); the
        # exact pass's own share is kept for the tables.
        phases = dict(j["phases_seconds"])
        phases["exact"] = (light.get("exact_penumbra") or {}).get("seconds") or 0.0
        entry["runs" + suffix].append((wall, phases))
        entry["spp_mean"] = light["spp_mean"]
        entry["rays"] = light["rays_traced"]


def shadow(phases):
    """The area light's passes: sampled, then exact (0 without --penumbra exact)."""
    return phases["shadow"]


def oracle_ladder(ctx, size, method, gbuffer, smallest_error, where):
    """Targets from LADDER_START down until the penumbra error is below smallest_error (or the
    method's floor); medians of the reps."""
    m = METHODS[method]
    ladder = []
    target = LADDER_START
    while target >= m["floor"] * (1 - 1e-9):
        entry = {"method": method, "target": target, "runs": [], "runs_no_previews": [],
                 "dir": str(where / ("%s_%.6g" % (method, target)))}
        ladder.append(entry)
        rep(ctx, size, entry)
        error = evaluate(ctx, gbuffer, [pathlib.Path(entry["dir"]) / "oracle.exr"])["images"][0]
        entry.update(mae=error["penumbra_mae"], p99=error["penumbra_p99"],
                     signed=error["penumbra_signed_mean"])
        print("  oracle %dx%d %s, target %.6g: penumbra mae %.3g, shadow passes %.3f s, whole "
              "%.3f s" % (size, size, method, target, entry["mae"], shadow(entry["runs"][0][1]),
                          entry["runs"][0][0]))
        sys.stdout.flush()
        if entry["mae"] < smallest_error:
            break
        target *= m["step"]
    for _ in range(1, ctx.args.reps):  # the other repetitions, interleaved over the ladder
        for entry in ladder:
            rep(ctx, size, entry)
    for entry in ladder:
        both = entry["runs"] + entry["runs_no_previews"]
        entry["area_s"] = statistics.median(shadow(r[1]) for r in both)  # previews or not
        for suffix in ("", "_no_previews"):
            runs = entry.pop("runs" + suffix)
            entry["whole" + suffix + "_s"] = statistics.median(r[0] for r in runs)
            entry["phases" + suffix + "_s"] = {name: statistics.median(r[1][name] for r in runs)
                                               for name in runs[0][1]}
            # Medians of each run's own differences, so that a slow run does not mix with another
            # run's phases: process start and exit (outside every phase), and all but the shadow.
            # "exact" is inside "shadow" already: it is kept apart for the tables only.
            entry["start_exit" + suffix + "_s"] = statistics.median(
                r[0] - sum(v for k, v in r[1].items() if k != "exact") for r in runs)
            entry["fixed" + suffix + "_s"] = statistics.median(r[0] - shadow(r[1]) for r in runs)
    return ladder


TIMES = ("target", "area_s", "whole_s", "whole_no_previews_s")


def sampled_at(ladder, error):
    """The sampled ladder's times at a penumbra error: log-log between the two runs around it.
    "how" is "" (interpolated), "<=" (every run is more accurate: the loosest run's times bound
    it) or "not reached"."""
    for r0, r1 in zip(ladder, ladder[1:]):
        e0, e1 = r0["mae"], r1["mae"]
        if e0 >= error >= e1 and e0 > e1:
            f = math.log(error / e0) / math.log(e1 / e0)
            out = {k: math.exp(math.log(r0[k]) + f * (math.log(r1[k]) - math.log(r0[k])))
                   for k in TIMES}
            out["how"] = ""
            return out
    if error > ladder[0]["mae"]:
        return dict({k: ladder[0][k] for k in TIMES}, how="<=", mae=ladder[0]["mae"])
    return {"how": "not reached"}


def exact_at(ladder, error):
    """The exact ladder's loosest run with an error at most `error`: its times bound the time to
    that error ("<="); "not reached" where none is that accurate."""
    for r in ladder:
        if r["mae"] <= error:
            return dict({k: r[k] for k in TIMES}, how="<=", mae=r["mae"])
    return {"how": "not reached"}


def run_case(ctx, size, spps, blender_version):
    where = ctx.out / ("%d" % size)
    where.mkdir(parents=True, exist_ok=True)
    view, gbuffer, light = make_view(ctx, size, where / "view")
    cycles = []
    for spp in spps:
        c = render_cycles(ctx, view, light, spp, where / ("cycles_%d" % spp))
        cycles.append(c)
        print("  cycles %dx%d %d spp: shadowed render %.2f s, unshadowed %.2f s, whole Blender "
              "process %.2f s" % (size, size, spp, c["shadowed_s"], c["unshadowed_s"],
                                  c["whole_s"]))
        sys.stdout.flush()
    judged = evaluate(ctx, gbuffer, [c["exr"] for c in cycles])
    for c, e in zip(cycles, judged["images"]):
        c.update(mae=e["penumbra_mae"], p99=e["penumbra_p99"], signed=e["penumbra_signed_mean"],
                 outside_pixels_off=e["outside_pixels_off"],
                 noise_bound=judged["noise_bound_1spp"] / math.sqrt(c["spp"]))
        print("  cycles %dx%d %d spp: penumbra mae %.3g (independent samples: %.3g)"
              % (size, size, c["spp"], c["mae"], c["noise_bound"]))
    smallest = min(c["mae"] for c in cycles)
    ladders = {m: oracle_ladder(ctx, size, m, gbuffer, smallest, where / "oracle")
               for m in METHODS}
    for c in cycles:
        c["oracle"] = {"sampled": sampled_at(ladders["sampled"], c["mae"]),
                       "exact": exact_at(ladders["exact"], c["mae"])}
        for o in c["oracle"].values():
            if o["how"] != "not reached":
                o["ratio_render_to_area"] = c["shadowed_s"] / o["area_s"]
                o["ratio_whole"] = c["whole_s"] / o["whole_s"]
                o["ratio_whole_no_previews"] = c["whole_s"] / o["whole_no_previews_s"]
    return {"size": size, "penumbra_pixels": judged["penumbra_pixels"],
            "covered_pixels": judged["covered_pixels"], "cycles": cycles, "ladders": ladders,
            "blender": blender_version}


# ---------------------------------------------------------------- tables
def sec(v, how=""):
    if v is None:
        return "not reached"
    return ("≤ " if how == "<=" else "") + ("%.3f" % v if v < 10 else "%.1f" % v)


def ratio(v, how=""):
    if v is None:
        return "–"
    return ("≥ " if how == "<=" else "") + ("%.0fx" % v if v >= 10 else "%.1fx" % v)


def spp_text(spp):
    return "{:,}".format(spp)


def reference_row(case, reference_spp):
    """The Cycles row at the reference sample count, else the nearest (a case without it)."""
    return min(case["cycles"], key=lambda c: abs(math.log(c["spp"] / reference_spp)))


def fixed_costs_row(case, method, reference):
    """Where a ladder run's time goes: for sampled, the run nearest (in log error) to the
    reference error; for exact, the run that reaches it. Cells: with previews (without, in
    brackets, where they differ)."""
    ladder = case["ladders"][method]
    if method == "exact":
        reaching = [r for r in ladder if r["mae"] <= reference]
        r = reaching[0] if reaching else ladder[-1]
    else:
        r = min(ladder, key=lambda e: abs(math.log(e["mae"] / reference)))
    ph, phn = r["phases_s"], r["phases_no_previews_s"]
    cells = ["%d x %d" % (case["size"], case["size"]), METHODS[method]["name"],
             "%.3g" % r["target"], "%.3g" % r["mae"],
             "%.3f (%.3f)" % (r["whole_s"], r["whole_no_previews_s"]), "%.3f" % r["area_s"],
             "%.3f" % (ph.get("load", 0) + ph.get("build_bvh", 0)), "%.3f" % ph.get("primary", 0),
             "%.3f" % phn.get("write", 0), "%.3f" % (ph.get("write", 0) - phn.get("write", 0)),
             "%.3f (%.3f)" % (r["start_exit_s"], r["start_exit_no_previews_s"]),
             "%.3f (%.3f)" % (r["fixed_s"], r["fixed_no_previews_s"])]
    return "| " + " | ".join(cells) + " |"


def goal_line(case, c):
    parts = []
    for method, o in c["oracle"].items():
        name = METHODS[method]["name"]
        if o["how"] == "not reached":
            parts.append("%s: its ladder did not reach that error" % name)
            continue
        reached = [label for label, key in (("whole processes", "ratio_whole"),
                                            ("whole processes without previews",
                                             "ratio_whole_no_previews"),
                                            ("Cycles' render against the shadow passes",
                                             "ratio_render_to_area"))
                   if o[key] >= GOAL]
        parts.append("%s: %s whole process against whole process (%s with `--no-previews`), %s "
                     "render against shadow passes; %s"
                     % (name, ratio(o["ratio_whole"], o["how"]),
                        ratio(o["ratio_whole_no_previews"], o["how"]),
                        ratio(o["ratio_render_to_area"], o["how"]),
                        ("%.0fx reached by: " % GOAL + ", ".join(reached)) if reached
                        else "%.0fx not reached" % GOAL))
    return ("**Goal (%.0fx at Cycles' %s-spp error), %d x %d.** " % (
        GOAL, spp_text(c["spp"]), case["size"], case["size"]) + "; ".join(parts) + ".")


def tables(summary):
    m = summary["machine"]
    out = ["*Generated by `%s` on %s, revision %s: %s, %d cores, load average %.2f at the start "
           "and %.2f at the end; Blender %s (Cycles) and shadow-oracle both on %d threads; the "
           "oracle's times are medians of %d runs each, Cycles' one run each.*"
           % (summary["command"], m["date"], m["revision"], m["cpu"], m["cores"],
              m["load_start"], m["load_end"], summary["cases"][0]["blender"],
              summary["threads"], summary["reps"]),
           "",
           "Cycles (penumbra mean absolute error against the closed form, beside what independent "
           "samples would give; the renders as `render_shadows.py` times them; the whole Blender "
           "process: start, glTF import, both renders, V written):",
           "",
           "| size | spp | penumbra MAE | independent-sample MAE | shadowed render s | "
           "unshadowed render s | whole Blender process s |",
           "|---|---|---|---|---|---|---|"]
    for case in summary["cases"]:
        for c in case["cycles"]:
            out.append("| %d x %d | %s | %.3g | %.3g | %s | %s | %s |"
                       % (case["size"], case["size"], spp_text(c["spp"]), c["mae"],
                          c["noise_bound"], sec(c["shadowed_s"]), sec(c["unshadowed_s"]),
                          sec(c["whole_s"])))
    out += ["",
            "The oracle at the same penumbra error, and Cycles' time over the oracle's. Sampled: "
            "interpolated between the two runs of its ladder around that error (log time against "
            "log error). Exact: the loosest target whose run's error is at most Cycles' (≤: the "
            "time to reach exactly that error is at most this). The shadow passes are the area "
            "light's, from oracle.json: `phases_seconds.shadow`, which holds the sampled pass and "
            "the exact one (`exact_penumbra.seconds`), the median over the runs with and without previews, "
            "which do the same work there; the "
            "whole `trace` is timed from start to exit, with its PNG preview and with "
            "`--no-previews`:",
            "",
            "| size | Cycles spp | error | oracle | target | shadow passes s | whole trace s | "
            "whole, --no-previews s | Cycles render / shadow passes | Blender / trace | Blender / "
            "trace --no-previews |",
            "|---|---|---|---|---|---|---|---|---|---|---|"]
    for case in summary["cases"]:
        for c in case["cycles"]:
            for method, o in c["oracle"].items():
                how = o["how"]
                if how == "not reached":
                    cells = ["not reached"] * 4 + ["–"] * 3
                else:
                    cells = [("≥ " if how == "<=" and method == "sampled" else "") +
                             "%.3g" % o["target"], sec(o["area_s"], how), sec(o["whole_s"], how),
                             sec(o["whole_no_previews_s"], how),
                             ratio(o["ratio_render_to_area"], how), ratio(o["ratio_whole"], how),
                             ratio(o["ratio_whole_no_previews"], how)]
                out.append("| %d x %d | %s | %.3g | %s | %s |"
                           % (case["size"], case["size"], spp_text(c["spp"]), c["mae"],
                              METHODS[method]["name"], " | ".join(cells)))
    out += ["",
            "Where the oracle's time goes, at the run nearest Cycles' %s-spp error (sampled) and "
            "the run that reaches it (exact), or the nearest sample count's (seconds; in brackets "
            "with `--no-previews`): the whole process; the shadow passes; scene load and BVH "
            "build; primary rays; writing oracle.exr; the preview PNG with the OpenImageIO module "
            "it loads (the write phase with previews less without); process start and exit (each "
            "run's whole time less its phases in oracle.json); everything but the shadow passes "
            "(each run's whole less its shadow passes); medians over the runs:"
            % spp_text(summary["reference_spp"]),
            "",
            "| size | oracle | target | its error | whole | shadow passes | load + BVH | primary | "
            "oracle.exr | preview PNG + module | start + exit | all but the shadow passes |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for case in summary["cases"]:
        ref = reference_row(case, summary["reference_spp"])
        for method in METHODS:
            out.append(fixed_costs_row(case, method, ref["mae"]))
    out.append("")
    for case in summary["cases"]:
        for c in case["cycles"]:
            if c["spp"] == summary["reference_spp"]:
                out += [goal_line(case, c), ""]
    return "\n".join(out)


def write_docs(text, docs):
    write_between_markers(docs, "cycles-compare", text)


def machine(load_start):
    cpu = "unknown CPU"
    try:
        for line in pathlib.Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    rev = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"],
                         stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True).stdout.strip()
    dirty = subprocess.run(["git", "-C", str(ROOT), "status", "--porcelain", "--untracked-files=no"],
                           stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True).stdout
    return {"cpu": cpu, "cores": os.cpu_count(), "system": platform.platform(),
            "date": datetime.date.today().isoformat(),
            "revision": (rev or "unknown") + ("+changes" if dirty.strip() else ""),
            "load_start": load_start, "load_end": os.getloadavg()[0]}


def main():
    ap = argparse.ArgumentParser(description="the oracle beside Blender Cycles (docs/benchmarks.md)")
    ap.add_argument("--case", action="append", type=parse_case, metavar="SIZE:SPP[,SPP...]",
                    help="an image size and Cycles' sample counts (default: 200:256,1024,4096 "
                         "and 512:1024)")
    ap.add_argument("--threads", type=int, default=2, help="threads for both (default 2)")
    ap.add_argument("--reps", type=int, default=3, help="timed runs per oracle target (default 3)")
    ap.add_argument("--reference-spp", type=int, default=1024,
                    help="the Cycles sample count the goal is stated at (default 1024)")
    ap.add_argument("--out", default=str(ROOT / "out" / "cycles-compare"))
    ap.add_argument("--no-docs", action="store_true", help="leave docs/benchmarks.md alone")
    ap.add_argument("--build", default=str(ROOT / "build"))
    args = ap.parse_args()
    if args.threads < 1 or args.reps < 1:
        ap.error("--threads and --reps must be at least 1")
    cases = args.case or [(200, [256, 1024, 4096]), (512, [1024])]
    blender = os.environ.get("BLENDER") or "blender"
    if not shutil.which(blender):
        skip("no %s on PATH (Debian: apt-get install blender python3-numpy; or set BLENDER)"
             % blender)
    load_start = os.getloadavg()[0]
    version = probe_blender(blender)
    ctx = Context(args)
    ctx.out.mkdir(parents=True, exist_ok=True)
    shown = [a for i, a in enumerate(sys.argv[1:])
             if a != "--build" and (i == 0 or sys.argv[i] != "--build")]
    summary = {"command": " ".join(["scripts/cycles-compare"] + shown),
               "threads": args.threads, "reps": args.reps, "reference_spp": args.reference_spp,
               "scene": str(SCENE.relative_to(ROOT)), "cases": []}
    for size, spps in cases:
        print("case %d x %d, Cycles at %s spp, %d threads" % (size, size, spps, args.threads))
        sys.stdout.flush()
        summary["cases"].append(run_case(ctx, size, spps, version))
    summary["machine"] = machine(load_start)
    text = tables(summary)
    (ctx.out / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    (ctx.out / "tables.md").write_text(text + "\n")
    print()
    print(text)
    if not args.no_docs:
        write_docs(text, DOCS)
        print("updated %s" % DOCS.relative_to(ROOT))


if __name__ == "__main__":
    main()
