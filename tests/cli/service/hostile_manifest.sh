# A manifest whose references are named to escape --out ("...obj" has the stem "..", "..obj"
# the stem ".") or to collide (x/a, y/a and a_2), or in bytes that are not UTF-8 (a Latin-1
# "café"): every asset is finished in a folder of its own inside --out, nothing outside it is
# touched, and a re-run skips them all.
source "$(dirname "$0")/lib.sh"
mkdir -p assets/x assets/y out
latin1=$(printf 'caf\351.obj')
for name in "...obj" "..obj" "x/a.obj" "y/a.obj" "a_2.obj" "a.obj" "$latin1"; do cp "$ASSET" "assets/$name"; done
printf '...obj\n..obj\nx/a.obj\ny/a.obj\na_2.obj\na.obj\ncaf\351.obj\n' >assets/manifest.txt
echo keep >sentinel_above_out
echo keep >out/sentinel_in_out  # a foreign file: --out needs --force

"$SUBDFIT" batch assets/manifest.txt --out out --force "${QUICK[@]}" 2>log.txt || fail "batch failed: $(cat log.txt)"
[ -f sentinel_above_out ] && [ -f out/sentinel_in_out ] || fail "a file beside or in --out was removed"
finished=$(find out -mindepth 1 -maxdepth 1 -type d ! -name '.subdfit' | wc -l)
[ "$finished" -eq 7 ] || fail "expected 7 asset folders, found $finished: $(ls -a out)"
for dir in out/*/; do
  grep -q '"state": "done"' "$dir/status.json" || fail "$dir is not done"
  grep -q '"xxh3_128"' "$dir/status.json" || fail "$dir records no input identity"
done
grep -q "7 finished, 0 skipped" log.txt || fail "summary: $(tail -1 log.txt)"

"$SUBDFIT" batch assets/manifest.txt --out out "${QUICK[@]}" 2>again.txt || fail "re-run failed: $(cat again.txt)"
grep -q "0 finished, 7 skipped" again.txt || fail "re-run summary: $(tail -1 again.txt)"

# A changed input is not done, even in a folder that says so.
echo "# touched" >>assets/x/a.obj
"$SUBDFIT" batch assets/manifest.txt --out out "${QUICK[@]}" 2>changed.txt || fail "changed run failed"
grep -q "1 finished, 6 skipped" changed.txt || fail "a changed input was skipped: $(tail -1 changed.txt)"
echo "ok"
