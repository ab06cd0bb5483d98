#!/usr/bin/env python3
"""Writes the lightmap tables (scripts/lightmap-table) from the sweep's merged metrics.json
(scenes/sweeps/lightmap.json) and bench_lightmap's JSON into a markdown file between its
"BEGIN lightmap tables" and "END lightmap tables" markers."""
import json, sys
from doc_markers import write_between_markers

FILTERS = ["nearest", "bilinear", "bicubic"]


def fmt(v, digits):
    return "n/a" if v is None else f"{v:.{digits}f}"


def load_sweep(path):
    """{(scene, light): {"lightmap": {(density, filter, dilate): row}, "baseline": row}}"""
    m = json.load(open(path))
    out = {}
    for r in m["results"]:
        scene = r["task"]["scene"].split("/")[-1].split(".")[0]
        p = r["parameters"]
        for light, row in r["lights"].items():
            entry = out.setdefault((scene, light), {"lightmap": {}, "baseline": None})
            if r["technique"] == "lightmap":
                key = (p["texels_per_unit"], FILTERS[int(p["filter"])], int(p["dilate"]))
                entry["lightmap"][key] = row
            else:
                entry["baseline"] = row
    gl = sorted({r["gl"]["renderer"] for r in m["results"] if isinstance(r.get("gl"), dict)})
    return out, m, gl


def load_bench(path):
    """{(scene, light): {label: row}}"""
    b = json.load(open(path))
    out = {}
    for s in b["scenes"]:
        scene = s["scene"].split("/")[-1].split(".")[0]
        for row in s["rows"]:
            out.setdefault((scene, row["light"]), {})[row["label"]] = row
    return out, b


def label(d, f, dilate=2):
    return f"lightmap:texels_per_unit={d:g},filter={f}" + (",dilate=0" if dilate == 0 else "")


def area(row):
    return row.get("penumbra_mae") is not None


def density_table(sweep):
    """Error against density and memory, bilinear, with the shadow map it bakes from."""
    rows = ["| scene, light | texels / unit | memory MiB | bake ms | frame ms | mae | aliasing rate "
            "(hard) or penumbra mae (area) | boundary displacement p95 px | peter-panning rate |",
            "|---|---|---|---|---|---|---|---|---|"]
    for (scene, light), e in sorted(sweep.items()):
        for (d, f, dil), r in sorted(e["lightmap"].items()):
            if f != "bilinear" or dil != 2:
                continue
            c = r["cost"]
            second = r["penumbra_mae"] if area(r) else r["aliasing_rate"]
            rows.append(f"| {scene}, {light} | {d:g} | {c['memory_bytes'] / 2**20:.2f} | "
                        f"{c['bake_ms']:.0f} | {c['frame_ms']:.2f} | {r['mae']:.4f} | "
                        f"{fmt(second, 4)} | {r['boundary_displacement_px']['p95']:.2f} | "
                        f"{fmt(r.get('peter_panning_rate'), 4)} |")
        b = e["baseline"]
        if b:
            c = b["cost"]
            second = b["penumbra_mae"] if area(b) else b["aliasing_rate"]
            rows.append(f"| {scene}, {light} | slope-bias 2048 | {c['memory_bytes'] / 2**20:.2f} | "
                        f"– | {c['frame_ms']:.2f} | {b['mae']:.4f} | {fmt(second, 4)} | "
                        f"{b['boundary_displacement_px']['p95']:.2f} | "
                        f"{fmt(b.get('peter_panning_rate'), 4)} |")
    return "\n".join(rows) + "\n"


def filter_table(sweep, bench):
    """Blockiness and the filtered edge's width per filter."""
    rows = ["| scene, light | texels / unit | texel px | mae nearest / bilinear / bicubic | "
            "boundary displacement p95 px | edge width px (10%-90%) |",
            "|---|---|---|---|---|---|"]
    for (scene, light), e in sorted(sweep.items()):
        densities = sorted({d for (d, f, dil) in e["lightmap"]})
        bl = bench.get((scene, light), {})
        for d in densities:
            rs = [e["lightmap"].get((d, f, 2)) for f in FILTERS]
            if None in rs:
                continue
            bs = [bl.get(label(d, f), {}) for f in FILTERS]
            texel = bs[1].get("texel_px")
            edges = " / ".join(fmt(b.get("edge_px"), 2) for b in bs) if "edge_px" in bs[1] else \
                "area light: see penumbra width"
            rows.append(f"| {scene}, {light} | {d:g} | {fmt(texel, 2)} | "
                        + " / ".join(f"{r['mae']:.4f}" for r in rs) + " | "
                        + " / ".join(f"{r['boundary_displacement_px']['p95']:.2f}" for r in rs)
                        + f" | {edges} |")
        base = bl.get("slope-bias:resolution=2048")
        if base and "edge_px" in base:
            rows.append(f"| {scene}, {light} | slope-bias 2048 | – | {e['baseline']['mae']:.4f} | "
                        f"{e['baseline']['boundary_displacement_px']['p95']:.2f} | "
                        f"{base['edge_px']:.2f} |")
    return "\n".join(rows) + "\n"


def seam_table(sweep, bench):
    """What dilation saves: bilinear with and without it."""
    rows = ["| scene, light | texels / unit | mae dilated / not | false shadow rate dilated / not | "
            "pixels a seam moves (> 0.02) | largest move |",
            "|---|---|---|---|---|---|"]
    for (scene, light), e in sorted(sweep.items()):
        bl = bench.get((scene, light), {})
        for (d, f, dil), bare in sorted(e["lightmap"].items()):
            if dil != 0:
                continue
            dilated = e["lightmap"].get((d, "bilinear", 2))
            if dilated is None:
                continue
            b = bl.get(label(d, "bilinear", 0), {})
            rows.append(f"| {scene}, {light} | {d:g} | {dilated['mae']:.4f} / {bare['mae']:.4f} | "
                        f"{dilated['false_shadow_rate']:.4f} / {bare['false_shadow_rate']:.4f} | "
                        f"{fmt(b.get('seam_share'), 4)} | {fmt(b.get('seam_max'), 3)} |")
    return "\n".join(rows) + "\n"


def frame_table(bench):
    """Per frame against the shadow map a bake is made from, every setting of a scene
    interleaved frame by frame (bench_lightmap): the frame's wall time covers every light."""
    rows = ["| scene | texels / unit | lightmap frame ms | slope-bias 2048 frame ms | ratio | "
            "bake ms (all lights) | memory MiB (all lights): lightmap / slope-bias |",
            "|---|---|---|---|---|---|---|"]
    for s in bench["scenes"]:
        scene = s["scene"].split("/")[-1].split(".")[0]
        lights = sorted({r["light"] for r in s["rows"]})
        base = [r for r in s["rows"] if r["label"].startswith("slope-bias")]
        base_ms = base[0]["frame_ms"]
        base_mem = sum(r["memory_bytes"] for r in base) / 2**20
        for d in sorted({r["texels_per_unit"] for r in s["rows"] if "texels_per_unit" in r}):
            lm = [r for r in s["rows"] if r.get("texels_per_unit") == d and
                  r.get("filter") == "bilinear" and r.get("dilate") == 2]
            if len(lm) != len(lights):
                continue
            ms = lm[0]["frame_ms"]
            rows.append(f"| {scene} | {d:g} | {ms:.2f} | {base_ms:.2f} | {ms / base_ms:.2f} | "
                        f"{sum(r['bake_ms'] for r in lm):.0f} | "
                        f"{sum(r['memory_bytes'] for r in lm) / 2**20:.2f} / {base_mem:.2f} |")
    return "\n".join(rows) + "\n"


def main(sweep_path, bench_path, doc_path):
    sweep, m, gl = load_sweep(sweep_path)
    bench, b = load_bench(bench_path)
    failed = m.get("failed", [])
    header = (f"The sweep `scenes/sweeps/lightmap.json` ({m['finished']} of {m['tasks']} tasks "
              f"finished, 320 x 240, 3 timed frames, one task at a time) and `bench_lightmap` "
              f"(the same scenes, densities and size, every setting of a scene interleaved frame by "
              f"frame), on {', '.join(gl) or b['gl']}. Frame times are the median wall time of a "
              "frame; `bake_ms` is each light's bake, once, before the frames. Memory is what the "
              "technique holds for the light (atlas, lookup table, the light's V and aliasing "
              "targets).")
    if failed:
        header += f" Failed: {', '.join(f['label'] + ' on ' + f['scene'] for f in failed)}."
    text = (header + "\n\n**Error against density and memory** (filter bilinear, dilate 2, "
            "padding 2; the last row of each light: slope-bias with the bake's 2048 map, every "
            "frame):\n\n" + density_table(sweep) +
            "\n**Blockiness and the filtered edge** (`texel px`: a texel's median size in pixels "
            "on the lit surfaces, from `aliasing_pred`; the edge width is the image's own mean "
            "10%-90% transition width where the light faces the surface, hard lights only):\n\n" +
            filter_table(sweep, bench) +
            "\n**Seams** (bilinear, with and without dilation; a seam's pixels: those whose V "
            "moves by more than 0.02 when the charts are not dilated, among the pixels the light "
            "faces):\n\n" + seam_table(sweep, bench) +
            "\n**Per frame, against the shadow map a bake is made from** (`bench_lightmap`: "
            "bilinear, every setting of a scene and the baseline taking turns frame by frame; the "
            "frame's wall time covers all the scene's lights):\n\n" + frame_table(b))
    write_between_markers(doc_path, "lightmap tables", text)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], sys.argv[3])
