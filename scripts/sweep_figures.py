#!/usr/bin/env python3
"""scripts/sweep-figures: measures the sweep's overhead per task against plain compare runs and
runs the shipped bias sweep, and writes both tables into a markdown file between its markers."""
import argparse, csv, json, os, shutil, subprocess, sys, time
from doc_markers import replace_between_markers

OVERHEAD_SETTINGS = [f"slope-bias:slope_factor={a},min={m}" for a in (0.5, 1, 2) for m in (0.1, 0.5)]
SIZE = (320, 180)
FRAMES = 9
REPEATS = 3
SLOPE_DEFAULT = {"slope_factor": 1, "min": 0.1}  # `shadow-oracle techniques`


def run(cmd):
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - t0


def overhead(tool, out):
    """Whole sweeps (oracle present, rows removed) against one compare per setting, REPEATS
    times each, alternating; the median of each."""
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    spec = os.path.join(out, "spec.json")
    scene = os.path.abspath("scenes/contact_box.scene.json")
    json.dump({"sweep_format": 1, "name": "overhead", "scenes": [scene], "width": SIZE[0],
               "height": SIZE[1], "frames": FRAMES,
               "techniques": [{"name": "slope-bias",
                               "params": {"slope_factor": [0.5, 1, 2], "min": [0.1, 0.5]}}]},
              open(spec, "w"))
    sweep_dir = os.path.join(out, "sweep")
    run([tool, "sweep", spec, "--out", sweep_dir, "--quiet"])  # traces the oracle once
    sweeps, compares, inside = [], [], []
    for _ in range(REPEATS):
        shutil.rmtree(os.path.join(sweep_dir, "rows"))
        sweeps.append(run([tool, "sweep", spec, "--out", sweep_dir, "--quiet"]))
        rows = os.path.join(sweep_dir, "rows")
        inside.append(sum(json.load(open(os.path.join(rows, f)))["seconds"]
                          for f in os.listdir(rows) if f.endswith(".json")))
        total = 0.0
        for k, label in enumerate(OVERHEAD_SETTINGS):
            total += run([tool, "compare", scene, "--technique", label, "--width", str(SIZE[0]),
                          "--height", str(SIZE[1]), "--frames", str(FRAMES), "--cache",
                          os.path.join(sweep_dir, "oracles"), "--out",
                          os.path.join(out, f"compare{k}")])
        compares.append(total)
    median = lambda v: sorted(v)[len(v) // 2]
    n = len(OVERHEAD_SETTINGS)
    s, c, w = median(sweeps) / n, median(compares) / n, median(inside) / n
    gl = json.load(open(os.path.join(sweep_dir, "metrics.json")))["results"][0]["gl"]["renderer"]
    return (f"{n} slope-bias settings on `scenes/contact_box.scene.json`, {SIZE[0]} x {SIZE[1]}, "
            f"{FRAMES} timed frames, {gl}, one task at a time; the median of {REPEATS} runs, each "
            "with the oracle already present. The sweep's time is the whole command (plan, one "
            "oracle task, the tasks as child processes, the merge and its report) over the "
            "settings; compare's is one `compare --technique SETTING` per setting (its report "
            "and oracle.exr included, which a sweep task does not write).\n\n"
            "The third row is the work of a task as the task measures it (from the plan read to its "
            "row written: the scene, the oracle from the folder, GL, the render, the metrics); what "
            "the sweep adds to that (processes, the plan, the oracle task, the merge) is the last.\n\n"
            "| per setting | seconds |\n|---|---|\n"
            f"| `sweep --jobs 1`, the whole command | {s:.3f} |\n| `compare` | {c:.3f} |\n"
            f"| a sweep task's own work | {w:.3f} |\n"
            f"| the sweep against `compare` | {100 * (s - c) / c:+.1f}% |\n"
            f"| the sweep against its tasks' own work | {100 * (s - w) / w:+.1f}% |\n")


def bias_spec(out, size):
    """scenes/sweeps/bias.json as shipped, or at SIZE (W, H): a copy with its scene globs made
    absolute and its size replaced, so that the figures can be made at a size 2 cores allow."""
    shipped = "scenes/sweeps/bias.json"
    if size is None:
        return shipped
    spec = json.load(open(shipped))
    folder = os.path.dirname(os.path.abspath(shipped))
    spec["scenes"] = [os.path.normpath(os.path.join(folder, g)) for g in spec["scenes"]]
    spec["width"], spec["height"] = size
    path = os.path.join(out, "bias-spec.json")
    json.dump(spec, open(path, "w"), indent=2)
    return path


def run_bias(tool, out, size):
    d = os.path.join(out, "bias")
    shutil.rmtree(d, ignore_errors=True)  # a whole run, not a resumed one
    spec = bias_spec(out, size)
    t0 = time.perf_counter()
    subprocess.run([tool, "sweep", spec, "--out", d, "--jobs", "2", "--quiet"], check=True,
                   stdout=subprocess.DEVNULL)
    json.dump({"seconds": time.perf_counter() - t0, "spec": spec},
              open(os.path.join(d, "figures-run.json"), "w"))


def short_scene(scene):
    return scene[3:] if scene.startswith("../") else os.path.relpath(scene, "scenes")


def bias(out):
    d = os.path.join(out, "bias")
    run = json.load(open(os.path.join(d, "figures-run.json")))
    m = json.load(open(os.path.join(d, "metrics.json")))
    best, defaults = {}, {}
    for r in m["results"]:
        scene = short_scene(r["task"]["scene"])
        swept = r.get("swept") or {}
        if r.get("technique") != "slope-bias" or swept == SLOPE_DEFAULT:
            # the biases that need no tuning, and slope-bias's own default, at their defaults
            name = r["technique"] if r.get("technique") != "slope-bias" else "slope-bias (default)"
            for light, v in r["lights"].items():
                defaults.setdefault((scene, light), {})[name] = v
        if r.get("technique") != "slope-bias":
            continue
        for light, v in r["lights"].items():
            b = best.setdefault((scene, light), {"free": 0, "total": 0, "best": None})
            b["total"] += 1
            if v.get("acne_rate") != 0:
                continue
            b["free"] += 1
            pp = v.get("peter_panning_rate")
            pp = float("inf") if pp is None else pp
            if b["best"] is None or pp < b["best"][0]:
                b["best"] = (pp, swept)
    rows = ["| scene | light | acne-free settings | no acne, least peter-panning | "
            "its peter-panning rate |", "|---|---|---|---|---|"]
    for (scene, light), b in sorted(best.items()):
        if b["best"] is None:
            rows.append(f"| `{scene}` | {light} | 0 of {b['total']} | every setting has acne | |")
            continue
        pp, swept = b["best"]
        setting = ", ".join(f"{k}={v:g}" for k, v in swept.items())
        rate = ("not measured (no `contact` effect: the first acne-free setting, the least bias)"
                if pp == float("inf") else f"{pp:.4f}")
        rows.append(f"| `{scene}` | {light} | {b['free']} of {b['total']} | {setting} | {rate} |")
    gl = m["results"][0]["gl"]["renderer"]
    size = json.load(open(run["spec"]))
    command = ("`shadow-oracle sweep scenes/sweeps/bias.json --jobs 2`"
               if run["spec"] == "scenes/sweeps/bias.json" else
               f"`shadow-oracle sweep` of scenes/sweeps/bias.json at {size['width']} x "
               f"{size['height']} (`scripts/sweep-figures --size {size['width']}x{size['height']}`"
               ", `--jobs 2`, niced, on 2 shared cores)")
    return (f"{command}: {m['tasks']} tasks ({m['finished']} finished) in {run['seconds']:.0f} s "
            f"on {gl}, over the shipped scenes (`scenes/*.scene.json`) and the real ones "
            "(`scenes/real/*/*.scene.json`). The report (out/sweeps/bias/report.html) draws the "
            "whole slope_factor x min grid; here its answer, ties on peter-panning to the first setting "
            "in the spec's order.\n\n" + "\n".join(rows) + "\n" + untuned(defaults))


# The biases that need no tuning at their defaults (and slope-bias's): acne and peter-panning per
# scene and light, and which of them has neither on every one; where none does, what breaks each.
ACNE_BAR = 0.01  # issue 54's bar for receiver-plane and oriented-bias (now half-texel-bias)


def verdict(method, defaults):
    lights = [(k, by[method]) for k, by in sorted(defaults.items()) if method in by]
    acne = [(v["acne_rate"], k) for k, v in lights if v.get("acne_rate")]
    over = [(a, k) for a, k in acne if a > ACNE_BAR]
    pp = [(v["peter_panning_rate"], k) for k, v in lights if v.get("peter_panning_rate")]
    measured = sum(1 for _, v in lights if v.get("peter_panning_rate") is not None)
    where = lambda items: ", ".join(f"{k[0].split('/')[-1].split('.')[0]} {k[1]} {a:.4f}"
                                    for a, k in sorted(items, reverse=True))
    text = f"**{method}**: "
    text += (f"acne on {len(acne)} of {len(lights)} lights" if acne else "no acne on any light")
    if acne:
        text += f" (the most: {where(sorted(acne, reverse=True)[:1])})"
        text += (f"; above {ACNE_BAR} on {len(over)}: {where(over)}" if over
                 else f"; none above {ACNE_BAR}")
    text += (f"; peter-panning on {len(pp)} of the {measured} lights that measure it: {where(pp)}"
             if pp else f"; no peter-panning on the {measured} lights that measure it")
    return text + "."


def untuned(defaults):
    methods = sorted({t for v in defaults.values() for t in v})
    if not methods:
        return ""
    rows = ["| scene | light | " + " | ".join(f"{t}: acne, peter-panning" for t in methods) + " |",
            "|---|---|" + "---|" * len(methods)]
    clean = {t: True for t in methods}
    for (scene, light), by in sorted(defaults.items()):
        cells = []
        for t in methods:
            v = by.get(t, {})
            acne, pp = v.get("acne_rate"), v.get("peter_panning_rate")
            clean[t] &= acne == 0 and (pp is None or pp == 0)
            cells.append(f"{acne:.4f}, " + ("n/a" if pp is None else f"{pp:.4f}")
                         if acne is not None else "")
        rows.append(f"| `{scene}` | {light} | " + " | ".join(cells) + " |")
    none = [t for t in methods if clean[t]]
    with_pp = sorted({k[0].split("/")[-1].split(".")[0] for k, by in defaults.items()
                      if any(v.get("peter_panning_rate") is not None for v in by.values())})
    return ("\nThe biases that need no tuning (docs/techniques.md#biases-that-need-no-tuning) and "
            "slope-bias (slope_factor=1, min=0.1), each at its default, in the same sweep. Free of both "
            "acne (not one pixel) and peter-panning on every shipped and real scene and light: "
            + (", ".join(none) if none else "none of them") + ". Peter-panning is measured only "
            "where the scene has the `contact` effect (" + ", ".join(with_pp) + "; n/a "
            "elsewhere). What breaks each:\n\n"
            + "\n".join("- " + verdict(t, defaults) for t in methods) + "\n\n"
            + "\n".join(rows) + "\n")


def replace(doc, marker, body):
    return replace_between_markers(doc, marker, body)


def main(argv):
    """TOOL OUT DOC [--size WxH] [--bias-only] [--table-only]: --size runs the bias sweep at that
    size; --bias-only skips the overhead runs; --table-only rewrites the bias table from the last
    run in OUT/bias without running anything."""
    parser = argparse.ArgumentParser()
    parser.add_argument("tool")
    parser.add_argument("out")
    parser.add_argument("doc")
    parser.add_argument("--size", type=lambda s: tuple(int(v) for v in s.split("x")))
    parser.add_argument("--bias-only", action="store_true")
    parser.add_argument("--table-only", action="store_true")
    a = parser.parse_args(argv)
    os.makedirs(a.out, exist_ok=True)
    doc = open(a.doc).read()
    if not (a.bias_only or a.table_only):
        doc = replace(doc, "sweep overhead", overhead(a.tool, os.path.join(a.out, "overhead")))
    if not a.table_only:
        run_bias(a.tool, a.out, a.size)
    doc = replace(doc, "bias sweep", bias(a.out))
    open(a.doc, "w").write(doc)
    print(f"updated {a.doc}")


if __name__ == "__main__":
    main(sys.argv[1:])
