#!/usr/bin/env python3
"""Writes the animated glTF files of the loader and oracle tests (issue 52), and the broken ones of
tests/data/broken_scene/ (anim_*). Every buffer is embedded as a data: URI so that each file stands
alone (the fuzz corpus takes them as they are). Run from anywhere; rewrites only the files it names.

sliding_box.gltf: a floor (8 x 8 quad at y = 0, node "floor") and a unit box (node "box", its base
on the floor) that a LINEAR translation slides from x = -2 at t = 0 to x = +2 at t = 0.5 s (clip
"slide"). floor.gltf and box.gltf hold the same meshes without animation, for a static scene that
places the box by hand. chain.gltf: node "arm" turned by a LINEAR rotation from 0 to 90 degrees
about +y over t in [0, 1] (clip "turn"), its child "hand" at (1, 0, 0) drawing a small triangle.
"""
import base64
import json
import math
import pathlib
import struct

HERE = pathlib.Path(__file__).resolve().parent
BROKEN = HERE.parent / "broken_scene"

FLOOR = ([(-4, 0, -4), (4, 0, -4), (4, 0, 4), (-4, 0, 4)], [0, 2, 1, 0, 3, 2])
BOX_V = [(x, y, z) for x in (-0.5, 0.5) for y in (0.0, 1.0) for z in (-0.5, 0.5)]
BOX_I = [0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1,
         2, 3, 7, 2, 7, 6, 0, 2, 6, 0, 6, 4, 1, 5, 7, 1, 7, 3]
TRI = ([(-0.2, 0, -0.2), (0.2, 0, -0.2), (0, 0, 0.2)], [0, 1, 2])


class Builder:
    def __init__(self):
        self.data = bytearray()
        self.views, self.accessors, self.meshes = [], [], []

    def accessor(self, floats, type_, count, extra=None):
        while len(self.data) % 4:
            self.data.append(0)
        offset = len(self.data)
        self.data += struct.pack("<%df" % len(floats), *floats)
        self.views.append({"buffer": 0, "byteOffset": offset, "byteLength": 4 * len(floats)})
        a = {"bufferView": len(self.views) - 1, "componentType": 5126, "count": count,
             "type": type_}
        a.update(extra or {})
        self.accessors.append(a)
        return len(self.accessors) - 1

    def indices(self, idx):
        while len(self.data) % 4:
            self.data.append(0)
        offset = len(self.data)
        self.data += struct.pack("<%dI" % len(idx), *idx)
        self.views.append({"buffer": 0, "byteOffset": offset, "byteLength": 4 * len(idx)})
        self.accessors.append({"bufferView": len(self.views) - 1, "componentType": 5125,
                               "count": len(idx), "type": "SCALAR"})
        return len(self.accessors) - 1

    def mesh(self, name, verts, idx):
        flat = [c for v in verts for c in v]
        lo = [min(v[k] for v in verts) for k in range(3)]
        hi = [max(v[k] for v in verts) for k in range(3)]
        pos = self.accessor(flat, "VEC3", len(verts), {"min": lo, "max": hi})
        self.meshes.append({"name": name, "primitives": [
            {"attributes": {"POSITION": pos}, "indices": self.indices(idx)}]})
        return len(self.meshes) - 1

    def sampler(self, times, values, width, interpolation="LINEAR"):
        t = self.accessor(times, "SCALAR", len(times), {"min": [min(times)], "max": [max(times)]})
        v = self.accessor(values, "VEC%d" % width, len(values) // width)
        return {"input": t, "output": v, "interpolation": interpolation}

    def write(self, path, nodes, roots, animations=(), extra=None):
        doc = {"asset": {"version": "2.0", "generator": "tests/data/anim/make_anim_gltf.py"},
               "scene": 0, "scenes": [{"nodes": roots}], "nodes": nodes, "meshes": self.meshes,
               "accessors": self.accessors, "bufferViews": self.views,
               "buffers": [{"byteLength": len(self.data), "uri": "data:application/octet-stream;"
                            "base64," + base64.b64encode(bytes(self.data)).decode()}]}
        if animations:
            doc["animations"] = list(animations)
        doc.update(extra or {})
        path.write_text(json.dumps(doc, indent=1) + "\n")


def one_channel(b, node, path, times, values, width, interpolation="LINEAR", name="clip"):
    return {"name": name, "samplers": [b.sampler(times, values, width, interpolation)],
            "channels": [{"sampler": 0, "target": {"node": node, "path": path}}]}


def sliding_box(path, **broken):
    b = Builder()
    floor, box = b.mesh("floor", *FLOOR), b.mesh("box", BOX_V, BOX_I)
    nodes = [{"name": "floor", "mesh": floor}, {"name": "box", "mesh": box}]
    anim = one_channel(b, 1, "translation", [0.0, 0.5], [-2, 0, 0, 2, 0, 0], 3, name="slide")
    if "target_node" in broken:
        anim["channels"][0]["target"]["node"] = broken["target_node"]
    if "target_path" in broken:
        anim["channels"][0]["target"]["path"] = broken["target_path"]
    if "times" in broken:
        anim = one_channel(b, 1, "translation", broken["times"], [-2, 0, 0, 2, 0, 0], 3,
                           name="slide")
    if "cubic_count" in broken:  # CUBICSPLINE with one value a key instead of three
        anim["samplers"][0]["interpolation"] = "CUBICSPLINE"
    if "matrix" in broken:
        nodes[1]["matrix"] = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
    if "skinned" in broken:  # a skinned box as the moving node's child
        nodes[1].pop("mesh")
        nodes[1]["children"] = [2]
        nodes.append({"name": "skinned", "mesh": box, "skin": 0})
    b.write(path, nodes, [0, 1], [anim], {"skins": [{"joints": [1]}]} if "skinned" in broken else {})


def static_parts():
    b = Builder()
    b.mesh("floor", *FLOOR)
    b.write(HERE / "floor.gltf", [{"name": "floor", "mesh": 0}], [0])
    b = Builder()
    b.mesh("box", BOX_V, BOX_I)
    b.write(HERE / "box.gltf", [{"name": "box", "mesh": 0}], [0])


def chain():
    b = Builder()
    hand = b.mesh("hand", *TRI)
    half = math.sqrt(0.5)
    nodes = [{"name": "arm", "children": [1]},
             {"name": "hand", "mesh": hand, "translation": [1, 0, 0]}]
    turn = one_channel(b, 0, "rotation", [0.0, 1.0], [0, 0, 0, 1, 0, half, 0, half], 4,
                       name="turn")
    b.write(HERE / "chain.gltf", nodes, [0], [turn])


def scene(path, gltf, extra=None):
    doc = {"scene_format": 5, "geometry": [{"file": gltf}],
           "camera": {"eye": [0, 6, 7], "target": [0, 0, 0], "vfov_deg": 45,
                      "width": 64, "height": 64},
           "lights": [{"name": "sun", "type": "directional", "direction": [-0.8, -1, -0.2]}],
           "sequence": {"frames": 16, "fps": 30}}
    doc.update(extra or {})
    doc = {k: v for k, v in doc.items() if v is not None}
    path.write_text(json.dumps(doc, indent=1) + "\n")


def main():
    sliding_box(HERE / "sliding_box.gltf")
    static_parts()
    chain()
    scene(HERE / "sliding_box.scene.json", "sliding_box.gltf")
    broken = {
        "anim_weights": {"target_path": "weights"},
        "anim_bad_node": {"target_node": 7},
        "anim_times": {"times": [0.5, 0.5]},
        "anim_cubic_count": {"cubic_count": True},
        "anim_matrix": {"matrix": True},
        "anim_skinned": {"skinned": True},
    }
    for name, how in broken.items():
        sliding_box(BROKEN / (name + ".gltf"), **how)
        scene(BROKEN / (name + ".json"), name + ".gltf")
    lamp = {"name": "lamp", "type": "point", "position": [0, 4, 0]}
    sun = {"name": "sun", "type": "directional", "direction": [-0.4, -1, -0.3]}
    two_keys = [{"t": 0, "position": [0, 4, 0]}, {"t": 1, "position": [1, 4, 0]}]
    light_paths = {
        "light_path_no_light": {"light_paths": {"moon": {"keyframes": two_keys}}},
        "light_path_direction_on_point": {
            "lights": [lamp], "light_paths": {"lamp": {"keyframes": [
                {"t": 0, "direction": [0, -1, 0]}, {"t": 1, "direction": [1, -1, 0]}]}}},
        "light_path_position_on_sun": {"light_paths": {"sun": {"keyframes": two_keys}}},
        "light_path_zero_direction": {"light_paths": {"sun": {"keyframes": [
            {"t": 0, "direction": [0, -1, 0]}, {"t": 1, "direction": [0, 0, 0]}]}}},
        "light_path_times": {"lights": [lamp], "light_paths": {"lamp": {"keyframes": [
            {"t": 1, "position": [0, 4, 0]}, {"t": 1, "position": [1, 4, 0]}]}}},
        "light_path_one_key": {"lights": [lamp], "light_paths": {"lamp": {
            "keyframes": two_keys[:1]}}},
        "light_path_mixed_keys": {"lights": [lamp, sun], "light_paths": {"lamp": {"keyframes": [
            {"t": 0, "position": [0, 4, 0]}, {"t": 1}]}}},
        "light_path_interpolation": {"lights": [lamp], "light_paths": {"lamp": {
            "keyframes": two_keys, "interpolation": "cubic"}}},
        "light_path_no_sequence": {"lights": [lamp], "sequence": None,
                                   "light_paths": {"lamp": {"keyframes": two_keys}}},
        "light_path_format_4": {"scene_format": 4, "sequence": None, "lights": [lamp],
                                "light_paths": {"lamp": {"keyframes": two_keys}}},
    }
    for name, extra in light_paths.items():
        scene(BROKEN / (name + ".json"), "tri.gltf", extra)
    sliding_box(BROKEN / "anim_clip.gltf")
    scene(BROKEN / "anim_clip_unknown.json", "anim_clip.gltf",
          {"sequence": {"frames": 4, "fps": 30, "animation": "jump"}})


if __name__ == "__main__":
    main()
