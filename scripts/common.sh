# Shared by scripts/demo and scripts/test: install what is missing, configure, build.
# Sourced, not run.
set -euo pipefail

SO_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
SO_JOBS="${SO_JOBS:-$(nproc 2>/dev/null || echo 2)}"

# Debian 12 packages the build needs. Checked one by one so a second run installs nothing.
SO_PACKAGES=(
  cmake g++ make git
  libembree-dev libglm-dev libopenexr-dev libtbb-dev nlohmann-json3-dev
  libtinygltf-dev libcli11-dev libxxhash-dev libgmp-dev libpolyclipping-dev libopenimageio-dev pkg-config
  libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri libepoxy-dev
  googletest libgtest-dev
  clang-format
  python3-dev pybind11-dev python3-numpy
  libdraco-dev libmeshoptimizer-dev libwebp-dev zlib1g-dev
)

# Only the tests need these: libcgal-demo ships the Stanford bunny (in its data.tar.gz) that the
# oracle is re-traced on; chromium, nodejs and npm run the browser test of the HTML reports
# (tests/browser, ctest label "browser"); pytest and matplotlib run the Python module's tests and
# docs/python.md's example (label "python").
SO_TEST_PACKAGES=(libcgal-demo chromium nodejs npm python3-pytest python3-matplotlib)
# Blender grades its own shadows against the oracle in the external-renderer test (ctest label
# "external", examples/blender/, docs/external.md): its glTF importer needs numpy, which Debian's
# blender does not pull in; xvfb and xauth are EEVEE's fallback display. Installed apart, like the
# fuzz packages, so that test skips, saying why, where they cannot be installed.
SO_EXTERNAL_PACKAGES=(blender python3-numpy xvfb xauth)
# clang with libFuzzer builds the fuzz harnesses (scripts/fuzz, docs/fuzzing.md). Installed apart
# from SO_TEST_PACKAGES so that scripts/test skips fuzzing, rather than failing, where they cannot
# be installed.
SO_FUZZ_PACKAGES=(clang libfuzzer-14-dev)

# Packages that also count as present when their command is on PATH: NodeSource's nodejs ships npm
# and conflicts with Debian's npm package, so installing that would fail.
declare -gA SO_PACKAGE_COMMANDS=([nodejs]=node [npm]=npm [chromium]=chromium)

# so_install_packages [extra packages...]
so_install_packages() {
  local missing=()
  for p in "${SO_PACKAGES[@]}" "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" && continue
    local cmd="${SO_PACKAGE_COMMANDS[$p]:-}"
    [ -n "$cmd" ] && command -v "$cmd" >/dev/null && continue
    missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "Installing missing Debian packages: ${missing[*]}"
  local sudo=()
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "error: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
    sudo=(sudo)
  fi
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -qq
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

# so_build DIR [cmake -D options...] -- [targets...]
so_build() {
  local dir="$1"; shift
  local opts=() targets=()
  while [ $# -gt 0 ] && [ "$1" != "--" ]; do opts+=("$1"); shift; done
  [ $# -gt 0 ] && shift
  targets=("$@")
  # Warnings are errors in CI builds; a user's newer compiler should not break the demo. Set only
  # when the folder is first configured, so demo and test never flip it and rebuild everything.
  if [ ! -f "$dir/CMakeCache.txt" ]; then
    local werror=OFF
    [ "${CI:-}" = "true" ] && werror=ON
    cmake -S "$SO_ROOT" -B "$dir" -DCMAKE_BUILD_TYPE=Release -DSHADOW_ORACLE_WERROR="$werror" "${opts[@]}" >/dev/null
  fi
  if [ ${#targets[@]} -gt 0 ]; then
    cmake --build "$dir" -j "$SO_JOBS" --target "${targets[@]}"
  else
    cmake --build "$dir" -j "$SO_JOBS"
  fi
}
