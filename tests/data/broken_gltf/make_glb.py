#!/usr/bin/env python3
"""Writes the .glb files of the glTF loader tests (broken ones here, a valid one in ../gltf/).

Run from anywhere: python3 make_glb.py. The output is committed; rerun only to change it.
"""
import base64
import json
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
VALID = os.path.join(HERE, "..", "gltf")


def triangle_bin():
    pos = b"".join(struct.pack("<3f", *p) for p in [(0, 0, 0), (1, 0, 0), (0, 1, 0)])
    idx = struct.pack("<3H", 0, 1, 2) + b"\0\0"
    return pos, idx


def triangle_json(bin_len, pos_count=3, buffer_len=None):
    return {
        "asset": {"version": "2.0"},
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": "Triangle"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": bin_len if buffer_len is None else buffer_len}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 36},
            {"buffer": 0, "byteOffset": 36, "byteLength": 6},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": pos_count, "type": "VEC3"},
            {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"},
        ],
    }


def chunk(kind, payload, pad, declared_len=None):
    while len(payload) % 4:
        payload += pad
    n = len(payload) if declared_len is None else declared_len
    return struct.pack("<I4s", n, kind) + payload


def glb(doc, bin_data, version=2, json_len=None, bin_len=None, total_len=None, pad_json=True):
    js = json.dumps(doc).encode()
    if pad_json:
        body = chunk(b"JSON", js, b" ", json_len)
    else:
        body = struct.pack("<I4s", len(js), b"JSON") + js
    if bin_data is not None:
        body += chunk(b"BIN\0", bin_data, b"\0", bin_len)
    n = 12 + len(body) if total_len is None else total_len
    return struct.pack("<4sII", b"glTF", version, n) + body


def write(folder, name, data):
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data)


def main():
    pos, idx = triangle_bin()
    data = pos + idx
    good = glb(triangle_json(len(data)), data)
    write(VALID, "triangle.glb", good)

    write(HERE, "truncated.glb", good[: len(good) - 10])
    write(HERE, "wrong_json_chunk_length.glb", glb(triangle_json(len(data)), data, json_len=4000))
    doc = triangle_json(len(data))
    doc["asset"]["generator"] = "x" * (4 - len(json.dumps(doc).encode()) % 4 + 1)  # odd length
    write(HERE, "unpadded_json_chunk.glb", glb(doc, data, pad_json=False))
    write(HERE, "wrong_bin_chunk_length.glb", glb(triangle_json(len(data)), data, bin_len=4000))
    write(HERE, "short_header.glb", b"glTF" + struct.pack("<II", 2, 12))
    write(HERE, "glb_version_1.glb", glb(triangle_json(len(data)), data, version=1))
    write(HERE, "glb_bin_too_small.glb", glb(triangle_json(len(data), buffer_len=100), data))
    write(HERE, "glb_no_bin_chunk.glb", glb(triangle_json(len(data)), None))
    write(HERE, "glb_accessor_past_view.glb", glb(triangle_json(len(data), pos_count=5), data))


if __name__ == "__main__":
    main()
