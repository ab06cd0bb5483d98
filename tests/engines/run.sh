#!/usr/bin/env bash
# ctest engines_three (label "engines"): three.js's shadows in headless Chromium, graded.
#   run.sh CLI_PATH SCENES_DIR WORK_DIR
# The scene is terrain_sun (a directional sun over a heightfield) with the `contact` effect added,
# so that compare can tell peter-panning (it needs the oracle's occluder distances); it is written
# into WORK_DIR beside a link to SCENES_DIR/meshes. At 96 x 72:
#   1. examples/web/render --engine three at its defaults (render runs `export` itself);
#   2. bias=-0.01 (three.js adds `bias` to the receiver's map depth: negative is toward lit);
#   3. shadowSide=front with bias 0, and with bias=-0.0005 (three.js draws back faces into the map
#      by default, which hides acne on closed and back-faced surfaces: the front faces show it);
#   4. a bad mode: one line, exit 1, no EXR;
#   5. Babylon.js at its defaults, with bias=0.005 and with bias=0.05; PlayCanvas and Filament at
#      their defaults (pages/babylon.js, playcanvas.js, filament.js);
#   6. shadow-oracle compare --image on all nine, grade.mjs on its metrics.json.
# Exit 0: passed; 1: failed; 77: skipped (no chromium, node or examples/web/node_modules), the
# reason on one line of stdout.
set -uo pipefail

skip() { echo "SKIP engines_three: $*"; exit 77; }
fail() { echo "FAIL engines_three: $*"; exit 1; }

[ $# -eq 3 ] || { echo "usage: $0 CLI_PATH SCENES_DIR WORK_DIR" >&2; exit 2; }
CLI=$1 SCENES=$2 WORK=$3
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
WEB=$(cd "$HERE/../../examples/web" && pwd)

source "$HERE/../lib/browser_checks.sh"
find_chromium
for m in puppeteer-core three @babylonjs/core playcanvas filament; do
  [ -d "$WEB/node_modules/$m" ] || skip "examples/web/node_modules/$m is missing (npm ci --prefix examples/web)"
done
[ -x "$CLI" ] || fail "no CLI at $CLI (build the shadow-oracle target)"
[ -f "$SCENES/terrain_sun.scene.json" ] || fail "no $SCENES/terrain_sun.scene.json"
# CLI11 lists the subcommands in the main help; a CLI built before `export` existed cannot run this.
"$CLI" --help 2>/dev/null | grep -Eq '^[[:space:]]+export([[:space:]]|$)' ||
  skip "$CLI has no export command"

rm -rf "$WORK" && mkdir -p "$WORK/renders" || fail "cannot create $WORK"
ln -s "$SCENES/meshes" "$WORK/meshes" || fail "cannot link $WORK/meshes"
scene="$WORK/terrain_sun_contact.scene.json"
node -e '
  const fs = require("fs");
  const s = JSON.parse(fs.readFileSync(process.argv[1], "utf8"));
  s.effects = ["hard", "contact"];
  fs.writeFileSync(process.argv[2], JSON.stringify(s, null, 1));
' "$SCENES/terrain_sun.scene.json" "$scene" || fail "cannot write $scene"
size=(--width 96 --height 72)
render() { # OUT_NAME [render options...]
  local name=$1; shift
  echo "== render $name: $*"
  "$WEB/render" "$scene" --engine three "${size[@]}" --tool "$CLI" --chromium "$chromium" --quiet "$@" \
    --out "$WORK/renders/$name" || fail "render $name exited $?"
}

start=$SECONDS
render default
"$CLI" export "$scene" --out "$WORK/export" "${size[@]}" > /dev/null || fail "shadow-oracle export exited $?"
ex=(--export-dir "$WORK/export")
render bias_large "${ex[@]}" --set bias=-0.01
render front_bias0 "${ex[@]}" --set shadowSide=front
render front_bias_small "${ex[@]}" --set shadowSide=front --set bias=-0.0005

echo "== render a bad mode"
"$WEB/render" "$scene" --engine three --mode nosuch "${size[@]}" "${ex[@]}" --chromium "$chromium" \
  --out "$WORK/renders/bad" 2> "$WORK/bad.stderr"
rc=$?
[ $rc -eq 1 ] || fail "a bad mode exited $rc, expected 1"
[ "$(wc -l < "$WORK/bad.stderr")" -eq 1 ] || fail "a bad mode printed $(wc -l < "$WORK/bad.stderr") lines: $(cat "$WORK/bad.stderr")"
grep -q "^render: three nosuch $scene: unknown mode \"nosuch\"" "$WORK/bad.stderr" || fail "a bad mode said: $(cat "$WORK/bad.stderr")"
[ -z "$(ls -A "$WORK/renders/bad")" ] || fail "a bad mode left files: $(ls "$WORK/renders/bad")"
echo "   $(cat "$WORK/bad.stderr")"

others=() # NAME=ENGINE
render_other() { # NAME ENGINE [render options...]
  local name=$1 engine=$2; shift 2
  echo "== render $name: $engine $*"
  "$WEB/render" "$scene" --engine "$engine" "${size[@]}" "${ex[@]}" --chromium "$chromium" --quiet "$@" \
    --out "$WORK/renders/$name" || fail "render $name exited $?"
  others+=("$name=$engine")
}
render_other babylon_default babylon
render_other babylon_bias_mid babylon --set bias=0.005
render_other babylon_bias_large babylon --set bias=0.05
render_other playcanvas_default playcanvas
render_other filament_default filament

echo "== compare --image"
images=()
for n in default bias_large front_bias0 front_bias_small; do
  images+=(--image "$n=$WORK/renders/$n/three-default.exr")
done
for o in "${others[@]}"; do
  images+=(--image "${o%%=*}=$WORK/renders/${o%%=*}/${o#*=}-default.exr")
done
"$CLI" compare "$scene" "${size[@]}" "${images[@]}" --out "$WORK/report" > "$WORK/compare.log" 2>&1 ||
  { cat "$WORK/compare.log"; fail "shadow-oracle compare exited $?"; }
node "$HERE/grade.mjs" "$WORK/report/metrics.json" || fail "the grades are not what the engines' settings cause (above)"
echo "engines_three: passed in $((SECONDS - start)) s (report in $WORK/report)"
