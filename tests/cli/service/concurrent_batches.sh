# Two batches on one --out at once (a scheduler re-launching a task while the first is alive):
# every asset is computed exactly once, both exit 0, and a holder killed with SIGKILL leaves no
# lock behind.
source "$(dirname "$0")/lib.sh"
for k in 1 2 3 4; do cp "$ASSET" "asset$k.obj"; done
printf 'asset1.obj\nasset2.obj\nasset3.obj\nasset4.obj\n' >manifest.txt

"$SUBDFIT" batch manifest.txt --out out "${QUICK[@]}" 2>first.txt &
first=$!
"$SUBDFIT" batch manifest.txt --out out "${QUICK[@]}" 2>second.txt &
second=$!
rc1=0 rc2=0
wait $first || rc1=$?
wait $second || rc2=$?
[ $rc1 -eq 0 ] && [ $rc2 -eq 0 ] || fail "exit codes $rc1 and $rc2: $(cat first.txt second.txt)"
started=$(cat first.txt second.txt | grep -c ": starting" || true)
[ "$started" -eq 4 ] || fail "assets started $started times in all, expected 4: $(cat first.txt second.txt)"
for k in 1 2 3 4; do
  n=$(ls -d out/asset$k-*/ 2>/dev/null | wc -l)
  [ "$n" -eq 1 ] || fail "asset$k has $n finished folders"
done
[ -z "$(ls -d out/*.partial 2>/dev/null)" ] || fail "partial folders left: $(ls out)"

# SIGKILL while an asset is held: its lock dies with the process, and the next run takes the
# asset up again (then SIGTERM stops that one promptly, its status saying interrupted).
# A fit of fixed length (anneal: no schedule that stops a stalled fit), long enough to be held.
printf 'asset1.obj --steps 10000 --res 64 --schedule anneal\n' >slow.txt
"$SUBDFIT" batch slow.txt --out killed "${QUICK[@]}" 2>killed.txt &
victim=$!
for _ in $(seq 200); do grep -q "^step " killed.txt && break; sleep 0.1; done
kill -KILL $victim; wait $victim || true
"$SUBDFIT" batch slow.txt --out killed "${QUICK[@]}" 2>after.txt &
again=$!
for _ in $(seq 200); do grep -qE ": running elsewhere|^step " after.txt && break; sleep 0.1; done
grep -q ": running elsewhere" after.txt && fail "the killed holder's lock outlived it"
kill -TERM $again
rc=0
wait $again || rc=$?
[ $rc -eq 130 ] || fail "SIGTERM during the fit: exit $rc, expected 130: $(tail -3 after.txt)"
grep -q '"state": "interrupted"' killed/*.partial/status.json || fail "status after SIGTERM: $(cat killed/*.partial/status.json)"
[ -f killed/*.partial/checkpoint.bin ] || fail "no checkpoint after SIGTERM"
echo "ok"
