#!/usr/bin/env python3
"""Writes the shipped default scenes and their meshes (committed; re-run only to change them).

All meshes are plain glTF 2.0 with an embedded base64 buffer: float32 positions, uint32 indices,
counter-clockwise outward winding. Output is deterministic (fixed formulas, no randomness).
"""
import base64, json, math, os, struct, zlib

HERE = os.path.dirname(os.path.abspath(__file__))
MESHES = os.path.join(HERE, "meshes")


def write_gltf(name, positions, indices):
    pos = b"".join(struct.pack("<3f", *p) for p in positions)
    idx = b"".join(struct.pack("<I", i) for i in indices)
    buf = pos + idx
    lo = [min(p[k] for p in positions) for k in range(3)]
    hi = [max(p[k] for p in positions) for k in range(3)]
    g = {
        "asset": {"version": "2.0", "generator": "shadow-oracle scenes/make_scenes.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": name}],
        "meshes": [{"name": name, "primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}],
        "buffers": [{"byteLength": len(buf),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(buf).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos), "target": 34962},
                        {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx), "target": 34963}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3",
                       "min": lo, "max": hi},
                      {"bufferView": 1, "componentType": 5125, "count": len(indices), "type": "SCALAR"}],
    }
    with open(os.path.join(MESHES, name + ".gltf"), "w") as f:
        json.dump(g, f, separators=(",", ":"))
        f.write("\n")


def write_png_rgba(path, w, h, rgba):
    """An 8-bit RGBA PNG (no filter), from rows of (r, g, b, a) tuples, top row first."""
    raw = b"".join(b"\x00" + bytes(c for px in row for c in px) for row in rgba)
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0))
           + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
    with open(path, "wb") as f:
        f.write(png)


def write_masked_gltf(name, positions, uvs, indices, image, cutoff=0.5, uv_scale=(1.0, 1.0)):
    """A glTF mesh with an alpha-tested material (alphaMode MASK): its base colour texture is the
    PNG `image` (beside it), read with nearest filtering and repeat wrapping, its coordinates scaled
    by KHR_texture_transform."""
    pos = b"".join(struct.pack("<3f", *p) for p in positions)
    tex = b"".join(struct.pack("<2f", *t) for t in uvs)
    idx = b"".join(struct.pack("<I", i) for i in indices)
    buf = pos + tex + idx
    lo = [min(p[k] for p in positions) for k in range(3)]
    hi = [max(p[k] for p in positions) for k in range(3)]
    g = {
        "asset": {"version": "2.0", "generator": "shadow-oracle scenes/make_scenes.py"},
        "extensionsUsed": ["KHR_texture_transform"],
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": name}],
        "meshes": [{"name": name, "primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2,
                                                  "mode": 4, "material": 0}]}],
        "materials": [{"name": name, "alphaMode": "MASK", "alphaCutoff": cutoff, "doubleSided": True,
                       "pbrMetallicRoughness": {"baseColorTexture": {
                           "index": 0, "extensions": {"KHR_texture_transform": {"scale": list(uv_scale)}}}}}],
        "textures": [{"sampler": 0, "source": 0}],
        "samplers": [{"magFilter": 9728, "minFilter": 9728, "wrapS": 10497, "wrapT": 10497}],
        "images": [{"uri": image}],
        "buffers": [{"byteLength": len(buf),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(buf).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos), "target": 34962},
                        {"buffer": 0, "byteOffset": len(pos), "byteLength": len(tex), "target": 34962},
                        {"buffer": 0, "byteOffset": len(pos) + len(tex), "byteLength": len(idx), "target": 34963}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3",
                       "min": lo, "max": hi},
                      {"bufferView": 1, "componentType": 5126, "count": len(uvs), "type": "VEC2"},
                      {"bufferView": 2, "componentType": 5125, "count": len(indices), "type": "SCALAR"}],
    }
    with open(os.path.join(MESHES, name + ".gltf"), "w") as f:
        json.dump(g, f, separators=(",", ":"))
        f.write("\n")


def grate_texture(n=64, period=16, bar=4):
    """Square holes in a lattice of bars: texel (i, j) is a bar where i or j mod period < bar, so a
    share (1 - bar / period)^2 is open (56.25% here)."""
    metal, hole = (92, 96, 104, 255), (0, 0, 0, 0)
    return [[metal if (i % period < bar or j % period < bar) else hole for i in range(n)] for j in range(n)]


def grid(n, m, f):
    """(n+1) x (m+1) vertices from f(i/n, j/m); two triangles per cell, facing +Y for f = xz-plane."""
    pos = [f(i / n, j / m) for j in range(m + 1) for i in range(n + 1)]
    idx = []
    for j in range(m):
        for i in range(n):
            a = j * (n + 1) + i
            b, d = a + 1, a + n + 1
            e = d + 1
            idx += [a, e, d, a, b, e]  # counter-clockwise seen from +Y
    return pos, idx


def box(lo, hi):
    pos = [((hi[0] if k & 1 else lo[0]), (hi[1] if k & 2 else lo[1]), (hi[2] if k & 4 else lo[2])) for k in range(8)]
    faces = [(0, 4, 6, 2), (1, 3, 7, 5), (0, 1, 5, 4), (2, 6, 7, 3), (0, 2, 3, 1), (4, 5, 7, 6)]
    idx = []
    for a, b, c, d in faces:
        idx += [a, b, c, a, c, d]
    return pos, idx


def uv_sphere(center, r, n=48, m=24):
    pos, idx = [], []
    pos.append((center[0], center[1] + r, center[2]))
    for j in range(1, m):
        th = math.pi * j / m
        for i in range(n):
            ph = 2 * math.pi * i / n
            pos.append((center[0] + r * math.sin(th) * math.cos(ph), center[1] + r * math.cos(th),
                        center[2] - r * math.sin(th) * math.sin(ph)))
    pos.append((center[0], center[1] - r, center[2]))
    south = len(pos) - 1
    ring = lambda j, i: 1 + (j - 1) * n + (i % n)
    for i in range(n):
        idx += [0, ring(1, i), ring(1, i + 1)]
        idx += [south, ring(m - 1, i + 1), ring(m - 1, i)]
    for j in range(1, m - 1):
        for i in range(n):
            a, b, c, d = ring(j, i), ring(j, i + 1), ring(j + 1, i), ring(j + 1, i + 1)
            idx += [a, c, d, a, d, b]
    return pos, idx


def cylinder(center, r, h, n=48):
    pos, idx = [], []
    for y in (0.0, h):
        for i in range(n):
            ph = 2 * math.pi * i / n
            pos.append((center[0] + r * math.cos(ph), center[1] + y, center[2] - r * math.sin(ph)))
    bottom_c, top_c = len(pos), len(pos) + 1
    pos += [(center[0], center[1], center[2]), (center[0], center[1] + h, center[2])]
    for i in range(n):
        a, b = i, (i + 1) % n
        idx += [a, b, b + n, a, b + n, a + n]
        idx += [top_c, a + n, b + n]
        idx += [bottom_c, b, a]
    return pos, idx


def torus(center, R, r, n=64, m=24):
    pos, idx = [], []
    for i in range(n):
        u = 2 * math.pi * i / n
        for j in range(m):
            v = 2 * math.pi * j / m
            pos.append((center[0] + (R + r * math.cos(v)) * math.cos(u), center[1] + r * math.sin(v),
                        center[2] - (R + r * math.cos(v)) * math.sin(u)))
    for i in range(n):
        for j in range(m):
            a, b = i * m + j, ((i + 1) % n) * m + j
            c, d = i * m + (j + 1) % m, ((i + 1) % n) * m + (j + 1) % m
            idx += [a, b, d, a, d, c]
    return pos, idx


def boulder(subdiv=5):
    """An icosphere displaced by a few octaves of smooth deterministic noise: a rock-like mesh."""
    t = (1 + 5 ** 0.5) / 2
    verts = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
             (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
             (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11),
             (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    verts = [tuple(c / math.sqrt(sum(x * x for x in v)) for c in v) for v in verts]
    for _ in range(subdiv):
        cache, nf = {}, []
        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                m = [(verts[a][k] + verts[b][k]) / 2 for k in range(3)]
                l = math.sqrt(sum(x * x for x in m))
                verts.append(tuple(x / l for x in m))
                cache[key] = len(verts) - 1
            return cache[key]
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            nf += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = nf
    def bump(x, y, z):
        return (0.18 * math.sin(2.1 * x + 1.3 * y) * math.cos(1.7 * z - 0.4 * x) + 0.09 * math.sin(4.7 * y + 3.1 * z)
                + 0.05 * math.cos(7.3 * x - 5.9 * z + 2.2 * y) + 0.025 * math.sin(13.1 * x + 11.7 * y - 9.3 * z))
    pos = []
    for x, y, z in verts:
        r = 1.0 + bump(x, y, z)
        pos.append((r * x * 1.3, r * y * 0.8 + 0.55, r * z))
    return pos, [i for f in faces for i in f]


def torus_knot(p=2, q=3, n=360, m=20, R=1.0, r=0.22):
    def curve(t):
        rr = math.cos(q * t) + 2
        return (rr * math.cos(p * t) / 3 * R * 1.5, math.sin(q * t) / 3 * R * 1.5, rr * math.sin(p * t) / 3 * R * 1.5)
    pos, idx = [], []
    for i in range(n):
        t = 2 * math.pi * i / n
        c0, c1 = curve(t), curve(t + 1e-3)
        tng = [c1[k] - c0[k] for k in range(3)]
        l = math.sqrt(sum(x * x for x in tng)); tng = [x / l for x in tng]
        up = (0.0, 1.0, 0.0)
        b = [tng[1] * up[2] - tng[2] * up[1], tng[2] * up[0] - tng[0] * up[2], tng[0] * up[1] - tng[1] * up[0]]
        l = math.sqrt(sum(x * x for x in b)); b = [x / l for x in b]
        nn = [b[1] * tng[2] - b[2] * tng[1], b[2] * tng[0] - b[0] * tng[2], b[0] * tng[1] - b[1] * tng[0]]
        for j in range(m):
            a = 2 * math.pi * j / m
            pos.append(tuple(c0[k] + r * (math.cos(a) * nn[k] + math.sin(a) * b[k]) for k in range(3)))
    for i in range(n):
        for j in range(m):
            a0, a1 = i * m + j, i * m + (j + 1) % m
            b0, b1 = ((i + 1) % n) * m + j, ((i + 1) % n) * m + (j + 1) % m
            idx += [a0, b0, b1, a0, b1, a1]
    return pos, idx


def write_multi_gltf(name, meshes):
    """One glTF with a mesh and node per (mesh name, positions, indices), uint16 indices, the
    buffer in NAME.bin beside it (a large scene: base64 would add a third)."""
    blob, views, accessors, gmeshes, nodes = b"", [], [], [], []
    for k, (mname, positions, indices) in enumerate(meshes):
        assert len(positions) < 65536
        pos = b"".join(struct.pack("<3f", *p) for p in positions)
        idx = b"".join(struct.pack("<H", i) for i in indices)
        idx += b"\0" * (-len(idx) % 4)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(pos), "target": 34962})
        blob += pos
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": 2 * len(indices), "target": 34963})
        blob += idx
        lo = [min(p[c] for p in positions) for c in range(3)]
        hi = [max(p[c] for p in positions) for c in range(3)]
        accessors.append({"bufferView": 2 * k, "componentType": 5126, "count": len(positions), "type": "VEC3",
                          "min": lo, "max": hi})
        accessors.append({"bufferView": 2 * k + 1, "componentType": 5123, "count": len(indices), "type": "SCALAR"})
        gmeshes.append({"name": mname, "primitives": [{"attributes": {"POSITION": 2 * k}, "indices": 2 * k + 1, "mode": 4}]})
        nodes.append({"mesh": k, "name": mname})
    g = {
        "asset": {"version": "2.0", "generator": "shadow-oracle scenes/make_scenes.py"},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes, "meshes": gmeshes,
        "buffers": [{"byteLength": len(blob), "uri": name + ".bin"}],
        "bufferViews": views, "accessors": accessors,
    }
    with open(os.path.join(MESHES, name + ".bin"), "wb") as f:
        f.write(blob)
    with open(os.path.join(MESHES, name + ".gltf"), "w") as f:
        json.dump(g, f, separators=(",", ":"))
        f.write("\n")


def big_terrain_height(x, z):
    # Long rolling hills (tens of units) with smaller bumps: a landscape seen to the horizon.
    return (6.0 * math.sin(0.021 * x + 0.4) * math.cos(0.017 * z) + 2.5 * math.sin(0.05 * x - 0.03 * z)
            + 0.8 * math.sin(0.13 * x + 0.11 * z) * math.cos(0.09 * z))


def big_terrain_meshes(half=256.0, chunks=8, cells=24, seed=12345):
    """The terrain in chunks x chunks meshes, each carrying the objects standing on it (posts,
    blocks and slabs at deterministic pseudo-random places: a linear congruential generator with a
    fixed seed), so that a renderer can cull per chunk. Objects: a few per chunk everywhere, and a
    denser field of smaller ones in the 76 units ahead of the camera (z from 160 to 232, denser
    nearer), as a player sees rocks and posts around them."""
    state = [seed]

    def rand():
        state[0] = (1103515245 * state[0] + 12345) % (1 << 31)
        return state[0] / float(1 << 31)

    side = 2 * half / chunks
    objects = []  # (x, z, kind, size, angle)
    for cj in range(chunks):
        for ci in range(chunks):
            x0, z0 = -half + ci * side, -half + cj * side
            for _ in range(6):
                objects.append((x0 + side * (0.1 + 0.8 * rand()), z0 + side * (0.1 + 0.8 * rand()),
                                rand(), 0.5 + 3.0 * rand(), 2 * math.pi * rand()))
    for _ in range(220):
        z = 160.0 + 72.0 * rand() ** 1.5
        x = (rand() - 0.5) * (8.0 + 1.0 * (236.0 - z))
        objects.append((x, z, rand(), 0.3 + 1.2 * rand(), 2 * math.pi * rand()))
    meshes = []
    for cj in range(chunks):
        for ci in range(chunks):
            x0, z0 = -half + ci * side, -half + cj * side
            pos, idx = grid(cells, cells, lambda u, v: (x0 + side * u, big_terrain_height(x0 + side * u, z0 + side * (1 - v)), z0 + side * (1 - v)))
            for x, z, kind, size, angle in objects:
                if not (x0 <= x < x0 + side and z0 <= z < z0 + side):
                    continue
                w, h, d = ((0.3 * size, 2.5 * size, 0.3 * size) if kind < 0.4 else
                           (size, size, size) if kind < 0.8 else (2.5 * size, 0.4 * size, 1.2 * size))
                y = big_terrain_height(x, z) - 0.3
                bp, bi = box((-w / 2, 0.0, -d / 2), (w / 2, h + 0.3, d / 2))
                c, s_ = math.cos(angle), math.sin(angle)
                base = len(pos)
                pos += [(x + c * p[0] + s_ * p[2], y + p[1], z - s_ * p[0] + c * p[2]) for p in bp]
                idx += [base + i for i in bi]
            meshes.append(("chunk_%d_%d" % (ci, cj), pos, idx))
    return meshes


def terrain_height(x, z):
    # Sums of sines: smooth hills with ridges; deterministic.
    return (0.9 * math.sin(0.45 * x) * math.cos(0.38 * z) + 0.35 * math.sin(1.3 * x + 0.7 * z)
            + 0.18 * math.cos(2.1 * z - 0.9 * x) + 0.08 * math.sin(4.3 * x) * math.sin(3.7 * z))


def scene(name, geometry, camera, lights, effects=("hard",), scene_format=1):
    s = {"scene_format": scene_format, "geometry": geometry, "camera": camera, "lights": lights, "effects": list(effects)}
    with open(os.path.join(HERE, name), "w") as f:
        json.dump(s, f, indent=2)
        f.write("\n")


def main():
    os.makedirs(MESHES, exist_ok=True)
    write_gltf("floor", *grid(8, 8, lambda u, v: (-10 + 20 * u, 0.0, 10 - 20 * v)))
    write_gltf("unit_box", *box((-0.5, 0.0, -0.5), (0.5, 1.0, 0.5)))
    write_gltf("sphere", *uv_sphere((0.0, 0.0, 0.0), 1.0))
    write_gltf("cylinder", *cylinder((0.0, 0.0, 0.0), 1.0, 1.0))
    write_gltf("torus", *torus((0.0, 0.0, 0.0), 1.0, 0.3))
    write_gltf("terrain", *grid(160, 160, lambda u, v: (-16 + 32 * u, terrain_height(-16 + 32 * u, 16 - 32 * v), 16 - 32 * v)))

    scene("contact_box.scene.json",
          [{"file": "meshes/floor.gltf"},
           {"file": "meshes/unit_box.gltf", "translate": [0, 0, 0], "scale": [2, 1.5, 2]}],
          {"eye": [-5.5, 4.0, -6.0], "target": [0.0, 0.5, 0.0], "up": [0, 1, 0], "vfov_deg": 40,
           "width": 640, "height": 480},
          [{"name": "key", "type": "point", "position": [3.0, 5.0, 2.5]}],
          effects=("hard", "contact"))  # occluder distances: peter-panning is what this scene is for

    scene("spot_objects.scene.json",
          [{"file": "meshes/floor.gltf"},
           {"file": "meshes/unit_box.gltf", "translate": [-2.5, 0, 0.5], "scale": [1.2, 2.0, 1.2]},
           {"file": "meshes/sphere.gltf", "translate": [0.5, 1.0, -1.5], "scale": 1.0},
           {"file": "meshes/cylinder.gltf", "translate": [2.5, 0, 1.5], "scale": [0.6, 2.5, 0.6]},
           {"file": "meshes/torus.gltf", "translate": [0.0, 0.3, 2.5], "scale": 0.9}],
          {"eye": [0.0, 9.0, 11.0], "target": [0.0, 0.5, 0.0], "up": [0, 1, 0], "vfov_deg": 45,
           "width": 640, "height": 480},
          [{"name": "cone", "type": "spot", "position": [1.5, 8.0, 3.0], "direction": [-0.15, -1.0, -0.3],
            "outer_cone_deg": 32, "inner_cone_deg": 26},
           {"name": "fill", "type": "point", "position": [-6.0, 4.0, 6.0]}])

    write_gltf("square", *grid(1, 1, lambda u, v: (-1 + 2 * u, 0.0, 1 - 2 * v)))
    write_gltf("boulder", *boulder())
    write_gltf("torus_knot", *torus_knot())

    # Closed form: a rectangular light, a parallel square occluder and a plane (docs/oracle.md).
    scene("penumbra_square.scene.json",
          [{"file": "meshes/floor.gltf"},
           {"file": "meshes/square.gltf", "translate": [0, 1.5, 0]}],
          {"eye": [0.0, 7.0, 6.0], "target": [0.0, 0.0, 0.0], "up": [0, 1, 0], "vfov_deg": 40,
           "width": 320, "height": 240},
          [{"name": "panel", "type": "rect", "center": [0.5, 4.0, 0.25], "u": [2.0, 0, 0], "v": [0, 0, 1.5]}],
          effects=("penumbra",))

    # A sphere light over rock-like and knotted meshes, with occluder distances for contact.
    scene("sphere_light.scene.json",
          [{"file": "meshes/floor.gltf"},
           {"file": "meshes/boulder.gltf", "translate": [-1.2, 0, 0.3]},
           {"file": "meshes/torus_knot.gltf", "translate": [1.8, 1.3, -0.4], "scale": 0.8}],
          {"eye": [0.0, 5.5, 8.0], "target": [0.2, 0.6, 0.0], "up": [0, 1, 0], "vfov_deg": 42,
           "width": 320, "height": 240},
          [{"name": "globe", "type": "sphere", "center": [0.8, 4.5, 1.5], "radius": 0.6}],
          effects=("penumbra", "contact"))

    # Soft shadows (issue 14): a chair (seat, four legs, a back: boxes) and a box beside it on the
    # floor under a window-sized rect light and a bulb-sized sphere light. Occluders at several
    # heights above the receiver, so penumbrae of many widths, and contact at the legs.
    chair = [([0.0, 1.0, 0.0], [2.0, 0.15, 2.0]),
             ([0.0, 1.15, 0.93], [2.0, 1.3, 0.14])]
    for x in (-0.93, 0.93):
        for z in (-0.93, 0.93):
            chair.append(([x, 0.0, z], [0.14, 1.0, 0.14]))
    boxes = [{"file": "meshes/unit_box.gltf", "translate": t, "scale": sc} for t, sc in chair]
    boxes.append({"file": "meshes/unit_box.gltf", "translate": [2.4, 0.0, -0.6], "scale": [0.9, 0.6, 0.9]})
    scene("soft_chair.scene.json",
          [{"file": "meshes/floor.gltf"}] + boxes,
          {"eye": [-4.5, 5.0, -6.5], "target": [0.4, 0.6, 0.2], "up": [0, 1, 0], "vfov_deg": 42,
           "width": 320, "height": 240},
          [{"name": "window", "type": "rect", "center": [1.2, 4.2, 0.8], "u": [2.0, 0, 0], "v": [0, 0, 1.2]},
           {"name": "bulb", "type": "sphere", "center": [-2.2, 3.2, -1.4], "radius": 0.35}],
          effects=("penumbra",))

    # Polygon lights (scene_format 4): a hexagonal softbox over a small box on the floor, and a
    # tilted triangle beside it. Each is counter-clockwise seen from below, so it lights the floor.
    hexagon = [[round(1.2 * math.cos(math.pi * k / 3), 12), 4.0, round(1.2 * math.sin(math.pi * k / 3), 12)]
               for k in range(6)]
    scene("polygon_softbox.scene.json",
          [{"file": "meshes/floor.gltf"},
           {"file": "meshes/unit_box.gltf", "translate": [0, 0, 0], "scale": [0.8, 1.0, 0.8]}],
          {"eye": [0.0, 6.5, 7.5], "target": [0.3, 0.3, 0.0], "up": [0, 1, 0], "vfov_deg": 42,
           "width": 320, "height": 240},
          [{"name": "softbox", "type": "polygon", "vertices": hexagon},
           {"name": "wedge", "type": "polygon",
            "vertices": [[2.5, 3.0, -1.0], [3.5, 2.6, -1.0], [3.0, 3.2, 0.0]]}],
          effects=("penumbra",), scene_format=4)

    # Alpha-tested occluders (issue 17): a grate of square holes (a 64 x 64 RGBA texture, alphaMode
    # MASK, repeated 3 x 2 times by KHR_texture_transform) tilted 20 degrees, 1.6 above the floor,
    # under the sun and a rect light: every hole is a small hard shadow or a penumbra blur.
    write_png_rgba(os.path.join(MESHES, "grate.png"), 64, 64, grate_texture())
    tilt = math.radians(20.0)
    corner = lambda u, v: (-1.5 + 3.0 * u, 1.6 + (v - 0.5) * 2.0 * math.sin(tilt),
                           (0.5 - v) * 2.0 * math.cos(tilt))
    quad = [corner(u, v) for v in (0.0, 1.0) for u in (0.0, 1.0)]
    write_masked_gltf("grate", quad, [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)],
                      [0, 2, 3, 0, 3, 1], "grate.png", uv_scale=(3.0, 2.0))
    scene("alpha_grate.scene.json",
          [{"file": "meshes/floor.gltf"}, {"file": "meshes/grate.gltf"}],
          {"eye": [-3.5, 4.5, 5.5], "target": [0.3, 0.4, -0.4], "up": [0, 1, 0], "vfov_deg": 40,
           "width": 320, "height": 240},
          [{"name": "sun", "type": "directional", "direction": [0.35, -1.0, -0.45]},
           {"name": "panel", "type": "rect", "center": [-0.5, 4.5, 0.8], "u": [1.2, 0, 0], "v": [0, 0, 0.8]}],
          effects=("hard", "penumbra", "alpha"))

    # The sun 8 degrees above the horizon: long shadows, many points near grazing.
    el = math.radians(8.0)
    az = math.radians(35.0)
    sun = [-math.cos(el) * math.cos(az), -math.sin(el), -math.cos(el) * math.sin(az)]
    scene("terrain_sun.scene.json",
          [{"file": "meshes/terrain.gltf"}],
          {"eye": [-14.0, 9.0, 18.0], "target": [1.0, -1.0, -2.0], "up": [0, 1, 0], "vfov_deg": 45,
           "width": 640, "height": 480},
          [{"name": "sun", "type": "directional", "direction": [round(c, 6) for c in sun]}])

    # A landscape 512 units wide, the camera two metres up at its edge looking to the horizon: one
    # shadow map cannot give both the near ground and the far hills the texels they need
    # (cascades, adaptive; docs/benchmarks.md). The camera path walks slowly forward and turns a
    # little, for shimmer (temporal_flicker_rate).
    write_multi_gltf("large_terrain", big_terrain_meshes())
    eye_y = round(big_terrain_height(0.0, 236.0) + 2.0, 3)
    sun = [-0.75, -0.35, 0.45]  # low, from ahead and to the right: shadows fall towards the camera
    keys = []
    for k in range(5):
        z = 236.0 - 1.0 * k
        keys.append({"t": k, "eye": [round(0.4 * k, 3), round(big_terrain_height(0.4 * k, z) + 2.0, 3), z],
                     "target": [round(6.0 * k, 3), round(eye_y - 6.0, 3), -120.0]})
    s = {"scene_format": 2, "geometry": [{"file": "meshes/large_terrain.gltf"}],
         "camera": {"eye": [0.0, eye_y, 236.0], "target": [0.0, round(eye_y - 6.0, 3), -120.0], "up": [0, 1, 0],
                    "vfov_deg": 55, "width": 800, "height": 450},
         "camera_path": {"keyframes": keys, "interpolation": "catmull-rom"},
         "lights": [{"name": "sun", "type": "directional", "direction": sun}], "effects": ["hard"]}
    with open(os.path.join(HERE, "large_terrain.scene.json"), "w") as f:
        json.dump(s, f, indent=2)
        f.write("\n")


if __name__ == "__main__":
    main()
