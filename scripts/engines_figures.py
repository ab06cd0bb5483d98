#!/usr/bin/env python3
"""Writes docs/engines.md's tables (see engines-figures) from a sweep of examples/web/sweep:
its metrics_wide.csv (one row per task and light). Per scene and light: each engine's defaults
(entries named ENGINE-default) beside the built-in techniques; per engine entry the setting of
least mae; per engine the artifact its defaults get most wrong. Nothing is typed by hand."""
import csv
import json
import pathlib
import sys
from collections import defaultdict
from doc_markers import write_between_markers

ARTIFACTS = [("acne_rate", "acne"), ("peter_panning_rate", "peter-panning"),
             ("aliasing_rate", "aliasing"), ("light_bleeding_rate", "light bleeding"),
             ("penumbra_spread_rate", "penumbra spread"), ("penumbra_mae", "penumbra mae")]


# Every error class of a pixel (raster_compare/compare/artifacts.h), for the defaults' summary.
CLASSES = ARTIFACTS[:5] + [("other_false_shadow_rate", "other false shadow"),
                           ("other_false_lit_rate", "other false lit")]


def num(text):
    return None if text in ("", None) else float(text)


def cell(v, digits=4):
    return "" if v is None else f"{v:.{digits}g}"


def read_rows(sweep):
    rows = list(csv.DictReader(open(sweep / "metrics_wide.csv", newline="")))
    if not rows:
        sys.exit(f"error: {sweep}/metrics_wide.csv: no rows")
    return rows


def scene_name(row):
    return pathlib.Path(row["scene"]).name.split(".")[0]


def is_engine(row):
    return row["technique"].split("-")[0] in ("three", "babylon", "playcanvas", "filament")


def metrics_cells(r):
    return [cell(num(r["mae"]))] + [cell(num(r[k])) for k, _ in ARTIFACTS]


def defaults_table(rows):
    head = ("| scene | light | renderer, setting | mae | " + " | ".join(n for _, n in ARTIFACTS) +
            " | frame ms | memory MiB |\n|" + "---|" * (6 + len(ARTIFACTS)) + "\n")
    lines = []
    for r in rows:
        t = r["technique"]
        if is_engine(r) and not t.endswith("-default"):
            continue
        if not is_engine(r) and ":" in r["label"]:
            continue  # a built-in technique's grid: its defaults alone stand beside the engines'
        mem = num(r["cost.memory_bytes"])
        lines.append((scene_name(r), r["light"], t, "| " + " | ".join(
            [scene_name(r), r["light"], r["label"]] + metrics_cells(r) +
            [cell(num(r["cost.frame_ms"]), 3), "" if mem is None else f"{mem / 2**20:.3g}"]) + " |"))
    return head + "\n".join(l for *_, l in sorted(lines))


def best_table(rows):
    by_entry = defaultdict(list)
    for r in rows:
        if is_engine(r):
            by_entry[(scene_name(r), r["light"], r["technique"])].append(r)
    head = ("| scene | light | entry | settings | mae | " + " | ".join(n for _, n in ARTIFACTS) +
            " | settings tried |\n|" + "---|" * (6 + len(ARTIFACTS)) + "\n")
    lines = []
    for (scene, light, entry), rs in sorted(by_entry.items()):
        best = min(rs, key=lambda r: num(r["mae"]))
        settings = best["label"].split(":", 1)[1] if ":" in best["label"] else "(its own)"
        lines.append("| " + " | ".join([scene, light, entry, settings] + metrics_cells(best) +
                                       [str(len(rs))]) + " |")
    return head + "\n".join(lines)


def setting_in_words(name, values):
    """One default setting over an engine's rows: its value where every scene light has the same,
    else its range (a default fitted per scene, e.g. a shadow distance that follows the scene)."""
    vals = sorted({v.strip('"') for v in values if v != ""})
    if len(vals) == 1:
        return f"{name} {vals[0]}"
    nums = [num(v) for v in vals]
    if all(n is not None for n in nums):
        return f"{name} per scene, {min(nums):.4g} to {max(nums):.4g}"
    return f"{name} per scene ({len(vals)} values)"


def default_stats(rows):
    """Per engine with an ENGINE-default entry: (entry, its settings in words, mean mae, scene
    lights, (mean rate, class, scene lights where it applies) of its two largest error classes, its
    worst scene light in words)."""
    out = []
    for engine in ("three", "babylon", "playcanvas", "filament"):
        rs = [r for r in rows if r["technique"] == engine + "-default"]
        if not rs:
            continue
        means = []
        for key, name in CLASSES:
            vals = [num(r[key]) for r in rs if num(r[key]) is not None]
            if vals:
                means.append((sum(vals) / len(vals), name, len(vals)))
        mae = sum(num(r["mae"]) for r in rs) / len(rs)
        params = ", ".join(setting_in_words(k[6:], [r[k] for r in rs])
                           for k in sorted(rs[0]) if k.startswith("param.") and rs[0][k] != "")
        worst_row = max(rs, key=lambda r: num(r["mae"]))
        worst_at = f"{scene_name(worst_row)} {worst_row['light']} (mae {num(worst_row['mae']):.3g}" + "".join(
            f", {name} {num(worst_row[key]):.3g}" for key, name in
            (("umbra_mae", "umbra mae"), ("penumbra_mae", "penumbra mae"), ("lit_mae", "lit mae"))
            if num(worst_row[key]) is not None) + ")"
        out.append((rs[0]["technique"], params, mae, len(rs), sorted(means, reverse=True)[:2], worst_at))
    return out


def summary(rows):
    """One sentence per engine: its defaults' largest artifact rate, averaged over scene lights."""
    def rate(c):
        return f"{c[1]} (mean rate {c[0]:.3g} over the {c[2]} scene lights where it applies)"
    return "\n".join(
        f"- **{entry}** ({params}): mean mae {mae:.4g} over {n} scene lights; its largest error "
        f"classes are {' and '.join(rate(c) for c in worst)}; its worst scene light is {worst_at}."
        for entry, params, mae, n, worst, worst_at in default_stats(rows))


def readme_line(rows):
    """The README's line: each engine's defaults, mean mae and largest artifact, and the link."""
    return "; ".join(f"{entry} mean mae {mae:.3g}, most often wrong as {worst[0][1]} "
                     f"(mean rate {worst[0][0]:.3g})"
                     for entry, _, mae, _, worst, _ in default_stats(rows)) + \
        " ([docs/engines.md](docs/engines.md))."


def main():
    if len(sys.argv) < 4:
        sys.exit("usage: engines_figures.py SWEEP_DIR [SWEEP_DIR ...] DOC.md README.md")
    # Several sweeps' rows join into one table (e.g. a scene swept later on its own).
    sweeps = [pathlib.Path(a) for a in sys.argv[1:-2]]
    doc, readme = sys.argv[-2], sys.argv[-1]
    rows = [r for sweep in sweeps for r in read_rows(sweep)]
    metas = [json.load(open(sweep / "metrics.json")) for sweep in sweeps]
    renderers = sorted({r.get("renderer", "") for m in metas for r in m["results"]
                        if r.get("renderer")})
    names = " and ".join(f"`{sweep.parent.name}/{sweep.name}/metrics_wide.csv`" for sweep in sweeps)
    finished = sum(m.get("finished", 0) for m in metas)
    tasks = sum(m.get("tasks", 0) for m in metas)
    source = (f"From {names} ({finished} of {tasks} tasks finished); engines rendered by "
              f"{'; '.join(renderers)}.")
    write_between_markers(doc, "engines-summary", source + "\n\n" + summary(rows))
    write_between_markers(doc, "engines-defaults", defaults_table(rows))
    write_between_markers(doc, "engines-best", best_table(rows))
    write_between_markers(readme, "engines-readme", readme_line(rows))


if __name__ == "__main__":
    main()
