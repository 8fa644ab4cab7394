#!/usr/bin/env bash
# `subdfit decode` for engines on a simplify result: by default about the reference's triangles
# (within 2x), `--lods 3` three files whose distances to level 0 rise as their triangles fall
# (with the JSON's counts and bytes true to the files), `--max-error` within its bound, `--bytes`
# a prefix from the cage's end on (and one ending inside the cage refused); bad options refused
# with exit 2 in one line naming the option, nothing written.
#   decode_for_engines.sh SUBDFIT OUT_DIR RESULT_DIR REFERENCE.obj
set -u
subdfit=$1 out=$2 result=$3 reference=$4
rm -rf "$out" && mkdir -p "$out"
source "$(dirname "$0")/expect_refusal.sh"
subd="$result/asset.subd"
reference_triangles=$(grep -c '^f ' "$reference")

if ! "$subdfit" decode "$subd" --out "$out/lod.glb" --lods 3 >/dev/null; then
  fail "decode --lods 3 failed"
else
  python3 - "$out" "$reference_triangles" <<'PY' || fail "the levels of detail"
import json, os, sys
out, reference = sys.argv[1], int(sys.argv[2])
doc = json.load(open(os.path.join(out, "lod_lods.json")))
lods = doc["lods"]
assert [l["file"] for l in lods] == ["lod.glb", "lod_lod1.glb", "lod_lod2.glb"], lods
assert reference / 2 <= lods[0]["triangles"] <= 2 * reference, (lods[0]["triangles"], reference)
for l in lods:
    assert os.path.getsize(os.path.join(out, l["file"])) == l["bytes"], l
for a, b in zip(lods, lods[1:]):
    assert b["triangles"] < a["triangles"], (a, b)
    assert b["mean_distance"] > a["mean_distance"] and b["max_distance"] > a["max_distance"], (a, b)
    assert b["screen_size"] < a["screen_size"], (a, b)
print("levels:", [(l["triangles"], l["bytes"], round(l["max_distance"], 5)) for l in lods], "reference", reference)
PY
fi

if ! "$subdfit" decode "$subd" --out "$out/bounded.glb" --max-error 0.5% --lods 1 >/dev/null; then
  fail "decode --max-error 0.5% failed"
else
  python3 -c "
import json, sys
e = json.load(open('$out/bounded_lods.json'))['max_error']
assert 0 < e['max_distance'] <= e['bound'], e
" || fail "--max-error: the chosen density is not within its bound"
fi

# A prefix: from the end of the cage (the first section) on it decodes; a byte short it is refused.
cage_end=$(python3 -c "import struct,sys; b=open(sys.argv[1],'rb').read(); print(28 + struct.unpack_from('<I', b, 20)[0])" "$subd")
if ! "$subdfit" decode "$subd" --out "$out/prefix.glb" --bytes "$cage_end" >/dev/null || [ ! -s "$out/prefix.glb" ]; then
  fail "decode --bytes $cage_end (the cage whole) failed"
fi
expect 1 "end before the cage does" -- decode "$subd" --out "$out/refused.glb" --bytes $((cage_end - 1))

for args in "--bytes 0" "--max-error 0" "--max-error abc" "--max-error -1%" "--lods 0" "--lods 9" "--tess 0"; do
  option=${args%% *}
  # shellcheck disable=SC2086
  expect 2 "$option" -- decode "$subd" --out "$out/refused.glb" $args
done
expect 2 "--max-error" -- decode "$subd" --out "$out/refused.glb" --max-error 0.01 --triangles 1000
expect 2 "--tess" -- decode "$subd" --out "$out/refused.glb" --tess 4 --max-error 0.01
[ -e "$out/refused.glb" ] && fail "a refused decode wrote its output"

if [ $failures -gt 0 ]; then echo "$failures failure(s)"; exit 1; fi
echo "decode for engines: as expected"
