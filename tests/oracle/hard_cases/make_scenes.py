#!/usr/bin/env python3
"""Writes the hard-case scenes the raster techniques are run on (docs/hard-cases.md): a box on a
floor under a directional light at grazing incidence (n.l = 1e-1, 1e-2, 1e-3), and a box resting
on the floor or hovering 1e-3 and 1e-5 of the scene's diagonal above it under a point light.
Committed; re-run only to change them. Meshes come from scenes/make_scenes.py's formulas, written
beside these scenes (a scene may only name files inside its own folder)."""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "scenes"))
import make_scenes as ms  # noqa: E402

OUT = os.path.join(HERE, "scenes")
DIAGONAL = math.sqrt(20.0 ** 2 + 20.0 ** 2 + 1.0)  # the floor (20 x 20) and the unit box


def write(name, geometry, camera, lights):
    ms.HERE = OUT
    ms.scene(name, geometry, camera, lights, effects=("hard", "contact"))


def main():
    ms.MESHES = os.path.join(OUT, "meshes")
    os.makedirs(ms.MESHES, exist_ok=True)
    ms.write_gltf("floor", *ms.grid(8, 8, lambda u, v: (-10 + 20 * u, 0.0, 10 - 20 * v)))
    ms.write_gltf("unit_box", *ms.box((-0.5, 0.0, -0.5), (0.5, 1.0, 0.5)))
    camera = {"eye": [-4.0, 5.0, -5.0], "target": [0.5, 0.0, 0.5], "up": [0, 1, 0],
              "vfov_deg": 45, "width": 320, "height": 240}
    box = {"file": "meshes/unit_box.gltf"}
    floor = {"file": "meshes/floor.gltf"}
    for label, nl in (("1e-1", 1e-1), ("1e-2", 1e-2), ("1e-3", 1e-3)):
        # Light travelling along +x and down: n.l = sin(elevation) on the floor.
        el = math.asin(nl)
        write("grazing_%s.scene.json" % label, [floor, box], camera,
              [{"name": "sun", "type": "directional",
                "direction": [math.cos(el), -math.sin(el), 0.0]}])
    for label, gap in (("resting", 0.0), ("hover_1e-3", 1e-3), ("hover_1e-5", 1e-5)):
        write("contact_%s.scene.json" % label,
              [floor, dict(box, translate=[0.0, gap * DIAGONAL, 0.0])], camera,
              [{"name": "key", "type": "point", "position": [3.0, 4.0, 2.0]}])


if __name__ == "__main__":
    main()
