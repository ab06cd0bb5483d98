#!/usr/bin/env python3
"""scripts/sweep-figures: measures the sweep's overhead per task against plain compare runs and
runs the shipped bias sweep, and writes both tables into a markdown file between its markers."""
import csv, json, os, shutil, subprocess, sys, time
from doc_markers import replace_between_markers

OVERHEAD_SETTINGS = [f"slope-bias:alpha={a},min={m}" for a in (0.5, 1, 2) for m in (0.1, 0.5)]
SIZE = (320, 180)
FRAMES = 9
REPEATS = 3


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
                               "params": {"alpha": [0.5, 1, 2], "min": [0.1, 0.5]}}]},
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


def bias(tool, out):
    d = os.path.join(out, "bias")
    shutil.rmtree(d, ignore_errors=True)  # a whole run, not a resumed one
    t0 = time.perf_counter()
    subprocess.run([tool, "sweep", "scenes/sweeps/bias.json", "--out", d, "--jobs", "2",
                    "--quiet"], check=True, stdout=subprocess.DEVNULL)
    seconds = time.perf_counter() - t0
    m = json.load(open(os.path.join(d, "metrics.json")))
    best, defaults = {}, {}
    for r in m["results"]:
        if r.get("technique") != "slope-bias":  # the biases that need no tuning, at defaults
            for light, v in r["lights"].items():
                defaults.setdefault((r["task"]["scene"], light), {})[r["technique"]] = v
            continue
        for light, v in r["lights"].items():
            key = (r["task"]["scene"], light)
            b = best.setdefault(key, {"free": 0, "total": 0, "best": None})
            b["total"] += 1
            if v.get("acne_rate") != 0:
                continue
            b["free"] += 1
            pp = v.get("peter_panning_rate")
            pp = float("inf") if pp is None else pp
            if b["best"] is None or pp < b["best"][0]:
                b["best"] = (pp, r["swept"])
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
    return (f"`shadow-oracle sweep scenes/sweeps/bias.json --jobs 2`: {m['tasks']} tasks "
            f"({m['finished']} finished) in {seconds:.0f} s on {gl}. The report "
            f"(out/sweeps/bias/report.html) draws the whole alpha x min grid; here its answer, "
            "ties on peter-panning to the first setting in the spec's order.\n\n"
            + "\n".join(rows) + "\n" + untuned(defaults))


# The biases that need no tuning at their defaults: acne and peter-panning per scene and light,
# and which of them has neither on every one.
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
    verdict = ("free of both acne and peter-panning at its default on every shipped scene and "
               "light: " + (", ".join(none) if none else "none of them") +
               " (n/a: no `contact` effect, peter-panning not measured).")
    return ("\nThe biases that need no tuning (docs/techniques.md#biases-that-need-no-tuning), at "
            "their defaults, in the same sweep: " + verdict + "\n\n" + "\n".join(rows) + "\n")


def replace(doc, marker, body):
    return replace_between_markers(doc, marker, body)


def main(tool, out, doc_path):
    os.makedirs(out, exist_ok=True)
    doc = open(doc_path).read()
    doc = replace(doc, "sweep overhead", overhead(tool, os.path.join(out, "overhead")))
    doc = replace(doc, "bias sweep", bias(tool, out))
    open(doc_path, "w").write(doc)
    print(f"updated {doc_path}")


if __name__ == "__main__":
    main(*sys.argv[1:4])
