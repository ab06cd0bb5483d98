#!/usr/bin/env python3
"""scripts/growth-study: what `shadow-oracle trace` costs as the work grows (issue 32).

Runs the real command on generated scenes (the benches' bumpy terrain grid and 16 spheres,
bench/bench_scene.h, written as a binary glTF with a scene file around it), varying one axis at a
time from a baseline of 718,976 triangles, 1024 x 1024 pixels and one point light:

  triangles  45,056 to 10.0 M (terrain grid 64 to 2232)
  pixels     512^2 to 4096^2 (0.26 to 16.8 Mpixels)
  lights     1 to 64, point lights and, as a second series, directional lights

and the area lights at the baseline: the benches' rect light with `penumbra`, and a disk of the
same area and place beside it (issue 55: a disk's exact pass at a rect's cost). Each run is a
child process: its wall time, its CPU time and its peak resident memory
(GNU time's %M; measure() says why not wait4) are measured, and oracle.json's phases_seconds
says where the time went.
Per axis it fits the growth (least squares on log-log: time ~ size^k) and, for memory, a straight
line (MiB per million triangles, per megapixel, per light: the slope, with the intercept).

Then `trace --tile I/N` as a Slurm job array on the local cluster (scripts/slurm-local) followed by
`trace-merge` as a dependent job, against one process: wall time from submission to the end of
the merge, the merge's own time and memory, and whether the merged oracle.exr equals the single
process's byte for byte. Skipped, with the reason, where no cluster can be had.

The tables go into a markdown file between "BEGIN growth study" and "END growth study" markers.
Measured, not asserted; every failing command stops the study with its log's tail.

    growth_study.py study --tool BIN [--work DIR] [--doc FILE] [--quick] [--reps N] [--no-slurm]
    growth_study.py render out/growth-study.json [--doc FILE]   (the tables again, no runs)
    growth_study.py measure OUT.json -- COMMAND...   (used inside the Slurm jobs)
"""
import argparse, datetime, filecmp, json, math, os, re, shutil, struct, subprocess, sys
import tempfile, threading, time

import numpy as np
from doc_markers import write_between_markers

# --- the generated scene (bench/bench_scene.h) -------------------------------------------------

SPHERES = 16
SPHERE_SEGMENTS, SPHERE_RINGS = 48, 24
SPHERE_TRIANGLES = SPHERES * SPHERE_SEGMENTS * SPHERE_RINGS * 2  # 36,864

BASE_GRID = 584  # 2 * 584^2 + 36,864 = 718,976 triangles
BASE_SIDE = 1024  # 1,048,576 pixels
FULL_AXES = {"grids": [64, 256, 420, 584, 1200, 1650, 2232],
             "sides": [512, 724, 1024, 1448, 2048, 2896, 4096],
             "lights": [1, 2, 4, 8, 16, 32, 64],
             "slurm_cases": [("point", 4096), ("rect", 1024)], "slurm_tasks": [2, 4, 8]}
QUICK_AXES = {"grids": [64, 128], "sides": [256, 384], "lights": [1, 4],
              "slurm_cases": [("point", 256), ("rect", 128)], "slurm_tasks": [2]}
QUICK_BASE = {"grid": 64, "side": 256}


def triangles_of(grid):
    return 2 * grid * grid + SPHERE_TRIANGLES


def terrain(n):
    """The benches' terrain: (n+1)^2 vertices over [-20, 20]^2, 2 n^2 triangles."""
    i = np.arange(n + 1, dtype=np.float64)
    x = -20.0 + 40.0 * i / n
    z = 20.0 - 40.0 * i / n
    xx, zz = np.meshgrid(x, z)  # row j: z_j, column i: x_i, as bench_scene.h's j * (n + 1) + i
    yy = 0.8 * np.sin(0.4 * xx) * np.cos(0.33 * zz) + 0.25 * np.sin(1.7 * xx + 0.9 * zz)
    positions = np.stack([xx, yy, zz], axis=-1).reshape(-1, 3)
    jj, ii = np.meshgrid(np.arange(n, dtype=np.uint32), np.arange(n, dtype=np.uint32),
                         indexing="ij")
    a = (jj * (n + 1) + ii).reshape(-1)
    b, d = a + 1, a + np.uint32(n + 1)
    e = d + 1
    indices = np.stack([a, d, e, a, e, b], axis=-1).reshape(-1)
    return positions, indices


def sphere(center, r, n, m):
    th = np.pi * np.arange(m + 1) / m
    ph = 2 * np.pi * np.arange(n + 1) / n
    tt, pp = np.meshgrid(th, ph, indexing="ij")
    positions = np.stack([np.sin(tt) * np.cos(pp), np.cos(tt), np.sin(tt) * np.sin(pp)],
                         axis=-1).reshape(-1, 3) * r + np.asarray(center)
    jj, ii = np.meshgrid(np.arange(m, dtype=np.uint32), np.arange(n, dtype=np.uint32),
                         indexing="ij")
    a = (jj * (n + 1) + ii).reshape(-1)
    b, d = a + 1, a + np.uint32(n + 1)
    e = d + 1
    return positions, np.stack([a, b, e, a, e, d], axis=-1).reshape(-1)


def write_glb(path, primitives):
    """A binary glTF 2.0 file: one node, one mesh, a primitive per (positions, indices)."""
    blobs, views, accessors, prims = [], [], [], []
    offset = 0
    for positions, indices in primitives:
        p32 = positions.astype(np.float32)
        for data, target in ((p32.tobytes(), 34962), (indices.astype(np.uint32).tobytes(), 34963)):
            views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(data),
                          "target": target})
            blobs.append(data)
            offset += len(data)  # both are multiples of 4
        accessors.append({"bufferView": len(views) - 2, "componentType": 5126,
                          "count": len(p32), "type": "VEC3",
                          "min": p32.min(axis=0).tolist(), "max": p32.max(axis=0).tolist()})
        accessors.append({"bufferView": len(views) - 1, "componentType": 5125,
                          "count": len(indices), "type": "SCALAR"})
        prims.append({"attributes": {"POSITION": len(accessors) - 2},
                      "indices": len(accessors) - 1, "mode": 4})
    doc = {"asset": {"version": "2.0", "generator": "scripts/growth_study.py"},
           "buffers": [{"byteLength": offset}], "bufferViews": views, "accessors": accessors,
           "meshes": [{"name": "growth", "primitives": prims}], "nodes": [{"mesh": 0}],
           "scenes": [{"nodes": [0]}], "scene": 0}
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    tmp = path + ".part"
    with open(tmp, "wb") as f:
        f.write(struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(text) + 8 + offset))
        f.write(struct.pack("<II", len(text), 0x4E4F534A))
        f.write(text)
        f.write(struct.pack("<II", offset, 0x004E4942))
        for blob in blobs:
            f.write(blob)
    os.replace(tmp, path)


def mesh_file(scenes_dir, grid):
    """scenes_dir/terrain_GRID.glb, generated once per work folder."""
    name = f"terrain_{grid}.glb"
    path = os.path.join(scenes_dir, name)
    if not os.path.exists(path):
        prims = [terrain(grid)]
        for k in range(SPHERES):
            a = 2 * math.pi * k / SPHERES
            prims.append(sphere((9 * math.cos(a), 3.0 + (k % 3), 9 * math.sin(a)), 1.2,
                                SPHERE_SEGMENTS, SPHERE_RINGS))
        write_glb(path, prims)
    return name


def point_lights(k):
    """The benches' point light, then k - 1 on a ring above the terrain."""
    lights = [{"name": "p0", "type": "point", "position": [2, 14, 3]}]
    for i in range(1, k):
        a = 2 * math.pi * (i - 1) / (k - 1) + 0.3
        r, h = 6.0 + 3.0 * (i % 3), 11.0 + 2.0 * (i % 4)
        lights.append({"name": f"p{i}", "type": "point",
                       "position": [round(r * math.cos(a), 6), h, round(r * math.sin(a), 6)]})
    return lights


def directional_lights(k):
    """The benches' sun, then k - 1 suns around it, 35 to 75 degrees above the horizon."""
    lights = [{"name": "d0", "type": "directional", "direction": [0.5, -1, 0.3]}]
    for i in range(1, k):
        a = 2 * math.pi * (i - 1) / (k - 1) + 0.3
        el = math.radians(35 + 10 * (i % 5))
        lights.append({"name": f"d{i}", "type": "directional",
                       "direction": [round(-math.cos(el) * math.cos(a), 6),
                                     round(-math.sin(el), 6),
                                     round(-math.cos(el) * math.sin(a), 6)]})
    return lights


def rect_light():
    """bench_area_shadow's rect light (4 x 3, 12 above the terrain, emitting downwards)."""
    return [{"name": "rect", "type": "rect", "center": [1, 12, 2], "u": [4, 0, 0],
             "v": [0, 0, 3]}]


def disk_light():
    """A disk of the rect's area (radius sqrt(12 / pi)) at its centre, emitting downwards."""
    return [{"name": "disk", "type": "disk", "center": [1, 12, 2], "normal": [0, -1, 0],
             "radius": round(math.sqrt(12.0 / math.pi), 6)}]


def scene_file(scenes_dir, grid, lights, tag, effects=("hard",)):
    path = os.path.join(scenes_dir, f"g{grid}_{tag}.scene.json")
    scene = {"scene_format": 1,
             "geometry": [{"file": mesh_file(scenes_dir, grid)}],
             "camera": {"eye": [0, 22, 26], "target": [0, 0, 0], "vfov_deg": 55,
                        "width": BASE_SIDE, "height": BASE_SIDE},
             "lights": lights, "effects": list(effects)}
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)
    return path


# --- measuring a child process ----------------------------------------------------------------

TIME = "/usr/bin/time"


def measure(cmd, log_path, relay=None):
    """Runs cmd under GNU time; returns its exit code, wall seconds, CPU seconds (user + system)
    and peak RSS in bytes. stdout and stderr go to log_path; with relay, stderr lines are also
    printed, prefixed, as they come (trace's progress lines).

    The peak RSS is GNU time's %M, not this process's wait4: Linux's ru_maxrss of a child keeps
    the high-water mark of the memory it was forked with (exec records the old mm's), so a child
    of this process, which holds the generated meshes, would report at least this process's
    size (/bin/true started from a parent of 800 MB reports 800 MB). time is small when it forks."""
    with tempfile.NamedTemporaryFile("r", suffix=".time") as times, open(log_path, "w") as log:
        t0 = time.perf_counter()
        p = subprocess.Popen([TIME, "-o", times.name, "-f", "%M %U %S", *cmd], stdout=log,
                             stderr=subprocess.PIPE, text=True)

        def pump():
            for line in p.stderr:
                log.write(line)
                log.flush()
                if relay:
                    print(f"{relay}{line.rstrip()}", file=sys.stderr, flush=True)

        reader = threading.Thread(target=pump)
        reader.start()
        rc = p.wait()
        wall = time.perf_counter() - t0
        reader.join()
        # A failed command adds a line ("Command exited with non-zero status N") before ours.
        last = times.read().strip().splitlines()[-1].split()
    if len(last) != 3:
        fail(f"{TIME}: unexpected output {' '.join(last)!r} for {' '.join(cmd)}")
    return {"rc": rc, "wall": wall, "cpu": float(last[1]) + float(last[2]),
            "rss": int(last[0]) * 1024}


def fail(what, log_path=None, rc=None):
    msg = f"growth-study: FAILED: {what}"
    if rc is not None:  # GNU time exits 128 + N when the command was killed by signal N
        msg += f" (exit {rc}" + (f", killed by signal {rc - 128}" if rc > 128 else "") + ")"
    print(msg, file=sys.stderr)
    if log_path and os.path.exists(log_path):
        tail = open(log_path, errors="replace").read().splitlines()[-15:]
        print(f"--- last lines of {log_path}:", *tail, sep="\n", file=sys.stderr)
    if rc == 128 + 9:
        print("growth-study: SIGKILL: probably the kernel's OOM killer (see dmesg)",
              file=sys.stderr)
    sys.exit(1)


def exr_seconds(log):
    """The time on trace's last progress line for writing oracle.exr ("writing DIR/oracle.exr:
    100.0% after 9.4s"); None where there is none (the stage took under two seconds)."""
    found = re.findall(r"writing \S*oracle\.exr: +100\.0% after ([0-9.]+)s", open(log).read())
    return float(found[-1]) if found else None


def exr_estimate(r):
    """The whole EXR write, estimated from exr_seconds: the progress line's clock starts at the
    first report, which comes after the first of the writer's 256-row blocks (core/exr_io.cpp),
    so it covers B - 1 of B blocks; scaled by B / (B - 1)."""
    if r["exr_s"] is None:
        return None
    blocks = -(-r["json"]["image"]["height"] // 256)
    return r["exr_s"] * blocks / (blocks - 1) if blocks > 1 else None


class Runner:
    """Runs `trace` for the study, counting and printing progress."""

    def __init__(self, tool, work, reps, total):
        self.tool, self.work, self.reps, self.total, self.done = tool, work, reps, total, 0
        self.t_start = time.perf_counter()

    def trace(self, label, scene, side, extra=()):
        """The fastest of `reps` runs (the least disturbed by other load), with its oracle.json;
        the peak memory is the largest of the runs'."""
        self.done += 1
        best = None
        for rep in range(self.reps):
            out = os.path.join(self.work, "runs", f"{label}.{rep}")
            shutil.rmtree(out, ignore_errors=True)
            os.makedirs(out)
            load = os.getloadavg()[0]
            elapsed = time.perf_counter() - self.t_start
            print(f"[{self.done}/{self.total}] {label} (rep {rep + 1}/{self.reps}, "
                  f"{elapsed:.0f} s so far, load {load:.1f}) ...", file=sys.stderr, flush=True)
            cmd = [self.tool, "trace", scene, "--out", out, "--width", str(side),
                   "--height", str(side), *extra]
            log = out + ".log"
            r = measure(cmd, log, relay="    ")
            if r["rc"] != 0:
                fail(" ".join(cmd), log, r["rc"])
            r["json"] = json.load(open(os.path.join(out, "oracle.json")))
            r["load"] = load
            r["exr"] = os.path.getsize(os.path.join(out, "oracle.exr"))
            r["exr_s"] = exr_seconds(log)
            shutil.rmtree(out)  # the images: up to a GiB at 16 Mpixels; oracle.json is kept in r
            print(f"    {r['wall']:.2f} s wall, {r['cpu']:.2f} s CPU, peak RSS "
                  f"{r['rss'] / 2**20:.0f} MiB", file=sys.stderr, flush=True)
            if best is None:
                best = r
            else:
                rss = max(best["rss"], r["rss"])
                best = min(best, r, key=lambda x: x["wall"])
                best["rss"] = rss
        return best


# --- fits -------------------------------------------------------------------------------------

def loglog_exponent(xs, ys):
    """k of y ~ c x^k by least squares on logs; None with fewer than two positive points."""
    pts = [(x, y) for x, y in zip(xs, ys) if x > 0 and y > 0]
    if len(pts) < 2:
        return None
    lx, ly = np.log([p[0] for p in pts]), np.log([p[1] for p in pts])
    return float(np.polyfit(lx, ly, 1)[0])


def line(xs, ys):
    slope, intercept = np.polyfit(np.asarray(xs, float), np.asarray(ys, float), 1)
    return float(slope), float(intercept)


PHASES = ["load", "build_bvh", "primary", "shadow", "write"]


def phase(r, name):
    return r["json"]["phases_seconds"].get(name, 0.0)


# --- the axes ---------------------------------------------------------------------------------

def run_axes(runner, scenes, axes, base):
    """{axis: [(x, run)]}: x is triangles, pixels or lights."""
    results = {"triangles": [], "pixels": [], "point lights": [], "directional lights": []}
    base_scene = scene_file(scenes, base["grid"], point_lights(1), "point1")
    for grid in axes["grids"]:
        scene = scene_file(scenes, grid, point_lights(1), "point1")
        r = runner.trace(f"triangles-{triangles_of(grid)}", scene, base["side"])
        results["triangles"].append((r["json"]["scene"]["triangles"], r))
    for side in axes["sides"]:
        r = runner.trace(f"pixels-{side}x{side}", base_scene, side)
        results["pixels"].append((side * side, r))
    for k in axes["lights"]:
        for kind, make in (("point", point_lights), ("directional", directional_lights)):
            scene = scene_file(scenes, base["grid"], make(k), f"{kind}{k}")
            r = runner.trace(f"lights-{kind}-{k}", scene, base["side"])
            results[f"{kind} lights"].append((k, r))
    areas = {}
    for kind, make in (("rect", rect_light), ("disk", disk_light)):
        scene = scene_file(scenes, base["grid"], make(), f"{kind}1", effects=("penumbra",))
        areas[kind] = runner.trace(f"area-{kind}", scene, base["side"])
    return results, areas


# --- Slurm ------------------------------------------------------------------------------------

def slurm_ready(root):
    """(True, "") when the local cluster answers (started if needed), else (False, why)."""
    script = os.path.join(root, "scripts", "slurm-local")
    st = subprocess.run([script, "status"], capture_output=True, text=True)
    started = False
    if st.returncode != 0:
        print("growth-study: starting the local Slurm cluster (scripts/slurm-local start)",
              file=sys.stderr, flush=True)
        st = subprocess.run([script, "start"], capture_output=True, text=True)
        if st.returncode != 0:
            lines = (st.stderr.strip() or st.stdout.strip() or "no output").splitlines()
            return False, f"`scripts/slurm-local start` failed: {lines[-1]}", False
        started = True
    env = subprocess.run([script, "env"], capture_output=True, text=True, check=True).stdout
    m = re.search(r"SLURM_CONF=(\S+)", env)
    os.environ["SLURM_CONF"] = m.group(1)
    return True, "", started


def sbatch(script_path, *args):
    r = subprocess.run(["sbatch", "--parsable", *args, script_path], capture_output=True,
                       text=True)
    if r.returncode != 0:
        fail(f"sbatch {script_path}: {r.stderr.strip()}")
    return r.stdout.strip().split(";")[0]


def job_state(job):
    """The job's state (an array: the first non-finished task's, else COMPLETED or the
    first failure); empty while it is unknown."""
    r = subprocess.run(["scontrol", "show", "job", job, "-o"], capture_output=True, text=True)
    states = re.findall(r"JobState=(\S+)", r.stdout)
    if not states:
        return ""
    for s in states:
        if s in ("PENDING", "RUNNING", "CONFIGURING", "COMPLETING", "SUSPENDED"):
            return s
    bad = [s for s in states if s != "COMPLETED"]
    return bad[0] if bad else "COMPLETED"


def wait_job(job, timeout=7200):
    t0 = time.time()
    while time.time() - t0 < timeout:
        s = job_state(job)
        if s and s not in ("PENDING", "RUNNING", "CONFIGURING", "COMPLETING", "SUSPENDED"):
            return s
        time.sleep(0.2)
    fail(f"Slurm job {job} still running after {timeout} s")


def job_script(path, lines, **sb):
    head = ["#!/bin/bash"] + [f"#SBATCH --{k.replace('_', '-')}={v}" for k, v in sb.items()]
    with open(path, "w") as f:
        f.write("\n".join(head + ["set -euo pipefail"] + lines) + "\n")


def slurm_run(tool, d, case, scene, side, n, cpus, single):
    """Submits the trace as N array tasks (N = 1: one job without --tile) and, for N > 1, the
    merge as a job depending on them; waits; returns the timeline, checked against the single
    process's files byte for byte."""
    me = os.path.abspath(__file__)
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(os.path.join(d, "logs"))
    band = lambda i: os.path.join(d, f"band-{i}")
    tile = f"--tile $SLURM_ARRAY_TASK_ID/{n}" if n > 1 else ""
    job_script(os.path.join(d, "bands.sbatch"),
               [f"exec {sys.executable} {me} measure {d}/band-$SLURM_ARRAY_TASK_ID.measure.json"
                f" -- {tool} trace {scene} {tile} --out {d}/band-$SLURM_ARRAY_TASK_ID "
                f"--width {side} --height {side} --threads {cpus} --quiet"],
               job_name=f"growth-{case}-n{n}", array=f"0-{n - 1}", cpus_per_task=cpus,
               output=f"{d}/logs/band-%a.log")
    load = os.getloadavg()[0]
    t_submit = time.time()
    bands = sbatch(os.path.join(d, "bands.sbatch"))
    last = bands
    if n > 1:
        job_script(os.path.join(d, "merge.sbatch"),
                   [f"exec {sys.executable} {me} measure {d}/merge.measure.json -- {tool} "
                    "trace-merge " + " ".join(band(i) for i in range(n))
                    + f" --out {d}/merged --quiet"],
                   job_name=f"growth-{case}-merge-n{n}", cpus_per_task=cpus,
                   output=f"{d}/logs/merge.log", kill_on_invalid_dep="yes")
        last = sbatch(os.path.join(d, "merge.sbatch"), f"--dependency=afterok:{bands}")
    for job, what in ((bands, "band"), (last, "merge")):
        state = wait_job(job)
        if state != "COMPLETED":
            fail(f"Slurm {what} job {job} ended {state} (logs in {d}/logs)",
                 os.path.join(d, "logs", "merge.log" if what == "merge" else "band-0.log"))
    ms = [json.load(open(band(i) + ".measure.json")) for i in range(n)]
    merge = json.load(open(os.path.join(d, "merge.measure.json"))) if n > 1 else None
    end = merge["end"] if merge else max(m["end"] for m in ms)
    result = os.path.join(d, "merged") if n > 1 else band(0)
    same = {f: filecmp.cmp(os.path.join(result, f), os.path.join(single["out"], f),
                           shallow=False)
            for f in sorted(os.listdir(single["out"])) if f.endswith((".exr", ".png"))}
    if not all(same.values()):
        fail(f"{result}: differs from the single process's {single['out']}: "
             + ", ".join(f for f, s in same.items() if not s))
    row = {"n": n, "total": end - t_submit, "bands": ms, "merge": merge, "load": load,
           "first_start": min(m["start"] for m in ms) - t_submit,
           "dispatch_gap": (merge["start"] - max(m["end"] for m in ms)) if merge else 0,
           "same": same,
           "band_phases": [json.load(open(os.path.join(band(i), "oracle.json")))
                           ["phases_seconds"] for i in range(n)]}
    for i in range(n):
        shutil.rmtree(band(i))
    shutil.rmtree(os.path.join(d, "merged"), ignore_errors=True)
    return row


def slurm_case(tool, work, scenes, base, case, side, tasks, cpus, reps):
    """One process, then the Slurm runs, of one scene (case: "point" or "rect"); each the
    fastest of `reps`, whole (submission to the merge's end)."""
    scene = (scene_file(scenes, base["grid"], point_lights(1), "point1") if case == "point" else
             scene_file(scenes, base["grid"], rect_light(), "rect1", effects=("penumbra",)))
    out = os.path.join(work, "slurm", f"{case}-single")
    single = None
    for rep in range(reps):
        shutil.rmtree(out, ignore_errors=True)
        os.makedirs(out)
        print(f"growth-study: Slurm, {case} light, {side} x {side}: one process (rep "
              f"{rep + 1}/{reps}) ...", file=sys.stderr, flush=True)
        cmd = [tool, "trace", scene, "--out", out, "--width", str(side), "--height", str(side),
               "--threads", str(cpus), "--quiet"]
        load = os.getloadavg()[0]
        r = measure(cmd, out + ".log")
        if r["rc"] != 0:
            fail(" ".join(cmd), out + ".log", r["rc"])
        r["json"] = json.load(open(os.path.join(out, "oracle.json")))
        r["load"] = load
        print(f"    {r['wall']:.2f} s", file=sys.stderr, flush=True)
        single = r if single is None or r["wall"] < single["wall"] else single
    single["out"] = out  # every rep wrote the same bytes (checked against each Slurm run)
    rows = []
    for n in [1] + tasks:
        best = None
        for rep in range(reps):
            print(f"growth-study: Slurm, {case} light, {n} task(s) (rep {rep + 1}/{reps}) ...",
                  file=sys.stderr, flush=True)
            row = slurm_run(tool, os.path.join(work, "slurm", f"{case}-n{n}"), case, scene, side,
                            n, cpus, single)
            print(f"    {row['total']:.2f} s from submission to the end; files identical",
                  file=sys.stderr, flush=True)
            best = row if best is None or row["total"] < best["total"] else best
        rows.append(best)
    shutil.rmtree(out)
    return {"case": case, "side": side, "single": single, "rows": rows}


def run_slurm(root, tool, work, scenes, axes, base, reps):
    ok, why, started = slurm_ready(root)
    if not ok:
        print(f"growth-study: skipping the Slurm split: {why}", file=sys.stderr)
        return {"skipped": why}
    foreign = subprocess.run(["squeue", "-h", "-o", "%i %j"], capture_output=True,
                             text=True).stdout.strip()
    cpus = os.cpu_count()
    try:
        cases = [slurm_case(tool, work, scenes, base, case, side, axes["slurm_tasks"], cpus,
                            reps) for case, side in axes["slurm_cases"]]
    finally:
        if started:  # leave the cluster as it was found
            left = subprocess.run(["squeue", "-h", "-o", "%i"], capture_output=True,
                                  text=True).stdout.strip()
            if left:
                print("growth-study: leaving the local cluster up: jobs are queued",
                      file=sys.stderr)
            else:
                subprocess.run([os.path.join(root, "scripts", "slurm-local"), "stop"],
                               capture_output=True)
    version = subprocess.run(["sinfo", "--version"], capture_output=True, text=True).stdout
    return {"cpus": cpus, "triangles": triangles_of(base["grid"]), "cases": cases,
            "version": version.strip(), "foreign_jobs": foreign}


# --- the markdown -----------------------------------------------------------------------------

def mib(b):
    return b / 2**20


def fmt_count(x):
    if x >= 1e6:
        return f"{x / 1e6:.2f} M"
    return f"{x:,}"


AXIS_UNITS = {"triangles": ("triangles", 1e6, "MiB per million triangles"),
              "pixels": ("pixels", 2**20, "MiB per megapixel (2^20 pixels)"),
              "point lights": ("lights", 1, "MiB per light"),
              "directional lights": ("lights", 1, "MiB per light")}


def axis_table(name, points):
    head = (f"| {AXIS_UNITS[name][0]} | wall s | CPU s | peak RSS MiB | load | build_bvh | "
            "primary | shadow | write | of which oracle.exr, about | oracle.exr MiB | "
            "load average |")
    rows = [head, "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for x, r in points:
        label = fmt_count(x) if name != "pixels" else f"{r['side']}² ({x / 2**20:.2f} M)"
        rows.append(f"| {label} | {r['wall']:.2f} | {r['cpu']:.2f} | {mib(r['rss']):.0f} | "
                    + " | ".join(f"{phase(r, p):.2f}" for p in PHASES)
                    + " | " + ("< 2" if exr_estimate(r) is None else f"{exr_estimate(r):.1f}")
                    + f" | {mib(r['exr']):.0f} | {r['load']:.1f} |")
    return "\n".join(rows)


def fits(name, points):
    xs = [x for x, _ in points]
    unit = AXIS_UNITS[name][1]
    f = {k: (loglog_exponent(xs, [r[k] for _, r in points]),
             loglog_exponent(xs[-2:], [r[k] for _, r in points[-2:]])) for k in ("wall", "cpu")}
    f["phases"] = {p: loglog_exponent(xs, [phase(r, p) for _, r in points]) for p in PHASES}
    mem = [mib(r["rss"]) for _, r in points]
    f["mem_slope"], f["mem_intercept"] = line(np.asarray(xs, float) / unit, mem)
    f["mem_top"] = (mem[-1] - mem[-2]) / ((xs[-1] - xs[-2]) / unit)
    f["mem_exponent"] = loglog_exponent(xs, mem)
    return f


def exp_str(k):
    return "–" if k is None else f"{k:.2f}"


def fits_table(results):
    rows = ["| axis | range | wall time exponent: all points; two largest | CPU time exponent: "
            "all; two largest | exponents of load / build_bvh / primary / shadow / write | "
            "peak RSS: slope of the line | intercept MiB | slope between the two largest | "
            "memory exponent |", "|---|---|---|---|---|---|---|---|---|"]
    for name, points in results.items():
        if len(points) < 2:
            continue
        f = fits(name, points)
        lo, hi = points[0][0], points[-1][0]
        rng = (f"{fmt_count(lo)} to {fmt_count(hi)}" if name != "pixels"
               else f"{lo / 2**20:.2f} to {hi / 2**20:.2f} M")
        unit = AXIS_UNITS[name][2]
        rows.append(f"| {name} | {rng} | {exp_str(f['wall'][0])}; {exp_str(f['wall'][1])} | "
                    f"{exp_str(f['cpu'][0])}; {exp_str(f['cpu'][1])} | "
                    + " / ".join(exp_str(f["phases"][p]) for p in PHASES)
                    + f" | {f['mem_slope']:.1f} {unit} | {f['mem_intercept']:.0f} | "
                    f"{f['mem_top']:.1f} {unit} | {exp_str(f['mem_exponent'])} |")
    return "\n".join(rows)


def phases_str(ph):
    return ", ".join(f"{p} {ph.get(p, 0.0):.2f}" for p in PHASES)


def case_title(c, triangles):
    what = ("one point light" if c["case"] == "point" else
            "the rect light with `penumbra`, adaptive (target 0.01)")
    return (f"{triangles:,} triangles, {what}, {c['side']} x {c['side']} "
            f"({c['side'] ** 2 / 2**20:.2f} Mpixels)")


def slurm_case_section(c, triangles):
    single = c["single"]
    lines = [f"*{case_title(c, triangles)}.* One process (`trace` without `--tile`, not through "
             f"Slurm): **{single['wall']:.2f} s** wall, {single['cpu']:.2f} s CPU, peak RSS "
             f"{mib(single['rss']):.0f} MiB, load average {single['load']:.1f} "
             f"(seconds: {phases_str(single['json']['phases_seconds'])}).", "",
             "| tasks N | submission to the end of trace-merge, s | against one process | "
             "bands: wall s (min-max; sum) | bands: CPU s (sum; the heaviest band's share) | "
             "bands: peak RSS MiB (max) | Slurm's own latency s (to the first start; last band "
             "to the merge; all idle) | trace-merge: wall s; CPU s | trace-merge: peak RSS MiB "
             "| merged files = one process's, byte for byte | load average at submission |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in c["rows"]:
        walls = [b["wall"] for b in r["bands"]]
        cpus = [b["cpu"] for b in r["bands"]]
        merge = r["merge"]
        mw = merge["wall"] if merge else 0.0
        idle = r["total"] - sum(walls) - mw
        same = ("yes: " + ", ".join(sorted(r["same"]))) if all(r["same"].values()) else "NO"
        lines.append(
            f"| {r['n']} | {r['total']:.2f} | {single['wall'] / r['total']:.2f}x | "
            f"{min(walls):.2f}-{max(walls):.2f}; {sum(walls):.2f} | {sum(cpus):.2f}; "
            f"{max(cpus) / sum(cpus):.2f} | {mib(max(b['rss'] for b in r['bands'])):.0f} | "
            f"{r['first_start']:.2f}; "
            + (f"{r['dispatch_gap']:.2f}; {idle:.2f} | {mw:.2f}; {merge['cpu']:.2f} | "
               f"{mib(merge['rss']):.0f}" if merge else f"–; {idle:.2f} | – | –")
            + f" | {same} | {r['load']:.1f} |")
    lines += ["", "What they predict for N nodes like this one, each band on a node of its own at "
              "once. In CPU seconds, which the other work on this shared machine disturbs far less "
              "than wall times: the critical path is the heaviest band, then the merge; the "
              "speed-up, the single process's CPU time over it (both run the same phases with the "
              "same threads). Slurm's latency (to the first start, and from the last band to the "
              "merge, on this cluster) comes on top in wall time:", "",
              "| tasks N | band phases, mean wall s | heaviest band: CPU s (share of the bands'; "
              "an even split: 1/N) | trace-merge CPU s | critical path, CPU s | predicted "
              "speed-up | bands' CPU beyond one process's, per added band, s | Slurm's latency "
              "here, s |", "|---|---|---|---|---|---|---|---|"]
    for r in c["rows"]:
        if r["n"] == 1:
            continue
        cpus = [b["cpu"] for b in r["bands"]]
        critical = max(cpus) + r["merge"]["cpu"]
        mean = {p: float(np.mean([ph.get(p, 0.0) for ph in r["band_phases"]])) for p in PHASES}
        lines.append(f"| {r['n']} | {phases_str(mean)} | {max(cpus):.2f} "
                     f"({max(cpus) / sum(cpus):.2f}; {1 / r['n']:.3f}) | {r['merge']['cpu']:.2f} "
                     f"| {critical:.2f} | {single['cpu'] / critical:.2f}x | "
                     f"{(sum(cpus) - single['cpu']) / (r['n'] - 1):.2f} | "
                     f"{r['first_start'] + r['dispatch_gap']:.2f} |")
    return "\n".join(lines)


def slurm_section(s):
    if "skipped" in s:
        return f"**The Slurm split was skipped**: {s['skipped']}.\n"
    lines = [f"{s['version']}, one node of {s['cpus']} cores (scripts/slurm-local). Each band is "
             f"an array task asking for all {s['cpus']} cores (`--cpus-per-task={s['cpus']}`, "
             f"`trace --tile I/N --threads {s['cpus']}`), as a band would have a node of its own "
             "on a cluster, so here the bands run one after another; `trace-merge` is a job "
             "submitted with `--dependency=afterok` on the array. Times are measured inside the "
             "jobs (each command's start and end; its CPU time and peak RSS from GNU time); "
             "\"submission\" is just before the first sbatch. N = 1 is one job without `--tile` "
             "and without a merge. Each row is the fastest of the runs, whole.", ""]
    if s["foreign_jobs"]:
        lines += [f"Other jobs were queued when it began: {s['foreign_jobs']}.", ""]
    for c in s["cases"]:
        lines += [slurm_case_section(c, s["triangles"]), ""]
    return "\n".join(lines)


def machine_line(info, reps):
    return (f"{info['date']}, {info['cpu']} ({info['cores']} cores, shared with other work), "
            f"{info['mem_gib']:.1f} GiB, Embree {info['embree']}, `--threads` all cores; the "
            f"fastest of {reps} run(s) per point, peak RSS the largest; load averages (1, 5, 15 "
            f"min) {info['load_before']} before and {info['load_after']} after.")


def largest_table(results, areas):
    """Where the time goes in the largest run of each axis, and the area lights'."""
    rows = ["| run | wall s | load | build_bvh | primary | shadow | write (of which oracle.exr) "
            "| not in a phase (start-up, exit) |", "|---|---|---|---|---|---|---|---|"]
    named = [(f"{fmt_count(pts[-1][0])} {AXIS_UNITS[name][0]}" if name != "pixels" else
              f"{pts[-1][1]['side']}² pixels", pts[-1][1])
             for name, pts in results.items() if pts]
    named[2:] = [(f"{label} ({name.split()[0]})", r) for (label, r), name in
                 zip(named[2:], list(results)[2:])]
    for label, r in named + [(f"the {kind} light (area)", r) for kind, r in areas.items()]:
        share = lambda sec: f"{sec:.2f} ({100 * sec / r['wall']:.0f}%)"
        exr = "" if exr_estimate(r) is None else f"; {exr_estimate(r):.1f}"
        rest = r["wall"] - sum(phase(r, p) for p in PHASES)
        rows.append(f"| {label} | {r['wall']:.2f} | "
                    + " | ".join(share(phase(r, p)) for p in PHASES[:4])
                    + f" | {share(phase(r, 'write'))}{exr} | {share(rest)} |")
    return "\n".join(rows)


def markdown(data):
    info, results, slurm = data["info"], data["results"], data["slurm"]
    # Before issue 55 a study ran the rect light alone ("area").
    areas = data.get("areas") or {"rect": data["area"]}
    parts = [f"`{data['cmdline']}`: {machine_line(info, data['reps'])}", ""]
    parts += ["**Fitted growth** (time ~ size^k by least squares on log-log, over every point and "
              "between the two largest; the memory: a straight line through the peak RSS by least "
              "squares, its slope and intercept, and the slope between the two largest points):",
              "", fits_table(results), ""]
    parts += ["**Where the time goes** in the largest run of each axis (seconds and share of the "
              "wall time; oracle.json's phases_seconds). `write` is the EXR, then a PNG preview per "
              "light; the EXR's part is estimated from trace's progress line (which starts after "
              "the first of its 256-row blocks: scaled by B / (B - 1) for B blocks; no line, so "
              "no estimate, under 2 s); the rest of `write` is the previews:", "",
              largest_table(results, areas), ""]
    for name, points in results.items():
        parts += [f"**{name[0].upper() + name[1:]}** (the others at the baseline):", "",
                  axis_table(name, points), ""]
    shapes = {"rect": "the benches' rect light (4 x 3, 12 above the terrain)",
              "disk": "a disk of the same area at the same place"}
    for kind, area in areas.items():
        light = area["json"]["lights"][0]
        method = light.get("penumbra_choice", {}).get("chosen", "sampled")
        exact = light.get("exact_penumbra") or {}
        parts += [f"**An area light** at the baseline: {shapes.get(kind, kind)}, with `penumbra` "
                  f"(`--penumbra auto`: {method}{'' if method != 'sampled' else ', adaptive, target 0.01'}): "
                  f"{area['wall']:.2f} s wall, {area['cpu']:.2f} s CPU, peak RSS "
                  f"{mib(area['rss']):.0f} MiB; {light.get('rays_traced', 0):,} rays"
                  + (f", mean {light['spp_mean']:.1f} spp (max {light['spp_max']})"
                     if light.get("spp_mean") is not None else "")
                  + (f", {exact['pixels_exact']:,} pixels exact" if exact.get("pixels_exact")
                     else "")
                  + f", shadow {phase(area, 'shadow'):.2f} s, write {phase(area, 'write'):.2f} s.",
                  ""]
    parts += ["**trace --tile over Slurm array tasks**:", "", slurm_section(slurm)]
    return "\n".join(parts)


def replace_between(doc_path, body):
    write_between_markers(doc_path, "growth study", body)


def machine_info(tool, embree):
    cpu = "?"
    for l in open("/proc/cpuinfo"):
        if l.startswith("model name"):
            cpu = l.split(":", 1)[1].strip()
            break
    mem = int(re.search(r"MemTotal:\s+(\d+)", open("/proc/meminfo").read()).group(1))
    return {"date": datetime.date.today().isoformat(), "cpu": cpu, "cores": os.cpu_count(),
            "mem_gib": mem / 2**20, "embree": embree}


def study(args):
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    tool = os.path.abspath(args.tool)
    if not os.access(tool, os.X_OK):
        fail(f"{tool}: not an executable (build it: cmake --build build --target shadow-oracle)")
    os.makedirs(os.path.join(root, "out"), exist_ok=True)
    temp = args.work is None
    work = os.path.abspath(args.work or tempfile.mkdtemp(prefix="growth-",
                                                         dir=os.path.join(root, "out")))
    scenes = os.path.join(work, "scenes")
    os.makedirs(scenes, exist_ok=True)
    os.makedirs(os.path.join(work, "runs"), exist_ok=True)
    axes = QUICK_AXES if args.quick else FULL_AXES
    base = QUICK_BASE if args.quick else {"grid": BASE_GRID, "side": BASE_SIDE}
    load_before = "%.2f, %.2f, %.2f" % os.getloadavg()
    if not os.access(TIME, os.X_OK):
        fail(f"{TIME} not found (Debian package time): it measures the peak memory")
    print(f"growth-study: work folder {work}; load averages {load_before}", file=sys.stderr)
    print("growth-study: generating meshes ...", file=sys.stderr, flush=True)
    for grid in sorted(set(axes["grids"] + [base["grid"]])):
        t0 = time.perf_counter()
        mesh_file(scenes, grid)
        print(f"    terrain grid {grid}: {triangles_of(grid):,} triangles "
              f"({time.perf_counter() - t0:.1f} s)", file=sys.stderr, flush=True)
    total = len(axes["grids"]) + len(axes["sides"]) + 2 * len(axes["lights"]) + 2
    runner = Runner(tool, work, args.reps, total)
    results, areas = run_axes(runner, scenes, axes, base)
    area = areas["rect"]
    for x, r in results["pixels"]:
        r["side"] = int(round(math.sqrt(x)))
    slurm = ({"skipped": "--no-slurm"} if args.no_slurm
             else run_slurm(root, tool, work, scenes, axes, base, args.reps))
    info = machine_info(tool, area["json"]["libraries"]["embree"])
    info["load_before"], info["load_after"] = load_before, "%.2f, %.2f, %.2f" % os.getloadavg()
    cmdline = "scripts/growth-study" + (" --quick" if args.quick else "") + (
        f" --reps {args.reps}" if args.reps != (1 if args.quick else 2) else "") + (
        " --no-slurm" if args.no_slurm else "")
    data = {"info": info, "results": results, "area": area, "areas": areas, "slurm": slurm,
            "reps": args.reps, "cmdline": cmdline}
    saved = os.path.join(root, "out", "growth-study-quick.json" if args.quick
                         else "growth-study.json")
    with open(saved, "w") as f:
        json.dump(data, f)
    print(f"growth-study: the measurements: {saved} (render them again with "
          f"scripts/growth_study.py render {os.path.relpath(saved, root)})", file=sys.stderr)
    if temp and not args.keep:
        shutil.rmtree(work)
    else:
        print(f"growth-study: kept {work}", file=sys.stderr)
    doc = args.doc if args.doc else (None if args.quick else os.path.join(
        root, "docs", "benchmarks-growth.md"))
    render(data, doc)


def render(data, doc):
    body = markdown(data)
    if doc:
        replace_between(doc, body)
        print(f"growth-study: updated {doc}", file=sys.stderr)
    else:
        print(body)


def measure_main(argv):
    """measure OUT.json -- COMMAND...: run it, write its times and peak RSS, exit with its code."""
    if len(argv) < 3 or argv[1] != "--":
        sys.exit("usage: growth_study.py measure OUT.json -- COMMAND...")
    start = time.time()
    r = measure(argv[2:], argv[0] + ".log")
    r.update(start=start, end=start + r["wall"])
    with open(argv[0], "w") as f:
        json.dump(r, f)
    sys.stdout.write(open(argv[0] + ".log").read())
    sys.exit(r["rc"])


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "measure":
        measure_main(sys.argv[2:])
    if len(sys.argv) > 1 and sys.argv[1] == "render":
        r = argparse.ArgumentParser(description="the tables again from a study's saved "
                                    "measurements (out/growth-study.json)")
        r.add_argument("command")
        r.add_argument("results")
        r.add_argument("--doc", help="markdown file to write between the markers (default: print)")
        a = r.parse_args()
        render(json.load(open(a.results)), a.doc)
        return
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("command", choices=["study"])
    p.add_argument("--tool", required=True, help="the shadow-oracle binary")
    p.add_argument("--work", help="folder for the generated scenes and the runs (default: a "
                   "temporary folder under out/, removed at the end)")
    p.add_argument("--keep", action="store_true", help="keep the temporary work folder")
    p.add_argument("--doc", help="markdown file to write between the markers (default "
                   "docs/benchmarks-growth.md; with --quick, none: the tables are printed)")
    p.add_argument("--quick", action="store_true", help="small axes: checks the script itself")
    p.add_argument("--reps", type=int, help="runs per point, the fastest kept (default 2; 1 "
                   "with --quick)")
    p.add_argument("--no-slurm", action="store_true", help="skip the Slurm split")
    args = p.parse_args()
    if args.reps is None:
        args.reps = 1 if args.quick else 2
    if args.reps < 1:
        sys.exit("growth_study.py: --reps: at least 1")
    study(args)


if __name__ == "__main__":
    main()
