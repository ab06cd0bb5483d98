#!/usr/bin/env python3
"""Writes docs/real-scenes.md's table and pictures (see real-scenes-figures): per real scene, its
size from the oracle's own count, the time of `shadow-oracle trace` at 480x360 (measured here) and
of scripts/demo's compare (its demo-seconds file, if the demo has run)."""
import json
import pathlib
import shutil
import subprocess
import sys
import time
from doc_markers import write_between_markers

WIDTH, HEIGHT = 480, 360


def trace(cli, scene, out):
    """(oracle.json as a dict or None, wall seconds, the error's first line or None)."""
    start = time.monotonic()
    r = subprocess.run([cli, "trace", str(scene), "--width", str(WIDTH), "--height", str(HEIGHT),
                        "--out", str(out), "--quiet"], capture_output=True, text=True)
    seconds = time.monotonic() - start
    if r.returncode != 0:
        lines = [l for l in r.stderr.splitlines() if not l.startswith("warning:")]
        error = lines[-1] if lines else "exit %d" % r.returncode
        # Paths relative to the checkout, so the table does not depend on where it lies.
        return None, seconds, error.replace(str(scene.parent.parent.parent.parent) + "/", "")
    return json.loads((out / "oracle.json").read_text()), seconds, None


def lights_cell(oracle, scene):
    lights = oracle["lights"] if oracle else json.loads(scene.read_text())["lights"]
    return ", ".join("%s (%s)" % (l["name"], l["type"]) for l in lights)


def demo_cell(demo, name):
    seconds = demo / name / "demo-seconds"
    metrics = demo / name / "metrics.json"
    if not seconds.is_file() or not metrics.is_file():
        return "– (no demo run)"
    results = json.loads(metrics.read_text()).get("results", [])
    return "%.0f s, %d settings" % (float(seconds.read_text()), len(results))


def main(root, cli, work, demo):
    rows = ["| scene | triangles | meshes | lights | `trace` 480x360 | demo `compare` |",
            "|---|---:|---:|---|---:|---:|"]
    for scene in sorted(root.glob("scenes/real/*/*.scene.json")):
        name = scene.name[:-len(".scene.json")]
        out = work / name
        oracle, seconds, error = trace(cli, scene, out)
        rel = scene.relative_to(root)
        if oracle is None:
            rows.append("| `%s` | – | – | %s | does not load with this build: `%s` | %s |" %
                        (rel, lights_cell(None, scene), error.replace("|", "\\|"),
                         demo_cell(demo, name)))
            continue
        s = oracle["scene"]
        rows.append("| `%s` | %s | %d | %s | %.2f s | %s |" %
                    (rel, format(s["triangles"], ","), s["meshes"], lights_cell(oracle, scene),
                     seconds, demo_cell(demo, name)))
        first = oracle["lights"][0]["name"]
        shutil.copyfile(out / (first + ".png"), root / "docs" / "images" / ("real-%s.png" % name))
    cores = len(__import__("os").sched_getaffinity(0))
    note = ("Made by `scripts/real-scenes-figures` on %d cores: `trace` is the wall time of "
            "`shadow-oracle trace SCENE --width %d --height %d --out DIR --quiet` (load, BVH, "
            "all lights, files), measured by the script; demo `compare` is the wall time of "
            "`scripts/demo`'s compare of that scene (480x360, its techniques; `demo-seconds` in "
            "its output folder) and the number of technique settings it rendered.") % (
                cores, WIDTH, HEIGHT)
    write_between_markers(root / "docs" / "real-scenes.md", "real-scenes",
                          "\n".join(rows) + "\n\n" + note)


if __name__ == "__main__":
    root, cli, work, demo = (pathlib.Path(a) for a in sys.argv[1:5])
    main(root, cli, work, demo)
