#!/usr/bin/env python3
"""Writes the aliasing-against-memory table (scripts/resolution-table) from a compare run's
metrics.json into a markdown file between its BEGIN/END resolution table markers."""
import json, sys
from doc_markers import write_between_markers


def fmt(v, digits):
    return "n/a" if v is None else f"{v:.{digits}f}"


def main(metrics_path, doc_path):
    m = json.load(open(metrics_path))
    rows = ["| technique | memory MiB | boundary displacement p95 px | mean px | aliasing rate | "
            "temporal flicker rate | frame ms (median) |", "|---|---|---|---|---|---|---|"]
    for t in m["results"]:
        for light in t["lights"].values():
            bd, cost = light["boundary_displacement_px"], light["cost"]
            rows.append("| `{}` | {:.1f} | {} | {} | {} | {} | {:.0f} |".format(
                t["label"], cost["memory_bytes"] / 2**20, fmt(bd["p95"], 2), fmt(bd["mean"], 2),
                fmt(light.get("aliasing_rate"), 4), fmt(light.get("temporal_flicker_rate"), 5),
                cost["frame_ms"]))
    gl = m.get("gl", {}).get("renderer", "?")
    camera = json.load(open(m["scene"]["file"]))["camera"]
    header = (f"Scene `{m['scene']['file']}` ({camera['width']} x {camera['height']}), light `sun`, "
              f"{gl}; flicker over {m['options'].get('frames_path', 0)} frames of its camera path; "
              "frame time the median of 5 frames.")
    table = header + "\n\n" + "\n".join(rows) + "\n"
    write_between_markers(doc_path, "resolution table", table)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
