# What a service meets besides manifests: a FIFO or a device as input (refused at once, never
# waited on), SIGTERM while loading (exit 130 promptly, nothing written), a damaged checkpoint
# (refused in one line), --resume with nothing to resume (said, then a fresh start), and --out
# folders that must not be used.
source "$(dirname "$0")/lib.sh"
FIT=(fit --cage "$ASSET" --reference "$REFERENCE" --holdout-views 1)
SMALL=(--res 32 --views 1)

mkfifo pipe.obj
expect_refusal "not a regular file" timeout 20 "$SUBDFIT" simplify pipe.obj --out fifo_out
[ ! -e fifo_out ] || fail "the FIFO run left its output folder"
ln -s /dev/zero zero.obj
expect_refusal "not a regular file" timeout 20 "$SUBDFIT" fit --cage zero.obj --reference "$REFERENCE" --out zero_out

# SIGTERM while the targets render (1024 views take seconds): out at once, nothing written.
"$SUBDFIT" "${FIT[@]}" --views 1024 --res 512 --out term_out 2>term.txt &
pid=$!
sleep 1.5
kill -TERM $pid
start=$(date +%s)
rc=0
wait $pid || rc=$?
[ $rc -eq 130 ] || fail "SIGTERM while loading: exit $rc, expected 130: $(cat term.txt)"
[ $(( $(date +%s) - start )) -le 5 ] || fail "SIGTERM took more than 5 s to stop the run"
[ ! -e term_out ] || fail "SIGTERM while loading left $(ls term_out)"

# A checkpoint with one flipped byte is refused, naming the file; --resume without one says so.
"$SUBDFIT" "${FIT[@]}" "${SMALL[@]}" --steps 3 --out fitted --resume 2>resume.txt >/dev/null || fail "fit failed: $(cat resume.txt)"
grep -q "no checkpoint" resume.txt || fail "--resume without a checkpoint said nothing"
size=$(stat -c %s fitted/checkpoint.bin)
printf '\x55' | dd of=fitted/checkpoint.bin bs=1 seek=$((size / 2)) conv=notrunc status=none
expect_refusal "checkpoint.bin: damaged checkpoint" "$SUBDFIT" "${FIT[@]}" "${SMALL[@]}" --steps 6 --out fitted --resume

# --out: never the root, never a file, not a foreign folder unless forced.
expect_refusal "filesystem root" "$SUBDFIT" "${FIT[@]}" "${SMALL[@]}" --out /
touch plain_file
expect_refusal "not a folder" "$SUBDFIT" "${FIT[@]}" "${SMALL[@]}" --out plain_file
mkdir foreign && touch foreign/thesis.tex
expect_refusal "--force" "$SUBDFIT" "${FIT[@]}" "${SMALL[@]}" --out foreign
"$SUBDFIT" "${FIT[@]}" "${SMALL[@]}" --steps 1 --out foreign --force 2>/dev/null >/dev/null || fail "--force was not honoured"
[ -f foreign/thesis.tex ] || fail "a foreign file was removed"
expect_refusal "not a folder" "$SUBDFIT-bench" step-cost --out plain_file
echo "ok"
