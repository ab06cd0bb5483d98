// tests/engines/run.sh's checks on compare's metrics.json (docs/metrics.md), with the figures.
//   node grade.mjs METRICS_JSON
// Thresholds, from what three.js 0.187.0 gives on terrain_sun + contact at 96 x 72 (2,600 counted
// pixels; measured: defaults agree on 97.2%, peter-panning 0.139; bias=-0.01 peter-panning 0.556;
// shadowSide=front acne 0.463 at bias 0 and 0.041 at bias=-0.0005):
// - defaults agree with the oracle on at least 95% of counted pixels, not all: three.js draws the
//   back faces into the map, which lifts shadows off their contacts (peter-panning), and a 512
//   map over 32 m of terrain under a low sun misses thin shadow features (aliasing);
// - a large negative bias is peter-panning: at least 0.3 of the contact shadows, twice the default's;
// - bias 0 on front faces is acne (at least 0.2 of the lit pixels), a small bias removes most of it
//   (under half), and the default (back faces) has next to none (at most 0.01).
import fs from 'node:fs';

const metrics = JSON.parse(fs.readFileSync(process.argv[2], 'utf8'));
const rows = Object.fromEntries(metrics.results.map((r) => [r.label, r.lights.sun]));
let failed = 0;
function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failed += 1;
}
for (const [label, m] of Object.entries(rows)) {
  console.log(`   ${label}: mae ${m.mae.toFixed(4)}, agree ${(1 - m.false_lit_rate - m.false_shadow_rate).toFixed(4)}, ` +
    `acne ${m.acne_rate.toFixed(3)}, peter-panning ${m.peter_panning_rate.toFixed(3)}, aliasing ${m.aliasing_rate.toFixed(3)}`);
}
const d = rows.default;
const agree = 1 - d.false_lit_rate - d.false_shadow_rate;
check(d.counted_pixels > 1000, `defaults: ${d.counted_pixels} counted pixels (> 1000)`);
check(agree >= 0.95, `defaults: ${(100 * agree).toFixed(1)}% of counted pixels agree with the oracle (>= 95%)`);
check(d.acne_rate <= 0.01, `defaults: acne ${d.acne_rate.toFixed(3)} (<= 0.01: back faces in the map)`);
const pp = rows.bias_large.peter_panning_rate;
check(pp >= 0.3 && pp >= 2 * d.peter_panning_rate,
  `bias=-0.01: peter-panning ${pp.toFixed(3)} (>= 0.3 and >= 2 x the default's ${d.peter_panning_rate.toFixed(3)})`);
const acne0 = rows.front_bias0.acne_rate;
const acneSmall = rows.front_bias_small.acne_rate;
check(acne0 >= 0.2, `shadowSide=front, bias 0: acne ${acne0.toFixed(3)} (>= 0.2)`);
check(acneSmall < acne0 / 2, `shadowSide=front, bias=-0.0005: acne ${acneSmall.toFixed(3)} (< half of bias 0's)`);

// The other engines (pages/babylon.js, playcanvas.js, filament.js), measured on the same scene
// (2,600 counted pixels): Babylon.js's defaults acne 0.442; bias=0.005 agrees on 96.7%, peter-
// panning 0.045; bias=0.05 peter-panning 0.302; PlayCanvas's defaults agree on 96.2%, Filament's
// on 95.6%. Not all: the biases that remove acne lift shadows off their contacts (peter-panning)
// and a 1024 map over 32 m of terrain under a low sun misses thin shadow features (aliasing).
const rate = (m) => 1 - m.false_lit_rate - m.false_shadow_rate;
const b0 = rows.babylon_default;
const bMid = rows.babylon_bias_mid;
const bLarge = rows.babylon_bias_large;
check(b0.acne_rate >= 0.2, `babylon defaults: acne ${b0.acne_rate.toFixed(3)} (>= 0.2: its bias 0.00005 is far under a texel's depth step)`);
check(rate(bMid) >= 0.94, `babylon bias=0.005: ${(100 * rate(bMid)).toFixed(1)}% agree (>= 94%)`);
check(bMid.acne_rate <= 0.01, `babylon bias=0.005: acne ${bMid.acne_rate.toFixed(3)} (<= 0.01)`);
check(bLarge.peter_panning_rate >= 0.2 && bLarge.peter_panning_rate >= 2 * bMid.peter_panning_rate,
  `babylon bias=0.05: peter-panning ${bLarge.peter_panning_rate.toFixed(3)} (>= 0.2 and >= 2 x bias=0.005's ${bMid.peter_panning_rate.toFixed(3)})`);
for (const name of ['playcanvas_default', 'filament_default']) {
  check(rate(rows[name]) >= 0.94, `${name}: ${(100 * rate(rows[name])).toFixed(1)}% agree (>= 94%)`);
}
process.exit(failed ? 1 : 0);
