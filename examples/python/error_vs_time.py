#!/usr/bin/env python3
"""What accuracy costs in time, on one scene: three techniques at a few settings each, every render
judged against the oracle, penumbra error plotted against frame time (docs/python.md).

    PYTHONPATH=build/python python3 examples/python/error_vs_time.py --out error_vs_time.png

The frame times are those of the GL the module finds (Mesa llvmpipe on a machine without a GPU).
"""

import argparse
import os

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt

import shadow_oracle as so

HERE = os.path.dirname(os.path.abspath(__file__))
SETTINGS = {
    "pcf": [{"kernel": k} for k in (1, 3, 5, 9)],
    "pcss": [{"filter_samples": n} for n in (8, 16, 32, 64)],
    "vsm": [{"blur": b} for b in (1, 3, 5)],
}


def label(technique, params):
    return technique + ":" + ",".join(f"{k}={v}" for k, v in params.items())


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default=os.path.join(HERE, "..", "..", "scenes",
                                                        "soft_chair.scene.json"))
    parser.add_argument("--out", default="error_vs_time.png")
    parser.add_argument("--width", type=int, default=320)
    parser.add_argument("--height", type=int, default=240)
    parser.add_argument("--frames", type=int, default=5)
    args = parser.parse_args()

    scene = so.load_scene(args.scene)
    oracle = so.trace(scene, width=args.width, height=args.height)
    light = scene.lights[0]["name"]
    # The error metric: the penumbra's where the light is an area light, else the mean error.
    metric = "penumbra_mae" if scene.lights[0]["area"] else "mae"

    fig, ax = plt.subplots(figsize=(6.4, 4.2), dpi=100)
    for technique, settings in SETTINGS.items():
        labels = [label(technique, p) for p in settings]
        metrics = so.compare(scene, oracle, techniques=labels, frames=args.frames, warmup=1)
        points = []
        for row in metrics["results"]:
            m = row["lights"][light]
            points.append((m["cost"]["frame_ms"], m[metric], row["label"]))
        points.sort()
        ax.plot([p[0] for p in points], [p[1] for p in points], "o-", label=technique)
        for ms, error, name in points:
            print(f"{name:28s} {ms:9.2f} ms  {metric} {error:.4f}")
            ax.annotate(name.split(":", 1)[1], (ms, error), fontsize=7, xytext=(3, 3),
                        textcoords="offset points")
    ax.set_xscale("log")
    ax.set_xlabel("frame time, ms (" + metrics["gl"]["renderer"] + ")")
    ax.set_ylabel(metric + " against the oracle")
    ax.set_title(os.path.basename(args.scene) + ", light " + light)
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.out)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
