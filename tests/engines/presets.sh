#!/usr/bin/env bash
# ctest engines_presets (label "engines"): each web engine at its `typical` preset agrees with the
# oracle on a closed box and on an alpha-tested grate, each under a sun and a spot.
#   presets.sh CLI_PATH SCENES_DIR WORK_DIR
# The two scenes are written into WORK_DIR (64 x 48, beside a link to SCENES_DIR/meshes): the box
# is contact_box's (a closed 2 x 1.5 x 2 box on the floor), the grate alpha_grate's (a tilted,
# double-sided, alpha-tested panel over the floor); both have the same sun and spot. Per engine and
# scene, examples/web/render --preset typical; per scene, one shadow-oracle compare --image over
# all engines; grade_presets.mjs on the two metrics.json. This is the check that catches a page
# that draws a cutout opaque into the map, lights a double-sided back face as shadow, or clips a
# local light's casters: each of those takes an engine below 95% here.
# Galacean shadows only its directional sun: it renders sun-only copies of the two scenes
# (box_sun, grate_sun), and its render of the box with the spot must be refused (exit 1, a line
# naming the spot) rather than an unshadowed image.
# Exit 0: passed; 1: failed; 77: skipped (no chromium, node or examples/web/node_modules), the
# reason on one line of stdout.
set -uo pipefail

skip() { echo "SKIP engines_presets: $*"; exit 77; }
fail() { echo "FAIL engines_presets: $*"; exit 1; }

[ $# -eq 3 ] || { echo "usage: $0 CLI_PATH SCENES_DIR WORK_DIR" >&2; exit 2; }
CLI=$1 SCENES=$(cd "$2" && pwd) WORK=$3
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
WEB=$(cd "$HERE/../../examples/web" && pwd)
ENGINES=(three babylon playcanvas filament three-webgpu babylon-webgpu)

source "$HERE/../lib/browser_checks.sh"
find_chromium
for m in puppeteer-core three @babylonjs/core playcanvas filament @galacean/engine; do
  [ -d "$WEB/node_modules/$m" ] || skip "examples/web/node_modules/$m is missing (npm ci --prefix examples/web)"
done
[ -x "$CLI" ] || fail "no CLI at $CLI (build the shadow-oracle target)"
for s in contact_box alpha_grate; do [ -f "$SCENES/$s.scene.json" ] || fail "no $SCENES/$s.scene.json"; done
"$CLI" --help 2>/dev/null | grep -Eq '^[[:space:]]+export([[:space:]]|$)' || skip "$CLI has no export command"

rm -rf "$WORK" && mkdir -p "$WORK" || fail "cannot create $WORK"
ln -s "$SCENES/meshes" "$WORK/meshes" || fail "cannot link $WORK/meshes"
# The geometry and camera of contact_box and alpha_grate, their lights replaced by one sun and one
# spot (35 degrees, from above and to the side: its shadow falls on the floor in view).
node -e '
  const fs = require("fs");
  const [scenes, work] = process.argv.slice(1);
  const lights = [
    { name: "sun", type: "directional", direction: [0.35, -1.0, -0.45] },
    { name: "spot", type: "spot", position: [1.5, 6.0, 2.0], direction: [-0.25, -1.0, -0.33], outer_cone_deg: 35, inner_cone_deg: 28 },
  ];
  for (const [from, to, effects] of [["contact_box", "box", ["hard"]], ["alpha_grate", "grate", ["hard", "alpha"]]]) {
    const s = JSON.parse(fs.readFileSync(`${scenes}/${from}.scene.json`, "utf8"));
    Object.assign(s.camera, { width: 64, height: 48 });
    Object.assign(s, { lights, effects });
    fs.writeFileSync(`${work}/${to}.scene.json`, JSON.stringify(s, null, 1));
    fs.writeFileSync(`${work}/${to}_sun.scene.json`, JSON.stringify({ ...s, lights: [lights[0]] }, null, 1));
  }
' "$SCENES" "$WORK" || fail "cannot write the scenes"

start=$SECONDS
# render_compare SCENE ENGINE...: each engine's typical render of WORK/SCENE.scene.json, one compare over them.
render_compare() {
  local scene=$1 engine images=()
  shift
  "$CLI" export "$WORK/$scene.scene.json" --out "$WORK/export_$scene" > /dev/null || fail "shadow-oracle export $scene exited $?"
  for engine in "$@"; do
    echo "== render $engine --preset typical on $scene"
    "$WEB/render" "$WORK/$scene.scene.json" --engine "$engine" --preset typical --export-dir "$WORK/export_$scene" \
      --chromium "$chromium" --quiet --out "$WORK/renders_$scene" || fail "render $engine on $scene exited $?"
    images+=(--image "$engine=$WORK/renders_$scene/$engine-typical.exr")
  done
  # A reference with no shadow at all (V = 1 for every light): its false-lit rate is the share of
  # the counted pixels the oracle shadows, against which grade_presets.mjs checks that each
  # engine drew its shadow (a missing shadow can agree on 95% where the shadow is small).
  node --input-type=module -e '
    import fs from "node:fs";
    import { encodeExr } from "'"$WEB"'/lib/exr.mjs";
    const [sceneFile, out] = process.argv.slice(1);
    const s = JSON.parse(fs.readFileSync(sceneFile, "utf8"));
    const n = s.camera.width * s.camera.height;
    const channels = Object.fromEntries(s.lights.map((l) => [`${l.name}.V`, new Float32Array(n).fill(1)]));
    fs.writeFileSync(out, encodeExr(s.camera.width, s.camera.height, channels));
  ' "$WORK/$scene.scene.json" "$WORK/unshadowed_$scene.exr" || fail "cannot write the unshadowed image of $scene"
  images+=(--image "unshadowed=$WORK/unshadowed_$scene.exr")
  "$CLI" compare "$WORK/$scene.scene.json" "${images[@]}" --out "$WORK/report_$scene" > "$WORK/compare_$scene.log" 2>&1 ||
    { cat "$WORK/compare_$scene.log"; fail "shadow-oracle compare on $scene exited $?"; }
}
for scene in box grate; do render_compare "$scene" "${ENGINES[@]}"; done
for scene in box_sun grate_sun; do render_compare "$scene" galacean; done
echo "== render galacean --preset typical on box (a spot: refused)"
refusal=$("$WEB/render" "$WORK/box.scene.json" --engine galacean --preset typical --export-dir "$WORK/export_box" \
  --chromium "$chromium" --quiet --out "$WORK/renders_box" 2>&1)
rc=$?
{ [ $rc -eq 1 ] && grep -q 'light "spot"' <<< "$refusal" && [ ! -e "$WORK/renders_box/galacean-typical.exr" ]; } ||
  fail "galacean on a scene with a spot: expected exit 1, no image and a line naming the spot; got exit $rc: $refusal"
echo "ok   galacean refuses the spot: ${refusal#render: }"
node "$HERE/grade_presets.mjs" "$WORK/report_box/metrics.json" "$WORK/report_grate/metrics.json" \
  "$WORK/report_box_sun/metrics.json" "$WORK/report_grate_sun/metrics.json" ||
  fail "an engine at its typical preset disagrees with the oracle (above)"
echo "engines_presets: passed in $((SECONDS - start)) s (reports in $WORK/report_*)"
