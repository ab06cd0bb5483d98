#!/usr/bin/env python3
"""Rebuilds the seed corpus of tests/fuzz/corpus/ (docs/fuzzing.md) from the project's own files
and, where installed, Debian's assimp-testmodels. Run from anywhere; rewrites only the seed files
it names (seed-*), so inputs added by `scripts/fuzz --merge` stay.

The gltf harness reads one byte of mode first (fuzz_gltf.cpp): 0 = .glb, 1 = .gltf followed by NUL
and the buffer file b.bin; +2 = load through loadScene. The gate harness reads the limits file,
NUL, metrics.json. The sweep harness reads a sweep spec whose folder holds a.scene.json,
b.scene.json and sub/c.scene.json, with ../outside.scene.json beside it (fuzz_sweep.cpp).
"""
import json
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[2]
CORPUS = ROOT / "tests/fuzz/corpus"
ASSIMP = pathlib.Path("/usr/share/assimp/models/glTF2")
MAX_GLTF_BYTES = 24 * 1024


def write(harness, name, data):
    d = CORPUS / harness
    d.mkdir(parents=True, exist_ok=True)
    (d / ("seed-" + name)).write_bytes(data)


def gltf_input(path, mode):
    """The gltf harness's input for a .gltf/.glb file: a single external buffer becomes b.bin."""
    raw = path.read_bytes()
    if path.suffix == ".glb":
        return bytes([mode]) + raw
    text = raw.decode("utf-8")
    j = json.loads(text)
    buffers = [b.get("uri", "") for b in j.get("buffers", [])]
    external = [u for u in buffers if u and not u.startswith("data:")]
    if len(external) == 1 and (path.parent / external[0]).is_file():
        bin_bytes = (path.parent / external[0]).read_bytes()
        text = text.replace('"' + external[0] + '"', '"b.bin"')
        return bytes([mode | 1]) + text.encode() + b"\0" + bin_bytes
    return bytes([mode | 1]) + text.encode()


def main():
    # scene: the shipped scenes and every scene of the loader tests.
    for f in sorted((ROOT / "scenes").glob("*.scene.json")):
        write("scene", f.name, f.read_bytes())
    for f in sorted((ROOT / "tests/data/broken_scene").glob("*.json")):
        write("scene", "broken-" + f.name, f.read_bytes())
    write("scene", "valid-scene.json", (ROOT / "tests/data/valid/scene.json").read_bytes())
    write("scene", "valid-path_keyframes.json",
          (ROOT / "tests/data/valid/path_keyframes.json").read_bytes())
    write("scene", "valid-dynamic.json", (ROOT / "tests/data/valid/dynamic.json").read_bytes())

    # gltf: the loader tests' files, the small shipped meshes, small assimp test models.
    sources = sorted((ROOT / "tests/data/broken_gltf").glob("*.gl*"))
    sources += sorted((ROOT / "tests/data/gltf").glob("*.gl*"))
    sources += [ROOT / "tests/data/valid/tri.gltf"]
    sources += [f for f in sorted((ROOT / "scenes/meshes").glob("*.gltf"))
                if f.stat().st_size <= MAX_GLTF_BYTES]
    if ASSIMP.is_dir():
        sources += [f for f in sorted(ASSIMP.rglob("*.gl*"))
                    if f.suffix in (".gltf", ".glb") and f.stat().st_size <= MAX_GLTF_BYTES]
    for f in sources:
        try:
            data = gltf_input(f, 0)
        except (UnicodeDecodeError, json.JSONDecodeError, RecursionError, AttributeError):
            data = bytes([1]) + f.read_bytes()  # broken on purpose: fed as is
        if len(data) > MAX_GLTF_BYTES + 4096:
            continue
        rel = f.relative_to(ASSIMP if ASSIMP in f.parents else ROOT)
        name = re.sub(r"[^A-Za-z0-9_.-]", "_", str(rel))
        write("gltf", name, data)
    # Animated files as a scene with a sequence loads them (mode bit 2: the animations play).
    for f in sorted((ROOT / "tests/data/anim").glob("*.gltf")) + sorted(
            (ROOT / "tests/data/broken_scene").glob("anim_*.gltf")):
        write("gltf", "anim-" + f.name, gltf_input(f, 4))
    # The same through loadScene, for a few.
    for f in [ROOT / "tests/data/gltf/lights_camera.gltf", ROOT / "tests/data/gltf/triangle.glb",
              ROOT / "tests/data/gltf/two_nodes.gltf", ROOT / "tests/data/gltf/strip_fan.gltf"]:
        write("gltf", "scene-" + f.name, gltf_input(f, 2))

    # gate: the shipped limits with the small built-in metrics (no NUL), and with a real one.
    limits = (ROOT / "scenes/limits.json").read_bytes()
    write("gate", "limits.json", limits)
    write("gate", "limits-empty-rules.json", b'{"limits_format": 1, "default": {"mae": 0.1}}')
    write("gate", "limits-globs.json",
          b'{"limits_format": 1, "rules": [{"scene": "contact*", "light": "k?y", "technique": '
          b'"*", "max": {"boundary_displacement_px.max": 2, "mae": 0.5}}]}')
    # gate --baseline: a limits_format 2 file with the baseline object, and two metrics files.
    baseline_limits = (b'{"limits_format": 2, "default": {"mae": 0.5}, "baseline": {"default": '
                       b'{"abs": 0.001, "rel": 0.05}, "metrics": {"cost.frame_ms": {"rel": 0.5}, '
                       b'"boundary_displacement_px.p95": {"abs": 1}}, "ignore": ["max_abs"]}}')
    write("gate", "limits-baseline.json", baseline_limits)
    write("gate", "baseline-pair.bin", baseline_limits + b"\0" + BASELINE_NEW + b"\0" + BASELINE_OLD)
    metrics = small_metrics()
    if metrics:
        write("gate", "limits-and-metrics.json", limits + b"\0" + metrics)
        write("gate", "baseline-demo.bin", baseline_limits + b"\0" + metrics + b"\0" + metrics)
        write("index", "metrics.json", metrics)
    write("index", "metrics-v1.json",
          b'{"schema_version": 1, "scene": {"file": "a.scene.json"}, "results": [{"technique": '
          b'"basic", "lights": {"key": {"mae": 0.1, "acne_rate": null}}}]}')
    sweep_seeds()
    image_seeds()


def png_grey(width, height, codes, bits):
    """A grey PNG (8 or 16 bit) of row-major codes: signature, IHDR, one IDAT, IEND."""
    import struct
    import zlib

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))
    raw = b""
    for y in range(height):
        row = codes[y * width:(y + 1) * width]
        raw += b"\0" + (bytes(row) if bits == 8 else b"".join(struct.pack(">H", c) for c in row))
    ihdr = struct.pack(">IIBBBBB", width, height, bits, 0, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(raw)) +
            chunk(b"IEND", b""))


def image_input(flags, width, height, image, cost=b""):
    """The image harness's input (fuzz_image.cpp): flags, the camera's size, the cost file's
    length, the cost file, the image."""
    return bytes([flags, width, height, len(cost) & 0xFF, len(cost) >> 8]) + cost + image


def image_seeds():
    """fuzz_image: oracle.exr of two shipped scenes at 16 x 12 (traced by the Release build's
    shadow-oracle, skipped without it), grey PNGs, and cost files good and bad."""
    import subprocess
    import tempfile
    cli = ROOT / "build/cli/shadow-oracle"
    w, h = 16, 12
    cost = (b'{"renderer": "my-engine 1.2", "frame_ms": 1.5, "shadow_ms": 0.5, "memory_bytes": '
            b'4096, "params": {"bias": 0.5, "filter": "pcf", "soft": true}}')
    codes = [(x * 17 + y * 5) % 256 for y in range(h) for x in range(w)]
    write("image", "png8.bin", image_input(1, w, h, png_grey(w, h, codes, 8), cost))
    write("image", "png16-srgb.bin",
          image_input(1 | 4, w, h, png_grey(w, h, [c * 257 for c in codes], 16)))
    write("image", "png-bad-cost.bin",
          image_input(1, w, h, png_grey(w, h, codes, 8), b'{"frame_ms": -1, "fps": 60}'))
    write("image", "png-two-lights.bin", image_input(1 | 2, w, h, png_grey(w, h, codes, 8)))
    with open(CORPUS.parent / "image.dict", "w") as out:
        out.write("# libFuzzer dictionary for fuzz_image: the cost file's keys and the channel names"
                  "\n# (written by tests/fuzz/make_corpus.py).\n")
        for word in ("renderer", "frame_ms", "shadow_ms", "memory_bytes", "params", "panel.V",
                     "cone.V", "fill.V"):
            out.write('"%s"\n' % word)
    if not cli.is_file():
        print("image seeds: no %s, EXR seeds left out" % cli)
        return
    with tempfile.TemporaryDirectory() as tmp:
        for scene, flags in (("spot_objects", 2), ("penumbra_square", 0)):
            out = pathlib.Path(tmp) / scene
            subprocess.run([str(cli), "trace", str(ROOT / "scenes" / (scene + ".scene.json")),
                            "--out", str(out), "--width", str(w), "--height", str(h), "--quiet"],
                           check=True)
            exr = (out / "oracle.exr").read_bytes()
            write("image", scene + ".bin", image_input(flags, w, h, exr))
            write("image", scene + "-cost.bin", image_input(flags, w, h, exr, cost))
            write("image", scene + "-wrong-size.bin", image_input(flags, w + 1, h, exr))
            write("image", scene + "-other-lights.bin", image_input(flags ^ 2, w, h, exr))


# gate --baseline: two small runs of one scene, an area light with the oracle's stats, a row in
# each that the other lacks, a null on one side.
BASELINE_OLD = (b'{"schema_version": 4, "scene": {"file": "scenes/p.scene.json"}, "oracle": {"stats": '
                b'{"lights": [{"name": "panel", "worst_half_width": 0.01, "cost_curve": [{"mean_half_width": '
                b'0.02, "penumbra_mean_half_width": 0.01}]}, {"name": "sun"}]}}, "results": [{"label": "pcss", '
                b'"technique": "pcss", "lights": {"panel": {"mae": 0.1, "penumbra_bias": -0.02, '
                b'"penumbra_mae": null, "cost": {"frame_ms": 2.0}}, "sun": {"acne_rate": 0.01}}}, '
                b'{"label": "gone", "lights": {"panel": {"mae": 0.3}}}]}')
BASELINE_NEW = (b'{"schema_version": 5, "scene": {"file": "scenes/p.scene.json"}, "oracle": {"stats": '
                b'{"lights": [{"name": "panel", "worst_half_width": 0.01, "cost_curve": [{"mean_half_width": '
                b'0.02, "penumbra_mean_half_width": 0.01}]}]}}, "results": [{"label": "pcss", '
                b'"technique": "pcss", "source": "external", "lights": {"panel": {"mae": 0.2, '
                b'"penumbra_bias": 0.03, "penumbra_mae": 0.1, "cost": {"frame_ms": null}}, "sun": '
                b'{"acne_rate": 0.5}}}, {"label": "added", "lights": {"panel": {"mae": 0.3}}}]}')


# sweep: specs over the harness's stand-in techniques (fuzz_sweep.cpp): basic (resolution),
# slope-bias (alpha, min, resolution), pcf (kernel, resolution, pattern: grid or poisson).
SWEEP_SEEDS = {
    "minimal.json": {"sweep_format": 1, "scenes": ["a.scene.json"],
                     "techniques": [{"name": "basic"}]},
    "images.json": {"sweep_format": 1, "scenes": ["*.scene.json", "sub/c.scene.json"],
                    "techniques": [{"name": "slope-bias", "params": {"alpha": [0, 1]}}],
                    "images": [{"name": "engine", "path": "img/{scene}_{bias}.exr",
                                "params": {"bias": [1, 2], "cascades": 4},
                                "scenes": ["[ab].scene.json"]},
                               {"name": "other", "path": "img/{scene}_1.png",
                                "scenes": ["sub/*"], "encoding": "srgb"}]},
    "images-only.json": {"sweep_format": 1, "scenes": ["a.scene.json"],
                         "images": [{"name": "engine", "path": "img/a_{bias}.exr",
                                     "params": {"bias": {"from": 1, "to": 2, "steps": 2}}}]},
    "bad-image-missing.json": {"sweep_format": 1, "scenes": ["a.scene.json"],
                               "images": [{"name": "engine", "path": "img/{scene}_{bias}.exr",
                                           "params": {"bias": [1, 3]}}]},
    "full.json": {
        "sweep_format": 1, "name": "bias study", "scenes": ["*.scene.json", "sub/c.scene.json"],
        "width": 320, "height": 240, "frames": 3, "boundary_radius": 2, "keep_outputs": True,
        "oracle": {"seed": 7, "target_error": 0.01, "agreement_target": 0.02, "max_spp": 4096,
                   "spp": 64},
        "techniques": [
            {"name": "basic", "params": {"resolution": [512, 1024, 2048]}},
            {"name": "slope-bias", "params": {"alpha": {"from": 0, "to": 4, "steps": 5},
                                              "min": [0, 0.5], "resolution": 2048}},
            {"name": "pcf", "params": {"kernel": [1, 3, 5],
                                       "resolution": {"from": 512, "to": 4096, "steps": 4,
                                                      "log": True}}}]},
    "globs.json": {"sweep_format": 1, "scenes": ["?.scene.json", "[ab].scene.json", "s*/*.json",
                                                 "../outside.scene.json"],
                   "techniques": [{"name": "slope-bias", "params": {"alpha": [1, 2]}}]},
    "large-grid.json": {"sweep_format": 1, "scenes": ["a.scene.json"],
                        "techniques": [{"name": "slope-bias", "params": {
                            "alpha": {"from": 0, "to": 16, "steps": 50},
                            "min": {"from": 0.01, "to": 16, "steps": 20, "log": True}}}]},
    "names.json": {"sweep_format": 1, "scenes": ["a.scene.json"],
                   "techniques": [{"name": "pcf", "params": {"pattern": ["grid", "poisson"],
                                                             "kernel": [1, 3]}},
                                  {"name": "pcf", "params": {"pattern": "poisson"}}]},
    "bad-unknown-name.json": {"sweep_format": 1, "scenes": ["a.scene.json"],
                              "techniques": [{"name": "pcf",
                                              "params": {"pattern": ["grid", "spiral"]}}]},
    "bad-unknown-param.json": {"sweep_format": 1, "scenes": ["a.scene.json"],
                               "techniques": [{"name": "pcf", "params": {"alpha": 1}}]},
    "bad-out-of-range.json": {"sweep_format": 1, "scenes": ["b.scene.json"],
                              "techniques": [{"name": "basic",
                                              "params": {"resolution": [128, 256]}}]},
    "bad-twice.json": {"sweep_format": 1, "scenes": ["a.scene.json"],
                       "techniques": [{"name": "basic", "params": {"resolution": [512, 512]}}]},
    "bad-no-scene.json": {"sweep_format": 1, "scenes": ["missing/*.scene.json"],
                          "techniques": [{"name": "basic"}]},
    "bad-format.json": {"sweep_format": 2, "scenes": ["a.scene.json"],
                        "techniques": [{"name": "basic"}], "oracle": {"spp": 0}},
}


def sweep_seeds():
    for name, spec in SWEEP_SEEDS.items():
        write("sweep", name, (json.dumps(spec, indent=1) + "\n").encode())


def json_strings(j, out):
    """The keys, and the short string values, of a parsed JSON value."""
    if isinstance(j, dict):
        for k, v in j.items():
            out.add(k)
            if isinstance(v, str) and len(v) < 24 and not v.startswith("data:"):
                out.add(v)
            json_strings(v, out)
    elif isinstance(j, list):
        for v in j:
            json_strings(v, out)


# Strings the JSON keys do not give: the sweep harness's scene files and a few globs.
DICT_EXTRA = {"sweep": ["a.scene.json", "b.scene.json", "sub/c.scene.json",
                        "../outside.scene.json", "*.scene.json", "sub/*"],
              # values of the compression extensions that no seed holds (issue 42)
              "gltf": ["OCTAHEDRAL", "QUATERNION", "NONE", "KHR_mesh_quantization",
                       "KHR_materials_variants", "normalized"]}


def write_dicts(harnesses=("scene", "gltf", "gate", "index", "sweep")):
    """tests/fuzz/<harness>.dict: libFuzzer dictionaries of the JSON keys of each corpus."""
    for h in harnesses:
        found = set()
        for f in (CORPUS / h).iterdir():
            data = f.read_bytes()[1:] if h == "gltf" else f.read_bytes()
            for part in data.split(b"\0"):
                try:
                    json_strings(json.loads(part), found)
                except (ValueError, RecursionError):
                    pass
        found.update(DICT_EXTRA.get(h, []))
        words = sorted(k for k in found
                       if 0 < len(k) <= 40 and re.fullmatch(r"[A-Za-z0-9_.:/*?# -]+", k))
        with open(CORPUS.parent / (h + ".dict"), "w") as out:
            out.write("# libFuzzer dictionary for fuzz_%s: the keys and short string values of its"
                      " seed corpus\n# (written by tests/fuzz/make_corpus.py).\n" % h)
            for w in words:
                out.write('"\\"%s\\""\n' % w)


def small_metrics():
    """The first two rows of a demo metrics.json (out/demo/), if the demo was run."""
    for f in sorted((ROOT / "out/demo").glob("*/metrics.json")):
        j = json.loads(f.read_text())
        j["results"] = j["results"][:2]
        return json.dumps(j, separators=(",", ":")).encode()
    return None


if __name__ == "__main__":
    main()
    write_dicts()
