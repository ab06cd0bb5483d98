#!/bin/sh
# The installed package used from outside (label "package"): `cmake --install BUILD --prefix P`,
# then this folder configured with CMAKE_PREFIX_PATH=P, built, and run against the installed
# program's oracle of SCENE.
set -eu
BUILD="$1"
SCENE="$2"
WORK="$3"
HERE="$(cd "$(dirname "$0")" && pwd)"
rm -rf "$WORK"
cmake --install "$BUILD" --prefix "$WORK/prefix" >"$WORK.install.log" 2>&1 || {
  cat "$WORK.install.log"
  exit 1
}
# Nothing of the build or source tree may be needed: the headers and config come from P.
cmake -S "$HERE" -B "$WORK/build" -DCMAKE_PREFIX_PATH="$WORK/prefix" -DCMAKE_BUILD_TYPE=Release \
  >"$WORK/configure.log" 2>&1 || {
  cat "$WORK/configure.log"
  exit 1
}
cmake --build "$WORK/build" -j 2 >"$WORK/build.log" 2>&1 || {
  cat "$WORK/build.log"
  exit 1
}
"$WORK/prefix/bin/shadow-oracle" trace "$SCENE" --out "$WORK/trace" --width 96 --height 64 --quiet
"$WORK/build/consumer" "$SCENE" "$WORK/trace/oracle.exr"
