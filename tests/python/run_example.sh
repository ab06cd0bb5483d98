#!/bin/sh
# docs/python.md's example, run so that it cannot rot: PYTHON SCRIPT OUT.png; exit 77 (skipped)
# without matplotlib. Fails unless the script ran and wrote a PNG.
PYTHON="$1"
SCRIPT="$2"
OUT="$3"
if ! "$PYTHON" -c "import matplotlib, numpy" 2>/dev/null; then
  echo "skipped: $PYTHON has no matplotlib (apt-get install python3-matplotlib)"
  exit 77
fi
rm -f "$OUT"
"$PYTHON" "$SCRIPT" --out "$OUT" --width 160 --height 120 --frames 3 || exit 1
head -c 8 "$OUT" | od -An -c | grep -q "P   N   G" || { echo "no PNG at $OUT"; exit 1; }
