#!/usr/bin/env python3
"""Writes the README's figures table from scripts/demo's metrics.json files (see readme-figures)."""
import json
import pathlib
import sys
from doc_markers import write_between_markers

# (scene, light, metric, column header): what each column shows.
COLUMNS = [
    ("terrain_sun", "sun", "acne_rate", "acne, terrain_sun"),
    ("spot_objects", "cone", "mae", "mae, spot_objects cone"),
    ("soft_chair", "window", "penumbra_mae", "penumbra mae, soft_chair window"),
    ("soft_chair", "window", "cost.frame_ms", "frame ms, soft_chair"),
    # The frame's work, what a GPU's time follows (docs/metrics.md, Work), beside llvmpipe's ms.
    ("soft_chair", "window", "cost.work.bytes_moved", "MB moved a frame, soft_chair window"),
]
ROWS = ["basic", "slope-bias", "pcf:kernel=5", "vsm", "volume-zfail", "pcss",
        "accumulate:samples=64", "lightmap",
        # What engines ship now (issue 63).
        "pcf:pattern=three,bias=back-faces", "pcf:contact=on", "smrt", "raytraced:spp=1,denoiser=ffx"]


def value(row, name):
    v = row
    for part in name.split("."):
        v = v.get(part) if isinstance(v, dict) else None
    return v


def cell(v, name):
    if v is None:
        return "–"
    if name.endswith("_rate"):
        return "%.2f%%" % (100 * v)
    if name.endswith("bytes_moved"):
        return "%.1f" % (v / 1e6)
    if name.endswith("_ms") or name.endswith("p95"):
        return "%.1f" % v
    return "%.4f" % v


def main(demo, readme):
    runs = {p.parent.name: json.loads(p.read_text())
            for p in sorted(pathlib.Path(demo).glob("*/metrics.json"))}
    renderer = next(iter(runs.values()))["gl"]["renderer"]
    lines = ["| technique | fidelity | " + " | ".join(c[3] for c in COLUMNS) + " |",
             "|---" * (len(COLUMNS) + 2) + "|"]
    for label in ROWS:
        # Whose designs the row grades (docs/metrics.md, Provenance), from any scene's row: each
        # part's fidelity ("pcss variant, bias=slope own"), the row's being the farthest.
        parts = next((r.get("provenance", {}).get("parts", [])
                      for run in runs.values() for r in run.get("results", [])
                      if r["label"] == label), [])
        cells = [", ".join("%s %s" % (p["of"].replace("technique ", ""), p["fidelity"])
                           for p in parts) or "–"]
        for scene, light, metric, _ in COLUMNS:
            rows = [r for r in runs.get(scene, {}).get("results", []) if r["label"] == label]
            cells.append(cell(value(rows[0]["lights"].get(light, {}), metric), metric)
                         if rows else "–")
        lines.append("| `%s` | %s |" % (label, " | ".join(cells)))
    table = "\n".join(lines)
    note = ("Made by `scripts/readme-figures` from `scripts/demo`'s output (480 x 360, times on %s; "
            "lower is better everywhere). Fidelity: for the technique and each named design its "
            "settings choose, whether it is its source's as published (`faithful`), a `variant` "
            "with its deviations listed, or a design of our `own` "
            "([docs/techniques.md](docs/techniques.md#provenance), `shadow-oracle techniques`).") % renderer
    bakes = [value(r["lights"].get("window", {}), "cost.bake_ms")
             for r in runs.get("soft_chair", {}).get("results", []) if r["label"] == "lightmap"]
    if bakes and bakes[0] is not None:
        note += (" A lightmap's frame leaves out its bake, paid once before the frames: %.1f s for "
                 "soft_chair's window." % (bakes[0] / 1000))
    write_between_markers(readme, "figures", table + "\n\n" + note + "\n")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
