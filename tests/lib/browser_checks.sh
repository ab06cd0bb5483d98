# Sourced by the ctest scripts that drive headless Chromium (tests/browser/run.sh,
# tests/engines/run.sh). The caller defines skip MESSAGE (exit 77 with the reason).
# find_chromium: sets `chromium` to $CHROMIUM or the first browser on PATH, and checks node (18 or
# newer, as puppeteer-core needs); skips with the reason otherwise.
find_chromium() {
  chromium=${CHROMIUM:-}
  if [ -z "$chromium" ]; then
    for c in chromium chromium-browser google-chrome; do
      if p=$(command -v "$c"); then chromium=$p; break; fi
    done
  fi
  [ -n "$chromium" ] && [ -x "$chromium" ] ||
    skip "no chromium binary found (apt-get install chromium, or set CHROMIUM=/path)"
  command -v node >/dev/null || skip "no node found (apt-get install nodejs)"
  node -e 'process.exit(+process.versions.node.split(".")[0] >= 18 ? 0 : 1)' ||
    skip "node $(node --version) is too old for puppeteer-core (18 or newer)"
}
