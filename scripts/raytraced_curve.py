#!/usr/bin/env python3
"""The error of ray-traced shadows against their rays, per denoiser (issue 53), on the shipped
area-light scenes: each scene as a sequence of still frames (a copy beside it with scene_format 5
and a `sequence`, removed afterwards), judged by `compare --sequence`: every (spp, denoiser) of
the `raytraced` family and pcss, the last frame's penumbra mae (the converged error) against the
rays a frame (cost.work.rays_traced). Writes the table into docs/benchmarks.md between its
"BEGIN raytraced curve" and "END raytraced curve" markers.

usage: raytraced_curve.py CLI OUT_DIR DOC [--scenes a,b] [--width W] [--height H] [--frames N]
                          [--spp 1,2,4]"""
import argparse
import json
import os
import pathlib
import subprocess

from doc_markers import write_between_markers

AREA_SCENES = ["penumbra_square", "polygon_softbox", "sphere_light", "soft_chair", "alpha_grate"]


def denoisers(cli):
    """The denoiser plug-ins by number, as `techniques --json` lists them (its "axes")."""
    listing = json.loads(subprocess.run([cli, "techniques", "--json"], check=True,
                                        capture_output=True, text=True).stdout)
    return [p["name"] for p in listing["axes"]["denoiser"]["plugins"]]


def still_sequence(scene_path, frames):
    """A copy of the scene beside it (its meshes are found from its folder) as `frames` still
    frames; the caller removes it."""
    scene = json.loads(scene_path.read_text())
    scene["scene_format"] = 5
    scene["sequence"] = {"frames": frames, "fps": 30}
    copy = scene_path.with_name("." + scene_path.name.replace(".scene.json", "") +
                                ".raytraced-curve.scene.json")
    copy.write_text(json.dumps(scene, indent=1))
    return copy


def measure(cli, scene_path, out, args):
    labels = [f"raytraced:spp={s},denoiser={d}" for d in args.denoisers for s in args.spp]
    labels += ["pcss"]
    copy = still_sequence(scene_path, args.frames)
    try:
        cmd = [cli, "compare", str(copy), "--sequence", "--width", str(args.width), "--height",
               str(args.height), "--frames", "1", "--warmup", "0", "--cache",
               str(out / "cache"), "--out", str(out / scene_path.name.split(".")[0]), "--quiet"]
        for label in labels:
            cmd += ["--technique", label]
        subprocess.run(cmd, check=True)
    finally:
        os.remove(copy)
    return json.loads((out / scene_path.name.split(".")[0] / "metrics.json").read_text())


def fmt(v):
    return "n/a" if v is None else f"{v:.4f}"


def table(scene, metrics, args):
    """One table per light: a row per denoiser, a column per spp (the last frame's penumbra mae,
    and the rays a frame under it in the header), pcss beneath."""
    by = {}
    for r in metrics["results"]:
        p = r["parameters"]
        for light, row in r["lights"].items():
            d = p.get("denoiser")
            name = d if isinstance(d, str) else args.denoisers[int(d or 0)]
            key = (name, int(p["spp"])) if r["technique"] == "raytraced" else ("pcss", None)
            by.setdefault(light, {})[key] = row
    out = []
    for light, rows in sorted(by.items()):
        rays = {s: rows.get(("none", s), {}).get("cost", {}).get("work", {}).get("rays_traced")
                for s in args.spp}
        head = " | ".join(f"spp {s} ({rays[s]:,} rays)" if rays[s] is not None else f"spp {s}"
                          for s in args.spp)
        out.append(f"**{scene}**, light `{light}`: penumbra mae at the last of {args.frames} still "
                   f"frames, {args.width} x {args.height}\n")
        out.append(f"| denoiser | {head} |")
        out.append("|---|" + "---|" * len(args.spp))
        for d in args.denoisers:
            def cell(s):
                row = rows.get((d, s), {})
                text = fmt(row.get("penumbra_mae"))
                # An adaptive denoiser (rtg) traces fewer rays than the column's: said beside it.
                own = row.get("cost", {}).get("work", {}).get("rays_traced")
                return text if own is None or own == rays[s] else f"{text} ({own:,} rays)"
            cells = " | ".join(cell(s) for s in args.spp)
            out.append(f"| {d} | {cells} |")
        pcss = rows.get(("pcss", None), {}).get("penumbra_mae")
        out.append(f"| pcss (no rays) | {fmt(pcss)}" + " |" * len(args.spp))
        out.append("")
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("cli")
    ap.add_argument("out")
    ap.add_argument("doc")
    ap.add_argument("--scenes", default=",".join(AREA_SCENES))
    ap.add_argument("--width", type=int, default=160)
    ap.add_argument("--height", type=int, default=120)
    ap.add_argument("--frames", type=int, default=16)
    ap.add_argument("--spp", default="1,2,4")
    args = ap.parse_args()
    args.spp = [int(s) for s in args.spp.split(",")]
    args.denoisers = denoisers(args.cli)
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    root = pathlib.Path(__file__).resolve().parent.parent
    parts = []
    gl = set()
    for name in args.scenes.split(","):
        metrics = measure(args.cli, root / "scenes" / f"{name}.scene.json", out, args)
        gl.add(metrics.get("gl", {}).get("renderer", "?"))
        parts.append(table(name, metrics, args))
    body = "\n".join(parts) + f"\nRenderer: {', '.join(sorted(gl))}. Command: `scripts/raytraced-curve " \
        f"--scenes {args.scenes} --width {args.width} --height {args.height} --frames " \
        f"{args.frames} --spp {','.join(map(str, args.spp))}`.\n"
    write_between_markers(args.doc, "raytraced curve", body)


if __name__ == "__main__":
    main()
