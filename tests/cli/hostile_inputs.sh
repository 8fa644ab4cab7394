#!/usr/bin/env bash
# Hostile inputs end to end: .subd files that state far more than they hold (tests/data/
# hostile-subd), `decode --out` pointed at what it must not replace, and impossible sizes and
# counts on the command line. Each refusal: a non-zero exit (2 for options), one stderr line
# naming the file or option, within seconds, nothing written.
#   hostile_inputs.sh SUBDFIT OUT_DIR DATA_DIR REFERENCE [SUBDFIT_BENCH]
set -u
subdfit=$1 out=$2 data=$3 reference=$4 bench=${5:-}
rm -rf "$out" && mkdir -p "$out/in"
# Copies: a decode that wrote over its input must not damage the repository's files.
cp "$data"/*.subd "$out/in/"
data="$out/in"
source "$(dirname "$0")/expect_refusal.sh"

# .subd bombs: refused, naming the file, nothing written.
for file in plain_2m_quads one_node_at_resolution_64 heights_on_1m_faces zstd_bomb; do
  expect 1 "$file.subd" -- decode "$data/$file.subd" --out "$out/$file.glb"
  [ -e "$out/$file.glb" ] && fail "$file: $out/$file.glb was written"
done
# The 90 000-quad cage decodes, to under a million triangles.
if ! timeout 60 "$subdfit" decode "$data/plain_90k_quads.subd" --out "$out/plain.glb" >/dev/null; then
  fail "plain_90k_quads.subd did not decode"
elif [ "$(stat -c %s "$out/plain.glb")" -gt 100000000 ]; then
  fail "plain_90k_quads.subd decoded to $(stat -c %s "$out/plain.glb") bytes"
fi
expect 1 "plain_90k_quads.subd: 64 segments" -- decode "$data/plain_90k_quads.subd" --tess 64 --out "$out/dense.glb"
expect 2 "--triangles" -- decode "$data/plain_90k_quads.subd" --triangles 0 --out "$out/none.glb"
expect 2 "--triangles" -- decode "$data/plain_90k_quads.subd" --triangles 99999999 --out "$out/none.glb"

# decode --out: only a regular file is replaced.
mkfifo "$out/fifo.glb"
mkdir "$out/folder.glb"
ln -s "$out/plain.glb" "$out/link.glb"
subd="$data/plain_90k_quads.subd"
expect 1 "fifo.glb: is not a regular file" -- decode "$subd" --out "$out/fifo.glb"
expect 1 "folder.glb: is a folder" -- decode "$subd" --out "$out/folder.glb"
expect 1 "link.glb: is a symlink" -- decode "$subd" --out "$out/link.glb"
expect 1 "is the input" -- decode "$subd" --out "$subd"
expect x "empty" -- decode "$subd" --out ""
[ -p "$out/fifo.glb" ] || fail "the FIFO was replaced"
[ -L "$out/link.glb" ] || fail "the symlink was replaced"

# Sizes and counts: strtod's extras refused; range and parse errors both exit 2.
for budget in 0x100 1e3 -5 " 200" 50 2TB; do
  expect 2 "--budget" -- simplify "$reference" --budget "$budget" --out "$out/budget"
done
for faces in 0 -1 3 2000000 abc; do
  expect 2 "--faces" -- simplify "$reference" --faces "$faces" --out "$out/faces"
done
[ -e "$out/budget" ] || [ -e "$out/faces" ] && fail "an output folder was created"

# A benchmark's --out: somebody else's non-empty folder only with --force.
if [ -n "$bench" ]; then
  mkdir -p "$out/foreign" && echo "mine" > "$out/foreign/notes.txt"
  err=$(timeout 20 "$bench" step-cost --out "$out/foreign" 2>&1 >/dev/null)
  rc=$?
  [ $rc -ne 0 ] && [ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || fail "step-cost wrote into a foreign folder (exit $rc): $err"
  [ "$(ls "$out/foreign")" = notes.txt ] || fail "step-cost left files in the foreign folder"
fi

if [ $failures -gt 0 ]; then echo "$failures failure(s)"; exit 1; fi
echo "all hostile inputs refused as expected"
