#!/usr/bin/env bash
# Grade Blender's shadows against the oracle, end to end (docs/external.md, "Blender: EEVEE and
# Cycles end to end"):
#   1. shadow-oracle view SCENE --out OUT/view            (view.json: camera, lights, geometry)
#   2. blender: render_shadows.py on OUT/view/view.json    (OUT/<label>/shadows.exr + .json)
#        cycles      Cycles, the reference settings, --cycles-samples spp
#        eevee-soft  EEVEE, soft shadows on
#        eevee-hard  EEVEE, soft shadows off
#   3. shadow-oracle compare SCENE --image LABEL=OUT/<label>/shadows.exr ... --out OUT/report
#
#   grade.sh SCENE OUT [--width W] [--height H] [--cycles-samples N] [--eevee-samples N]
#            [--eevee-cube-size S] [--eevee-cascade-size S] [--threads T] [--no-eevee]
#
# Environment: SHADOW_ORACLE (default: shadow-oracle on PATH), BLENDER (default: blender).
# EEVEE needs OpenGL: Blender falls back to surfaceless EGL with -b; where that fails the EEVEE
# render is retried under `xvfb-run -a`, and where that fails too EEVEE is left out with a line
# on stderr ("EEVEE: ...") and Cycles alone is graded. Exit: 0 graded, 1 a step failed, 2 bad input.
set -uo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
so=${SHADOW_ORACLE:-shadow-oracle}
blender=${BLENDER:-blender}

usage() { echo "usage: $0 SCENE OUT [--width W] [--height H] [--cycles-samples N] [--eevee-samples N] [--eevee-cube-size S] [--eevee-cascade-size S] [--threads T] [--no-eevee]" >&2; exit 2; }
[ $# -ge 2 ] || usage
scene=$1 out=$2
shift 2
width="" height="" cycles_spp=64 eevee_spp=16 cube=512 cascade=1024 threads=2 eevee=1
while [ $# -gt 0 ]; do
  case $1 in
    --width) width=${2:?}; shift 2 ;;
    --height) height=${2:?}; shift 2 ;;
    --cycles-samples) cycles_spp=${2:?}; shift 2 ;;
    --eevee-samples) eevee_spp=${2:?}; shift 2 ;;
    --eevee-cube-size) cube=${2:?}; shift 2 ;;
    --eevee-cascade-size) cascade=${2:?}; shift 2 ;;
    --threads) threads=${2:?}; shift 2 ;;
    --no-eevee) eevee=0; shift ;;
    *) usage ;;
  esac
done
[ -f "$scene" ] || { echo "grade.sh: error: no scene file $scene" >&2; exit 2; }
command -v "$so" >/dev/null || { echo "grade.sh: error: no shadow-oracle ($so); set SHADOW_ORACLE" >&2; exit 2; }
command -v "$blender" >/dev/null || { echo "grade.sh: error: no blender ($blender); set BLENDER" >&2; exit 2; }

size=()
[ -n "$width" ] && size+=(--width "$width")
[ -n "$height" ] && size+=(--height "$height")
mkdir -p "$out" || exit 1

echo "== 1. view" >&2
"$so" view "$scene" --out "$out/view" "${size[@]}" || { echo "grade.sh: error: shadow-oracle view failed" >&2; exit 1; }

# render LABEL SCRIPT_ARGS...: one render_shadows.py run into OUT/LABEL, Blender started by the
# words in the array `launcher`; its log in OUT/LABEL.log.
launcher=("$blender")
render() {
  local label=$1
  shift
  rm -rf "${out:?}/$label"
  "${launcher[@]}" -b --factory-startup --python-exit-code 1 -P "$here/render_shadows.py" -- \
    "$out/view/view.json" --out "$out/$label" --threads "$threads" "$@" > "$out/$label.log" 2>&1 &&
    [ -f "$out/$label/shadows.exr" ]
}

echo "== 2. blender: cycles ($cycles_spp spp)" >&2
render cycles --engine cycles --samples "$cycles_spp" ||
  { grep -m1 'render_shadows.py: error' "$out/cycles.log" >&2; echo "grade.sh: error: the Cycles render failed ($out/cycles.log)" >&2; exit 1; }
images=(--image "cycles=$out/cycles/shadows.exr")

if [ "$eevee" = 1 ]; then
  for soft in on off; do
    label=eevee-soft
    [ $soft = off ] && label=eevee-hard
    echo "== 2. blender: $label ($eevee_spp samples, cube $cube, cascade $cascade)" >&2
    eargs=(--engine eevee --samples "$eevee_spp" --eevee-soft-shadows $soft
           --eevee-cube-size "$cube" --eevee-cascade-size "$cascade")
    if render $label "${eargs[@]}"; then
      images+=(--image "$label=$out/$label/shadows.exr")
    elif command -v xvfb-run >/dev/null && launcher=(xvfb-run -a "$blender") && render $label "${eargs[@]}"; then
      echo "   (under xvfb-run: no surfaceless EGL)" >&2
      images+=(--image "$label=$out/$label/shadows.exr")
    else
      echo "EEVEE: cannot render here (no OpenGL 3.3 context through EGL or xvfb-run; $out/$label.log); grading Cycles alone" >&2
      break
    fi
  done
fi

echo "== 3. compare" >&2
"$so" compare "$scene" "${size[@]}" "${images[@]}" --out "$out/report" ||
  { echo "grade.sh: error: shadow-oracle compare failed" >&2; exit 1; }
echo "grade.sh: report in $out/report (report.html, metrics.json, metrics_wide.csv)" >&2
