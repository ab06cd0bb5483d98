#!/bin/sh
# tests/python under pytest with PYTHON (Debian's python3); exit 77 (skipped) without pytest.
PYTHON="$1"
DIR="$2"
if ! "$PYTHON" -c "import pytest, numpy" 2>/dev/null; then
  echo "skipped: $PYTHON has no pytest or numpy (apt-get install python3-pytest python3-numpy)"
  exit 77
fi
exec "$PYTHON" -m pytest -q -p no:cacheprovider "$DIR"
