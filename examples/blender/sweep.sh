#!/usr/bin/env bash
# Blender EEVEE's shadow settings as a sweep beside the built-in techniques (docs/external.md,
# "A renderer's settings in a sweep"; docs/sweep.md, "A renderer's images"):
#   1. shadow-oracle view, per scene                 OUT/view/<scene>/view.json
#   2. blender: render_shadows.py with EEVEE at every shadow cube size x soft shadows off/on
#                                                    OUT/renders/<scene>/cube_<size>_soft_<0|1>/shadows.exr
#   3. OUT/spec.json: those images as an "images" entry, and slope-bias and pcss over the shadow
#      map resolution, on the same scenes; shadow-oracle sweep OUT/spec.json --out OUT/sweep
#
#   sweep.sh OUT [--width W] [--height H] [--samples N] [--threads T] [SCENE ...]
#
# Default scenes: scenes/penumbra_square.scene.json (a rect light) and scenes/spot_objects.scene.json
# (a spot and a point light), at 160 x 120, EEVEE 16 samples. Environment: SHADOW_ORACLE (default:
# shadow-oracle on PATH), BLENDER (default: blender). EEVEE needs OpenGL: surfaceless EGL with -b,
# else under `xvfb-run -a`. Exit: 0 swept, 1 a step failed, 2 bad input.
set -uo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
so=${SHADOW_ORACLE:-shadow-oracle}
blender=${BLENDER:-blender}

usage() { echo "usage: $0 OUT [--width W] [--height H] [--samples N] [--threads T] [SCENE ...]" >&2; exit 2; }
[ $# -ge 1 ] || usage
out=$1
shift
width=160 height=120 samples=16 threads=2 scenes=()
while [ $# -gt 0 ]; do
  case $1 in
    --width) width=${2:?}; shift 2 ;;
    --height) height=${2:?}; shift 2 ;;
    --samples) samples=${2:?}; shift 2 ;;
    --threads) threads=${2:?}; shift 2 ;;
    -*) usage ;;
    *) scenes+=("$1"); shift ;;
  esac
done
[ ${#scenes[@]} -gt 0 ] || scenes=("$root/scenes/penumbra_square.scene.json" "$root/scenes/spot_objects.scene.json")
command -v "$so" >/dev/null || { echo "sweep.sh: error: no shadow-oracle ($so); set SHADOW_ORACLE" >&2; exit 2; }
command -v "$blender" >/dev/null || { echo "sweep.sh: error: no blender ($blender); set BLENDER" >&2; exit 2; }
for s in "${scenes[@]}"; do
  [ -f "$s" ] || { echo "sweep.sh: error: no scene file $s" >&2; exit 2; }
done
mkdir -p "$out" || exit 1
out=$(cd "$out" && pwd)

cubes=(512 1024 2048 4096)
launcher=("$blender")
# render VIEW DIR ARGS...: one EEVEE render into DIR (its log DIR.log), under xvfb-run when
# surfaceless EGL gives no OpenGL context.
render() {
  local view=$1 dir=$2
  shift 2
  rm -rf "$dir"
  mkdir -p "$(dirname "$dir")"
  for attempt in 1 2; do
    "${launcher[@]}" -b --factory-startup --python-exit-code 1 -P "$here/render_shadows.py" -- \
      "$view" --out "$dir" --engine eevee --samples "$samples" --threads "$threads" "$@" \
      > "$dir.log" 2>&1 && [ -f "$dir/shadows.exr" ] && return 0
    [ $attempt = 1 ] && command -v xvfb-run >/dev/null && [ "${launcher[0]}" != xvfb-run ] ||
      return 1
    launcher=(xvfb-run -a "$blender")
  done
}

for s in "${scenes[@]}"; do
  name=$(basename "$s"); name=${name%%.*}
  echo "== 1. view $name" >&2
  "$so" view "$s" --out "$out/view/$name" --width "$width" --height "$height" --quiet ||
    { echo "sweep.sh: error: shadow-oracle view failed on $s" >&2; exit 1; }
  for cube in "${cubes[@]}"; do
    for soft in 0 1; do
      dir="$out/renders/$name/cube_${cube}_soft_$soft"
      echo "== 2. blender EEVEE: $name, cube $cube, soft shadows $soft" >&2
      flag=off; [ $soft = 1 ] && flag=on
      render "$out/view/$name/view.json" "$dir" --eevee-soft-shadows $flag --eevee-cube-size "$cube" ||
        { echo "sweep.sh: error: the EEVEE render failed ($dir.log)" >&2; exit 1; }
    done
  done
done

echo "== 3. sweep" >&2
python3 - "$out/spec.json" "$width" "$height" "${scenes[@]}" <<'PY'
import json, sys
path, width, height, scenes = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4:]
spec = {
    "sweep_format": 1, "name": "blender-eevee", "scenes": scenes,
    "width": width, "height": height, "frames": 3,
    "techniques": [
        {"name": "slope-bias", "params": {"resolution": [512, 1024, 2048, 4096]}},
        {"name": "pcss", "params": {"resolution": [512, 1024, 2048, 4096]}}],
    "images": [{"name": "eevee", "path": "renders/{scene}/cube_{cube_size}_soft_{soft}/shadows.exr",
                "params": {"cube_size": [512, 1024, 2048, 4096], "soft": [0, 1]}}]}
with open(path, "w") as f:
    json.dump(spec, f, indent=1)
PY
"$so" sweep "$out/spec.json" --out "$out/sweep" --jobs 2 ||
  { echo "sweep.sh: error: the sweep did not finish (see above)" >&2; exit 1; }
echo "sweep.sh: report in $out/sweep/report.html (metrics_wide.csv, metrics.json)" >&2
