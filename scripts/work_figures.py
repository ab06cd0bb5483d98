#!/usr/bin/env python3
"""scripts/work-figures: compares every shipped scene with one set of techniques and writes, per
scene and light, the techniques ranked by llvmpipe's milliseconds, by bytes_moved and by
fragments, and the three Pareto fronts of error against them, between the "BEGIN which-ranking"
and "END which-ranking" markers of a markdown file (docs/benchmarks-ranking.md). Measured, not
asserted."""
import json, pathlib, subprocess, sys
from doc_markers import write_between_markers

TECHNIQUES = ["basic", "slope-bias", "pcf:kernel=5", "hw-pcf", "pcss", "vsm", "esm", "evsm",
              "msm", "volume-zfail", "blur:radius=8,bilateral=on", "accumulate:samples=16"]
SIZE = (320, 240)
FRAMES = 3
COSTS = [("ms", "llvmpipe ms"), ("bytes", "bytes_moved"), ("fragments", "fragments")]
# Pairs whose relative GPU cost has been published (docs/benchmarks-ranking.md, below the tables): their
# ratio on each axis, per scene.
PAIRS = [("hw-pcf", "slope-bias"), ("msm", "vsm"), ("vsm", "basic")]


def compare(tool, scene, out):
    cmd = [tool, "compare", str(scene), "--width", str(SIZE[0]), "--height", str(SIZE[1]),
           "--frames", str(FRAMES), "--out", str(out)]
    for t in TECHNIQUES:
        cmd += ["--technique", t]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return json.loads((out / "metrics.json").read_text())


def frame_costs(metrics):
    """Per technique: the frame's llvmpipe milliseconds (cost.frame_ms, the wall time of a frame
    with the GL finished: every light's passes and the camera pass, the figure to compare
    techniques by on llvmpipe, docs/techniques.md) and the frame's bytes_moved and fragments, its
    lights' work summed (the camera pass's, the same for every technique, left out)."""
    out = {}
    for r in metrics["results"]:
        lights = r["lights"].values()
        out[r["label"]] = {"ms": next(iter(lights))["cost"]["frame_ms"],
                           "bytes": sum(m["cost"]["work"]["bytes_moved"] for m in lights),
                           "fragments": sum(m["cost"]["work"]["fragments"] for m in lights),
                           "taps": sum(m["cost"]["work"]["texture_taps"] for m in lights)}
    return out


def points(metrics, light, costs):
    """Per technique: the light's error (penumbra_mae on area lights, else mae) and the frame's
    three costs."""
    out = []
    for r in metrics["results"]:
        m = r["lights"][light]
        area = m.get("penumbra_mae") is not None
        out.append(dict(costs[r["label"]], label=r["label"],
                        error=m["penumbra_mae"] if area else m["mae"],
                        error_name="penumbra_mae" if area else "mae"))
    return out


def ranks(pts, key):
    """1 for the cheapest; equal costs share a rank."""
    order = sorted(pts, key=lambda p: p[key])
    rank = {}
    for i, p in enumerate(order):
        rank[p["label"]] = rank[order[i - 1]["label"]] if i and p[key] == order[i - 1][key] else i + 1
    return rank


def front(pts, key):
    """The settings no other is both cheaper and more accurate than (tradeoff.h's rule)."""
    kept = []
    for p in sorted(pts, key=lambda p: (p[key], p["error"])):
        if not kept or p["error"] < kept[-1]["error"]:
            kept.append(p)
    return [p["label"] for p in kept]


def spearman(a, b):
    """Spearman's rho of two rankings, ties at their average rank."""
    labels = list(a)
    def average(r):
        groups = {}
        for l in labels:
            groups.setdefault(r[l], []).append(l)
        out, at = {}, 1
        for k in sorted(groups):
            n = len(groups[k])
            for l in groups[k]:
                out[l] = at + (n - 1) / 2
            at += n
        return out
    ra, rb = average(a), average(b)
    n = len(labels)
    ma, mb = sum(ra.values()) / n, sum(rb.values()) / n
    cov = sum((ra[l] - ma) * (rb[l] - mb) for l in labels)
    va = sum((ra[l] - ma) ** 2 for l in labels) ** 0.5
    vb = sum((rb[l] - mb) ** 2 for l in labels) ** 0.5
    return cov / (va * vb) if va and vb else float("nan")


def si(v):
    for unit, scale in (("G", 1e9), ("M", 1e6), ("k", 1e3)):
        if v >= scale:
            return "%.3g %s" % (v / scale, unit)
    return "%d" % v


def scene_section(scene, metrics):
    costs = frame_costs(metrics)
    lights = list(metrics["results"][0]["lights"])
    cost_pts = [dict(c, label=l) for l, c in costs.items()]
    r = {key: ranks(cost_pts, key) for key, _ in COSTS}
    lines = [f"#### {scene}", "",
             "| technique | llvmpipe frame ms (rank) | bytes_moved (rank) | fragments (rank) | " +
             " | ".join(f"{l}: {points(metrics, l, costs)[0]['error_name']}" for l in lights) + " |",
             "|---" * (4 + len(lights)) + "|"]
    errors = {l: {p["label"]: p["error"] for p in points(metrics, l, costs)} for l in lights}
    for label in sorted(costs, key=lambda l: costs[l]["ms"]):
        c = costs[label]
        lines.append(f"| `{label}` | {c['ms']:.1f} ({r['ms'][label]}) | {si(c['bytes'])} "
                     f"({r['bytes'][label]}) | {si(c['fragments'])} ({r['fragments'][label]}) | " +
                     " | ".join(f"{errors[l][label]:.4f}" for l in lights) + " |")
    rho_b, rho_f = spearman(r["ms"], r["bytes"]), spearman(r["ms"], r["fragments"])
    lines += ["", f"Rank correlation with the llvmpipe milliseconds (Spearman, ties averaged): "
                  f"bytes_moved {rho_b:+.2f}, fragments {rho_f:+.2f}.", ""]
    for light in lights:
        pts = points(metrics, light, costs)
        fronts = {key: front(pts, key) for key, _ in COSTS}
        lines.append(f"Pareto fronts of {light}'s {pts[0]['error_name']}:")
        lines.append("")
        for key, name in COSTS:
            lines.append(f"- against {name}: " + ", ".join(f"`{l}`" for l in fronts[key]))
        ms = set(fronts["ms"])
        for key, name in COSTS[1:]:
            other = set(fronts[key])
            if other == ms:
                lines.append(f"- {name}'s front is the milliseconds'")
            else:
                gained = ", ".join(f"`{l}`" for l in fronts[key] if l not in ms) or "none"
                lost = ", ".join(f"`{l}`" for l in fronts["ms"] if l not in other) or "none"
                lines.append(f"- {name}'s front gains {gained} and loses {lost}")
        lines.append("")
    return lines, rho_b, rho_f


def main(tool, out_dir, doc, reuse=False):
    out_dir = pathlib.Path(out_dir)
    scenes = sorted(pathlib.Path("scenes").glob("*.scene.json"))
    body, rhos, ratios = [], [], []
    renderer = None
    for scene in scenes:
        name = scene.name.split(".")[0]
        print(f"== {name}", flush=True)
        if reuse and (out_dir / name / "metrics.json").exists():
            metrics = json.loads((out_dir / name / "metrics.json").read_text())
        else:
            metrics = compare(tool, scene, out_dir / name)
        renderer = metrics["gl"]["renderer"]
        lines, rb, rf = scene_section(name, metrics)
        ratios.append((name, frame_costs(metrics)))
        body += lines
        rhos.append((name, rb, rf))
    summary = ["| scene | Spearman ms ~ bytes_moved | Spearman ms ~ fragments |", "|---|---|---|"]
    summary += [f"| {s} | {rb:+.2f} | {rf:+.2f} |" for s, rb, rf in rhos]
    summary += ["", "Ratios of the frame's costs between techniques whose GPU cost has been "
                "published (below), per scene: llvmpipe ms / bytes_moved / fragments / "
                "texture_taps.", "",
                "| scene | " + " | ".join(f"`{a}` / `{b}`" for a, b in PAIRS) + " |",
                "|---" * (1 + len(PAIRS)) + "|"]
    for name, costs in ratios:
        cells = []
        for a, b in PAIRS:
            q = lambda k: costs[a][k] / costs[b][k] if costs[b][k] else float("inf")
            cells.append(" / ".join("%.2f" % q(k) for k in ("ms", "bytes", "fragments", "taps")))
        summary.append(f"| {name} | " + " | ".join(cells) + " |")
    text = "\n".join(
        [f"Made by `scripts/work-figures` ({SIZE[0]} x {SIZE[1]}, {FRAMES} timed frames, "
         f"techniques {', '.join('`%s`' % t for t in TECHNIQUES)} with their defaults; times on "
         f"{renderer}). Per scene: the frame's llvmpipe milliseconds (`cost.frame_ms`, the wall "
         "time of a frame with the GL finished, which docs/techniques.md says to compare by on "
         "llvmpipe: its timer queries charge some passes' work to others) and the frame's work "
         "(`cost.work` summed over the lights; the camera pass, the same for every technique, left "
         "out), each with the techniques' rank (1: the cheapest; equal counts share one), and each "
         "light's error (penumbra_mae on area lights, else mae); per light, the Pareto front of "
         "its error against each cost, and where the work's fronts differ from the "
         "milliseconds'.", ""] + summary + [""] + body)
    write_between_markers(doc, "which-ranking", text)
    print(f"updated {doc}")


if __name__ == "__main__":
    # --reuse: the runs already in OUT_DIR (their metrics.json), to rewrite the tables only.
    main(*sys.argv[1:4], reuse="--reuse" in sys.argv[4:])
