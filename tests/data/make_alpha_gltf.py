#!/usr/bin/env python3
"""Writes the glTF files of the alpha-tested material tests (issue 17): valid ones into gltf/ (their
expected values are in tests/gltf_loader_test.cpp) and one broken file per rule into broken_gltf/
(their errors in broken_gltf/expected.tsv). Deterministic; re-run only to change them."""
import base64, copy, json, os, struct, zlib

HERE = os.path.dirname(os.path.abspath(__file__))
VALID, BROKEN = os.path.join(HERE, "gltf"), os.path.join(HERE, "broken_gltf")


def png(w, h, channels, pixel):
    """8-bit PNG bytes; pixel(i, j) gives `channels` values (1 grey, 2 grey+alpha, 3 RGB, 4 RGBA)."""
    kind = {1: 0, 2: 4, 3: 2, 4: 6}[channels]
    raw = b"".join(b"\x00" + bytes(c for i in range(w) for c in pixel(i, j)) for j in range(h))
    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, kind, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


# 4 x 4 RGBA: alpha 0, 85, 170, 255 by column, rows alike; colour irrelevant.
CHECKER = png(4, 4, 4, lambda i, j: (200, 100, 50, 85 * i))
# 2 x 2 grey+alpha: alpha 255 on the diagonal, 0 elsewhere.
DIAGONAL = png(2, 2, 2, lambda i, j: (128, 255 if i == j else 0))


def triangle_model(uv=((0.0, 0.0), (1.0, 0.0), (0.0, 1.0)), material=None, image=None, sampler=None,
                   transform=None, uv_type=("VEC2", 5126), uv_count=3):
    """One triangle with TEXCOORD_0 and (optionally) one material, texture, sampler and image."""
    pos = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    if uv_type == ("VEC2", 5126):
        tex = b"".join(struct.pack("<2f", *t) for t in uv)
    else:
        tex = b"".join(struct.pack("<3f", t[0], t[1], 0) for t in uv)
    tex = tex[: len(tex) * uv_count // 3]
    buf = pos + tex
    g = {
        "asset": {"version": "2.0"},
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0}]}],
        "buffers": [{"byteLength": len(buf),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(buf).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
                        {"buffer": 0, "byteOffset": len(pos), "byteLength": len(tex)}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": uv_type[1], "count": uv_count, "type": uv_type[0]}],
        "materials": [material if material is not None else {"alphaMode": "MASK", "alphaCutoff": 0.5,
                                   "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [sampler if sampler is not None else {"magFilter": 9728, "wrapS": 33071, "wrapT": 10497}],
        "images": [image if image is not None else {"uri": data_uri("image/png", CHECKER)}],
    }
    if transform is not None:
        g["extensionsUsed"] = ["KHR_texture_transform"]
        info = g["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]
        info["extensions"] = {"KHR_texture_transform": transform}
    return g


def huge_header():
    """A valid PNG signature and IHDR claiming 70000 x 70000 pixels, then one row of data: the size
    must be refused from the header, before any pixel is read."""
    one = png(1, 1, 1, lambda i, j: (0,))
    ihdr = b"IHDR" + struct.pack(">IIBBBBB", 70000, 70000, 8, 0, 0, 0, 0)
    return one[:8] + struct.pack(">I", 13) + ihdr + struct.pack(">I", zlib.crc32(ihdr)) + one[33:]


def data_uri(mime, data):
    return "data:" + mime + ";base64," + base64.b64encode(data).decode()


def write_json(folder, name, g):
    with open(os.path.join(folder, name), "w") as f:
        json.dump(g, f, separators=(",", ":"))
        f.write("\n")


def write_glb(folder, name, g, image_bytes):
    """GLB whose BIN chunk holds the model's data: URI buffer followed by the image."""
    g = copy.deepcopy(g)
    data = base64.b64decode(g["buffers"][0]["uri"].split(",", 1)[1])
    data += b"\x00" * (-len(data) % 4)
    offset = len(data)
    data += image_bytes + b"\x00" * (-len(image_bytes) % 4)
    g["buffers"] = [{"byteLength": len(data)}]
    g["bufferViews"].append({"buffer": 0, "byteOffset": offset, "byteLength": len(image_bytes)})
    g["images"] = [{"bufferView": len(g["bufferViews"]) - 1, "mimeType": "image/png"}]
    js = json.dumps(g, separators=(",", ":")).encode()
    js += b" " * (-len(js) % 4)
    body = struct.pack("<II", len(js), 0x4E4F534A) + js + struct.pack("<II", len(data), 0x004E4942) + data
    with open(os.path.join(folder, name), "wb") as f:
        f.write(struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body)


def main():
    with open(os.path.join(VALID, "alpha_checker.png"), "wb") as f:
        f.write(CHECKER)
    # The KHR_texture_transform example of its specification: the lower left quadrant, turned.
    write_json(VALID, "alpha_mask.gltf", triangle_model(
        image={"uri": "alpha_checker.png"},
        material={"alphaMode": "MASK", "alphaCutoff": 0.25,
                  "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.5], "baseColorTexture": {"index": 0}}},
        transform={"offset": [0, 1], "rotation": 1.57079632679, "scale": [0.5, 0.5]}))
    write_glb(VALID, "alpha_embedded.glb", triangle_model(
        sampler={"magFilter": 9729, "wrapS": 33648, "wrapT": 33071}), CHECKER)
    write_json(VALID, "alpha_blend_datauri.gltf", triangle_model(
        material={"alphaMode": "BLEND", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}},
        image={"uri": data_uri("image/png", DIAGONAL)}, sampler={}))

    broken = {
        "alpha_bad_mode.gltf": triangle_model(material={"alphaMode": "CUTOUT"}),
        "alpha_negative_cutoff.gltf": triangle_model(material={"alphaMode": "MASK", "alphaCutoff": -0.5}),
        "alpha_texture_out_of_range.gltf": triangle_model(
            material={"alphaMode": "MASK", "pbrMetallicRoughness": {"baseColorTexture": {"index": 3}}}),
        "alpha_bad_factor.gltf": triangle_model(
            material={"alphaMode": "MASK", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 2],
                                                                    "baseColorTexture": {"index": 0}}}),
        "alpha_image_outside.gltf": triangle_model(image={"uri": "../gltf/alpha_checker.png"}),
        "alpha_image_missing.gltf": triangle_model(image={"uri": "nothere.png"}),
        "alpha_image_truncated.gltf": triangle_model(image={"uri": data_uri("image/png", CHECKER[:40])}),
        "alpha_image_huge.gltf": triangle_model(image={"uri": data_uri("image/png", huge_header())}),
        "alpha_image_not_png.gltf": triangle_model(image={"uri": data_uri("image/png", b"GIF89a not an image")}),
        "alpha_bad_wrap.gltf": triangle_model(sampler={"wrapS": 12345}),
        "alpha_bad_filter.gltf": triangle_model(sampler={"magFilter": 9987}),
        "alpha_uv_count.gltf": triangle_model(uv_count=2),
        "alpha_uv_type.gltf": triangle_model(uv_type=("VEC3", 5126)),
        "alpha_transform_bad.gltf": triangle_model(transform={"scale": "twice"}),
    }
    no_uv = triangle_model()
    del no_uv["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"]
    broken["alpha_no_texcoord.gltf"] = no_uv
    no_source = triangle_model()
    del no_source["textures"][0]["source"]
    broken["alpha_texture_no_source.gltf"] = no_source
    for name, g in broken.items():
        write_json(BROKEN, name, g)


if __name__ == "__main__":
    main()
