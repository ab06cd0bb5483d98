#!/usr/bin/env python3
"""Writes docs/engines.md's tables (see engines-figures) from a sweep of examples/web/sweep:
its metrics_wide.csv (one row per task and light). The headline over the punctual lights only
(directional, spot, point: what the engines model), per kind: each engine's default and typical
rows (entries ENGINE-default, ENGINE-typical), its best entry per scene light, and the built-in
techniques at each setting swept (the matched map sizes). The area lights' stand-ins apart, graded
against the area truth and, given a sweep of the same scenes with `penumbra` off
(--point-truth), against the point truth. Per scene and light: each engine's defaults beside the
built-in techniques; per engine entry the setting of least mae; per engine the artifact its
defaults get most wrong. Nothing is typed by hand."""
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


ENGINES = ("three", "babylon", "playcanvas", "filament", "three-webgpu", "babylon-webgpu", "galacean")
# The lights an engine models; the others (rect, disk, sphere, polygon) reach it as stand-ins.
KINDS = (("directional", "sun"), ("spot", "spot"), ("point", "point"))


def is_engine(row):
    return row["technique"].split("-")[0] in ENGINES


def engine_of(row):
    """The engine of an entry ENGINE-NAME: the longest engine name it starts with."""
    return max((e for e in ENGINES if row["technique"].startswith(e + "-")), key=len)


def light_types(rows, bases):
    """(scene, light) -> the light's type, from each scene file (the csv names it; a relative path
    is tried against each sweep's folder and its parent)."""
    types = {}
    for r in rows:
        if (r["scene"], r["light"]) in types:
            continue
        path = pathlib.Path(r["scene"])
        found = [c for c in [path] + [b / path for b in bases] if c.is_file()]
        if not found:
            sys.exit(f"error: {r['scene']}: scene file not found (for the light types)")
        for light in json.load(open(found[0]))["lights"]:
            types[(r["scene"], light["name"])] = light["type"]
    return types


# Rows that are not the engine's shadows but a failure of this harness's setup on it, left out of
# every table (examples/web/README.md says why), as {engine: (light types)}. None now:
# babylon-webgpu's directional and point rows were such a failure until its page called the
# engine's beginFrame/endFrame around each frame.
BROKEN = {}


def drop_broken(rows, types):
    return [r for r in rows if not (is_engine(r) and types[(r["scene"], r["light"])] in
                                    BROKEN.get(engine_of(r), ()))]


def mean(vals):
    return sum(vals) / len(vals) if vals else None


def headline_rows(rows, types):
    """Per row of the headline, (name, {kind: [mae per scene light]}): each engine's default and
    typical entries, its best entry per scene light (the grid's third row), and the built-in
    techniques at each setting swept (the matched map sizes), over the punctual lights only."""
    punctual = [r for r in rows if types[(r["scene"], r["light"])] in dict(KINDS)]
    out = []
    for engine in ENGINES:
        rs = [r for r in punctual if is_engine(r) and engine_of(r) == engine]
        if not rs:
            continue
        for preset in ("default", "typical"):
            got = [r for r in rs if r["technique"] == f"{engine}-{preset}"]
            if got:
                out.append((f"{engine} {preset}", by_kind(got, types)))
        best = {}
        for r in rs:
            key = (r["scene"], r["light"])
            if key not in best or num(r["mae"]) < num(best[key]["mae"]):
                best[key] = r
        out.append((f"{engine} best of {len({r['technique'] for r in rs})} entries", by_kind(best.values(), types)))
    for label in sorted({r["label"] for r in punctual if not is_engine(r)}):
        out.append((label, by_kind([r for r in punctual if r["label"] == label], types)))
    return out


def by_kind(rs, types):
    kinds = defaultdict(list)
    for r in rs:
        kinds[types[(r["scene"], r["light"])]].append(num(r["mae"]))
    return kinds


def headline_table(rows, types):
    head = ("| renderer, row | " + " | ".join(f"{name} mae (lights)" for _, name in KINDS) +
            " | punctual lights mae (lights) |\n|" + "---|" * (2 + len(KINDS)) + "\n")
    lines = []
    for name, kinds in headline_rows(rows, types):
        every = [v for k, _ in KINDS for v in kinds.get(k, [])]
        cells = [f"{mean(kinds[k]):.4g} ({len(kinds[k])})" if kinds.get(k) else "" for k, _ in KINDS]
        lines.append("| " + " | ".join([name] + cells + [f"{mean(every):.4g} ({len(every)})"]) + " |")
    return head + "\n".join(lines)


def standin_table(rows, types, point_rows):
    """The area lights an engine draws as a spot or point stand-in: each engine row's mae against
    the area truth, and against the point truth (the same light as a point at its centre: the
    scene with `penumbra` off) where a sweep of it is given."""
    point = {(scene_name(r), r["light"], r["label"]): num(r["mae"]) for r in point_rows}
    head = ("| scene | light | renderer, setting | mae against the area truth | mae against the point truth |\n"
            "|---|---|---|---|---|\n")
    lines = []
    for r in rows:
        t = types[(r["scene"], r["light"])]
        if t in dict(KINDS) or (is_engine(r) and not r["technique"].endswith(("-default", "-typical"))):
            continue
        # The built-in techniques' rows stay, at every matched size: they draw the area light itself.
        p = point.get((scene_name(r), r["light"], r["label"]))
        lines.append((scene_name(r), r["light"], r["label"], "| " + " | ".join(
            [scene_name(r), f"{r['light']} ({t})", r["label"], cell(num(r["mae"])),
             cell(p) if p is not None else
             # A setting the point sweep could not render is left out there (its log says why).
             "(not rendered in the point-truth sweep)" if point_rows else "(no point-truth sweep given)"]) + " |"))
    return head + "\n".join(l for *_, l in sorted(lines))


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
    for engine in ENGINES:
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


def readme_line(rows, types):
    """The README's line: over the punctual lights only, each engine's default and typical mean
    mae beside the built-in baselines, ranked, and the link."""
    ranked = []
    for name, kinds in headline_rows(rows, types):
        if " best of " in name:
            continue
        every = [v for k, _ in KINDS for v in kinds.get(k, [])]
        ranked.append((mean(every), name, len(every)))
    n = max(c for *_, c in ranked)
    return (f"Over the punctual lights (sun, spot, point: {n} scene lights), mean mae: " +
            ", ".join(f"{name} {m:.3g}" + (f" (over {c} only)" if c != n else "") for m, name, c in sorted(ranked)) +
            " ([docs/engines.md](docs/engines.md); area lights' stand-ins in their own table there).")


def main():
    args = sys.argv[1:]
    point_sweeps = []
    while "--point-truth" in args:  # a sweep of the same scenes with `penumbra` off
        i = args.index("--point-truth")
        point_sweeps.append(pathlib.Path(args[i + 1]))
        del args[i:i + 2]
    if len(args) < 3:
        sys.exit("usage: engines_figures.py [--point-truth SWEEP_DIR]... SWEEP_DIR [SWEEP_DIR ...] DOC.md README.md")
    # Several sweeps' rows join into one table (e.g. a scene swept later on its own).
    sweeps = [pathlib.Path(a) for a in args[:-2]]
    doc, readme = args[-2], args[-1]
    rows = [r for sweep in sweeps for r in read_rows(sweep)]
    types = light_types(rows, [b for s in sweeps for b in (s, s.parent)])
    rows = drop_broken(rows, types)
    point_rows = [r for sweep in point_sweeps for r in read_rows(sweep)]
    metas = [json.load(open(sweep / "metrics.json")) for sweep in sweeps]
    renderers = sorted({r.get("renderer", "") for m in metas for r in m["results"]
                        if r.get("renderer")})
    names = " and ".join(f"`{sweep.parent.name}/{sweep.name}/metrics_wide.csv`" for sweep in sweeps)
    finished = sum(m.get("finished", 0) for m in metas)
    tasks = sum(m.get("tasks", 0) for m in metas)
    source = (f"From {names} ({finished} of {tasks} tasks finished); engines rendered by "
              f"{'; '.join(renderers)}.")
    write_between_markers(doc, "engines-headline", source + "\n\n" + headline_table(rows, types))
    write_between_markers(doc, "engines-standins", standin_table(rows, types, point_rows))
    write_between_markers(doc, "engines-summary", source + "\n\n" + summary(rows))
    write_between_markers(doc, "engines-defaults", defaults_table(rows))
    write_between_markers(doc, "engines-best", best_table(rows))
    write_between_markers(readme, "engines-readme", readme_line(rows, types))


if __name__ == "__main__":
    main()
