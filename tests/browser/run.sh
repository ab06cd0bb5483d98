#!/usr/bin/env bash
# ctest browser_reports (label "browser"): headless Chromium over the HTML pages of the CLI.
#   run.sh CLI_PATH SCENES_DIR WORK_DIR
# 1. report_test.mjs on tests/browser/fixture.html: a failure here is the harness's or the
#    browser's, told apart from a broken report;
# 2. `compare` on soft_chair and contact_box into WORK_DIR, and `index` over both where the CLI
#    has that command;
# 3. report_test.mjs on the two report.html files and index.html; screenshots in WORK_DIR/screenshots.
# Exit 0: passed; 1: failed; 77: skipped (no chromium, no node or puppeteer-core, no OpenGL), the
# reason on one line of stdout.
set -uo pipefail

skip() { echo "SKIP browser_reports: $*"; exit 77; }
fail() { echo "FAIL browser_reports: $*"; exit 1; }

[ $# -eq 3 ] || { echo "usage: $0 CLI_PATH SCENES_DIR WORK_DIR" >&2; exit 2; }
CLI=$1 SCENES=$2 WORK=$3
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)

source "$HERE/../lib/browser_checks.sh"
find_chromium
[ -d "$HERE/node_modules/puppeteer-core" ] ||
  skip "tests/browser/node_modules/puppeteer-core is missing (npm ci --prefix tests/browser)"
[ -x "$CLI" ] || fail "no CLI at $CLI (build the shadow-oracle target)"
[ -d "$SCENES" ] || fail "no scenes folder at $SCENES"

mkdir -p "$WORK" || fail "cannot create $WORK"
shots="$WORK/screenshots"
rm -rf "$shots" "$WORK/index.html"

echo "== the harness on tests/browser/fixture.html"
node "$HERE/report_test.mjs" --browser "$chromium" --screenshots "$shots" "$HERE/fixture.html" ||
  fail "the harness fails on tests/browser/fixture.html: report_test.mjs or chromium is broken, not a report"

scenes=(soft_chair contact_box)
reports=()
for s in "${scenes[@]}"; do
  echo "== compare $s"
  rm -rf "${WORK:?}/$s"
  # soft_chair's window (a rect light) gets the exact penumbra pass: its chart shows its point.
  exact=()
  [ "$s" = soft_chair ] && exact=(--penumbra exact)
  "$CLI" compare "$SCENES/$s.scene.json" --width 240 --height 180 --frames 2 --out "$WORK/$s" "${exact[@]}" \
    --technique slope-bias --technique slope-bias:resolution=512 --technique pcss --technique vsm \
    --technique evsm:blur=8 \
    2> "$WORK/$s.stderr"
  rc=$?
  cat "$WORK/$s.stderr" >&2
  if [ $rc -ne 0 ]; then
    # main.cpp reports a GlUnavailable as "error: no OpenGL: ..." with exit 1; where no EGL
    # implementation is installed at all, libepoxy aborts instead ("No provider of egl... found").
    nogl=$(grep -m1 -E '^error: no OpenGL|^No provider of egl[A-Za-z]* found' "$WORK/$s.stderr")
    if [ -n "$nogl" ]; then
      nogl=${nogl#error: }
      skip "no EGL/OpenGL display to render the reports with (${nogl%%  Requires*})"
    fi
    fail "shadow-oracle compare $s exited $rc"
  fi
  [ -f "$WORK/$s/report.html" ] || fail "compare $s wrote no $WORK/$s/report.html"
  reports+=("$WORK/$s/report.html")
done

index_args=()
# `index --help` on a CLI without the command prints the main help and exits 0 (CLI11), so the
# command is looked for in the main help's list of subcommands.
if "$CLI" --help 2>/dev/null | grep -Eq '^[[:space:]]+index([[:space:]]|$)' && "$CLI" index --help >/dev/null 2>&1; then
  echo "== index"
  dirs=()
  for s in "${scenes[@]}"; do dirs+=("$WORK/$s"); done
  "$CLI" index "${dirs[@]}" --out "$WORK/index.html" || fail "shadow-oracle index exited $?"
  [ -f "$WORK/index.html" ] || fail "index wrote no $WORK/index.html"
  index_args=(--index "$WORK/index.html")
else
  echo "NOTE browser_reports: $CLI has no index command: index.html is not checked"
fi

echo "== the harness on the reports"
node "$HERE/report_test.mjs" --browser "$chromium" --screenshots "$shots" "${index_args[@]}" "${reports[@]}" ||
  fail "the reports fail (screenshots in $shots)"
echo "browser_reports: passed (screenshots in $shots)"
