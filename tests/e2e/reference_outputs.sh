#!/usr/bin/env bash
# reference_outputs.sh BUILD OUT: every output a behaviour-preserving change must leave byte-identical --
# ipd table (text, json, latex --ci, csv --no-cache), ipd compare, ipd export rocks and the seven ipd figure
# kinds as svg/pdf/png -- on the built-in demo and on a 1,000-scene labels-only study. Compare two builds with
#   tests/e2e/reference_outputs.sh build-before /tmp/a && tests/e2e/reference_outputs.sh build /tmp/b && diff -r /tmp/a /tmp/b
set -u
B=$(realpath "$1")/app/ipd; FINAL=$2
# One working folder for every run: paths printed in the logs must not differ between two builds.
O=${TMPDIR:-/tmp}/ipd-reference-outputs; rm -rf "$O" "$FINAL"; mkdir -p "$O"
export SOURCE_DATE_EPOCH=1700000000 XDG_CACHE_HOME=$O/xdg
$B demo "$O/demo" >/dev/null
$B demo "$O/big" --labels-only --scenes 1000 >/dev/null
for S in demo big; do
  st=$O/$S
  $B table "$st" > "$O/$S.table.txt" 2>&1; echo "rc $?" >> "$O/$S.table.txt"
  $B table "$st" --format json > "$O/$S.table.json" 2>&1
  $B table "$st" --format latex --ci > "$O/$S.table.tex" 2>&1
  $B table "$st" --no-cache --format csv > "$O/$S.table.csv" 2>&1
  $B compare "$st" > "$O/$S.compare.txt" 2>&1; echo "rc $?" >> "$O/$S.compare.txt"
  $B export rocks "$st" --out "$O/$S.rocks.csv" > "$O/$S.export.log" 2>&1
  for f in pairs registration table compare distribution breakdown gallery; do
    for ext in svg pdf png; do
      $B figure $f "$st" --out "$O/$S.fig-$f.$ext" > "$O/$S.fig-$f.$ext.log" 2>&1; echo "rc $?" >> "$O/$S.fig-$f.$ext.log"
    done
  done
done
rm -rf "$O/xdg" "$O/demo" "$O/big"
# cairo stamps PDFs with the time: that line is left out of the comparison.
for p in "$O"/*.pdf; do sed -i "/CreationDate/d" "$p"; done
mv "$O" "$FINAL"
