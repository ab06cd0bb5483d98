#!/usr/bin/env python3
"""Writes docs/hard-cases.md's raster table from scripts/hard-cases-table's runs."""
import json
import pathlib
import sys
from doc_markers import write_between_markers

ORDER = ["grazing_1e-1", "grazing_1e-2", "grazing_1e-3",
         "contact_resting", "contact_hover_1e-3", "contact_hover_1e-5"]


def pct(v):
    if v is None:
        return "–"
    return "0" if v == 0 else "<0.01%" if v < 1e-4 else "%.2f%%" % (100 * v)


def main(runs, doc):
    scenes = {p.parent.name: json.loads(p.read_text())
              for p in pathlib.Path(runs).glob("*/metrics.json")}
    names = [n for n in ORDER if n in scenes]
    if not names:
        sys.exit("error: no runs in %s" % runs)
    labels = []
    for n in names:
        for r in scenes[n]["results"]:
            if r["label"] not in labels:
                labels.append(r["label"])
    lines = ["| technique | family | " + " | ".join("`%s`" % n for n in names) + " |",
             "|---|---|" + "---|" * len(names)]
    for label in labels:
        cells, family = [], ""
        for n in names:
            row = next((r for r in scenes[n]["results"] if r["label"] == label), None)
            if row is None:
                cells.append("–")
                continue
            family = row["family"]
            m = next(iter(row["lights"].values()))
            cells.append("%s / %s" % (pct(m.get("acne_rate")), pct(m.get("peter_panning_rate"))))
        lines.append("| `%s` | %s | %s |" % (label, family, " | ".join(cells)))
    gl = next(iter(scenes.values()))["gl"]["renderer"]
    table = ("Each cell: `acne_rate` / `peter_panning_rate` (docs/metrics.md) at 320 x 240, default "
             "parameters, rendered on %s.\n\n" % gl) + "\n".join(lines)
    write_between_markers(doc, "raster table", table + "\n")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
