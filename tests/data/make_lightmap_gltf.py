#!/usr/bin/env python3
"""Writes the glTF files of the lightmap coordinate tests (issue 34): TEXCOORD_1 read for every
primitive that has it. A valid file into gltf/ (its expected values are in
tests/gltf_loader_test.cpp) and one broken file per rule into broken_gltf/ (their errors in
broken_gltf/expected.tsv). Deterministic; re-run only to change them."""
import base64, json, os, struct

HERE = os.path.dirname(os.path.abspath(__file__))
VALID, BROKEN = os.path.join(HERE, "gltf"), os.path.join(HERE, "broken_gltf")

# A unit quad in z = 0 (two triangles) and its lightmap coordinates.
QUAD = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
QUAD_INDICES = [0, 1, 2, 0, 2, 3]
UV1 = [(0.125, 0.25), (0.5, 0.25), (0.5, 0.625), (0.125, 0.625)]


def quad_model(uv_bytes, uv_type="VEC2", component=5126, normalized=False, uv_count=4,
               uv_view_length=None):
    """The quad with TEXCOORD_1 given as raw bytes in its own bufferView."""
    pos = b"".join(struct.pack("<3f", *p) for p in QUAD)
    idx = b"".join(struct.pack("<H", i) for i in QUAD_INDICES)
    buf = pos + idx + uv_bytes
    accessor = {"bufferView": 2, "componentType": component, "count": uv_count, "type": uv_type}
    if normalized:
        accessor["normalized"] = True
    return {
        "asset": {"version": "2.0"},
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_1": 2}, "indices": 1}]}],
        "buffers": [{"byteLength": len(buf),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(buf).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
                        {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx)},
                        {"buffer": 0, "byteOffset": len(pos) + len(idx),
                         "byteLength": len(uv_bytes) if uv_view_length is None else uv_view_length}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"},
                      accessor],
    }


def floats(uvs):
    return b"".join(struct.pack("<2f", *t) for t in uvs)


def write_json(folder, name, g):
    with open(os.path.join(folder, name), "w") as f:
        json.dump(g, f, separators=(",", ":"))
        f.write("\n")


def main():
    write_json(VALID, "lightmap_uv.gltf", quad_model(floats(UV1)))
    # Normalized unsigned shorts: 65535 is 1.
    shorts = b"".join(struct.pack("<2H", round(u * 65535), round(v * 65535)) for u, v in UV1)
    write_json(VALID, "lightmap_uv_unorm16.gltf", quad_model(shorts, component=5123, normalized=True))
    broken = {
        "lightmap_uv_count.gltf": quad_model(floats(UV1[:3]), uv_count=3),
        "lightmap_uv_type.gltf": quad_model(b"".join(struct.pack("<3f", u, v, 0) for u, v in UV1),
                                            uv_type="VEC3"),
        "lightmap_uv_not_normalized.gltf": quad_model(shorts, component=5123),
        "lightmap_uv_nonfinite.gltf": quad_model(floats(UV1[:2] + [(float("nan"), 0.5)] + UV1[3:])),
        "lightmap_uv_past_view.gltf": quad_model(floats(UV1), uv_view_length=24),
    }
    for name, g in broken.items():
        write_json(BROKEN, name, g)


if __name__ == "__main__":
    main()
