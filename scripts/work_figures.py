#!/usr/bin/env python3
"""scripts/work-figures: compares every shipped scene with one set of techniques and writes, per
scene and light, the techniques ranked by llvmpipe's milliseconds, by bytes_moved and by
fragments, and the three Pareto fronts of error against them, between the "BEGIN which-ranking"
and "END which-ranking" markers of a markdown file (docs/benchmarks.md). Measured, not asserted."""
import json, pathlib, re, subprocess, sys

TECHNIQUES = ["basic", "slope-bias", "pcf:kernel=5", "hw-pcf", "pcss", "vsm", "esm", "evsm",
              "msm", "volume-zfail", "blur:radius=8,bilateral=on", "accumulate:samples=16"]
SIZE = (320, 240)
FRAMES = 3
COSTS = [("ms", "llvmpipe ms"), ("bytes", "bytes_moved"), ("fragments", "fragments")]


def compare(tool, scene, out):
    cmd = [tool, "compare", str(scene), "--width", str(SIZE[0]), "--height", str(SIZE[1]),
           "--frames", str(FRAMES), "--out", str(out)]
    for t in TECHNIQUES:
        cmd += ["--technique", t]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return json.loads((out / "metrics.json").read_text())


def points(metrics, light):
    """Per technique: its error (penumbra_mae on area lights, else mae) and three costs: the
    light's passes' llvmpipe milliseconds (shadow_map_ms + visibility_ms, medians), bytes_moved
    and fragments of a frame."""
    out = []
    for r in metrics["results"]:
        m = r["lights"][light]
        c = m["cost"]
        area = m.get("penumbra_mae") is not None
        out.append({"label": r["label"], "error": m["penumbra_mae"] if area else m["mae"],
                    "error_name": "penumbra_mae" if area else "mae",
                    "ms": c["shadow_map_ms"] + c["visibility_ms"],
                    "bytes": c["work"]["bytes_moved"], "fragments": c["work"]["fragments"]})
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
    labels = list(a)
    n = len(labels)
    if n < 2:
        return float("nan")
    d2 = sum((a[l] - b[l]) ** 2 for l in labels)
    return 1 - 6 * d2 / (n * (n * n - 1))


def si(v):
    for unit, scale in (("G", 1e9), ("M", 1e6), ("k", 1e3)):
        if v >= scale:
            return "%.3g %s" % (v / scale, unit)
    return "%d" % v


def light_section(scene, light, pts):
    r = {key: ranks(pts, key) for key, _ in COSTS}
    fronts = {key: front(pts, key) for key, _ in COSTS}
    lines = [f"#### {scene}, {light} ({pts[0]['error_name']})", "",
             "| technique | error | llvmpipe ms (rank) | bytes_moved (rank) | fragments (rank) |",
             "|---|---|---|---|---|"]
    for p in sorted(pts, key=lambda p: p["ms"]):
        lines.append(f"| `{p['label']}` | {p['error']:.4f} | {p['ms']:.1f} ({r['ms'][p['label']]}) | "
                     f"{si(p['bytes'])} ({r['bytes'][p['label']]}) | "
                     f"{si(p['fragments'])} ({r['fragments'][p['label']]}) |")
    lines.append("")
    rho_b, rho_f = spearman(r["ms"], r["bytes"]), spearman(r["ms"], r["fragments"])
    lines.append(f"Rank correlation with llvmpipe ms (Spearman): bytes_moved {rho_b:+.2f}, "
                 f"fragments {rho_f:+.2f}.")
    lines.append("")
    for key, name in COSTS:
        lines.append(f"- Pareto front against {name}: " + ", ".join(f"`{l}`" for l in fronts[key]))
    ms = set(fronts["ms"])
    for key, name in COSTS[1:]:
        other = set(fronts[key])
        if other == ms:
            lines.append(f"- against {name}: the same front as llvmpipe ms")
        else:
            gained = ", ".join(f"`{l}`" for l in fronts[key] if l not in ms) or "none"
            lost = ", ".join(f"`{l}`" for l in fronts["ms"] if l not in other) or "none"
            lines.append(f"- against {name}: joins the front {gained}; leaves it {lost}")
    lines.append("")
    return lines, rho_b, rho_f


def main(tool, out_dir, doc):
    out_dir = pathlib.Path(out_dir)
    scenes = sorted(pathlib.Path("scenes").glob("*.scene.json"))
    body, rhos = [], []
    renderer = None
    for scene in scenes:
        name = scene.name.split(".")[0]
        print(f"== {name}", flush=True)
        metrics = compare(tool, scene, out_dir / name)
        renderer = metrics["gl"]["renderer"]
        lights = list(metrics["results"][0]["lights"])
        for light in lights:
            lines, rb, rf = light_section(name, light, points(metrics, light))
            body += lines
            rhos.append((name, light, rb, rf))
    summary = ["| scene, light | Spearman ms ~ bytes_moved | Spearman ms ~ fragments |",
               "|---|---|---|"]
    summary += [f"| {s}, {l} | {rb:+.2f} | {rf:+.2f} |" for s, l, rb, rf in rhos]
    text = "\n".join(
        [f"Made by `scripts/work-figures` ({SIZE[0]} x {SIZE[1]}, {FRAMES} timed frames, "
         f"techniques {', '.join('`%s`' % t for t in TECHNIQUES)} with their defaults; times on "
         f"{renderer}). Per light: the error (penumbra_mae on area lights, else mae), the light's "
         "passes' llvmpipe milliseconds (`cost.shadow_map_ms` + `cost.visibility_ms`) and its work "
         "of a frame (`cost.work`), each cost with the techniques' rank (1: the cheapest); the "
         "Pareto front of the error against each cost, and where the work's fronts differ from "
         "the milliseconds'.", ""] + summary + [""] + body)
    doc = pathlib.Path(doc)
    old = doc.read_text()
    new = re.sub(r"(<!-- BEGIN which-ranking[^\n]*-->\n).*?(<!-- END which-ranking -->)",
                 lambda m: m.group(1) + "\n" + text + "\n" + m.group(2), old, flags=re.S)
    if new == old and "BEGIN which-ranking" not in old:
        sys.exit(f"error: {doc} lacks the which-ranking markers")
    doc.write_text(new)
    print(f"updated {doc}")


if __name__ == "__main__":
    main(*sys.argv[1:4])
