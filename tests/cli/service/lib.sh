# Shared by the service tests: each runs `subdfit` the way a scheduler or a hostile manifest
# would, and fails with a message naming what went wrong.
#   SUBDFIT: the binary; WORK: a scratch folder of the test's own (emptied here); ASSET: a small
#   mesh to simplify; REFERENCE (optional): a mesh to fit it to.
set -euo pipefail
SUBDFIT=$(realpath "$1") WORK=$2 ASSET=$(realpath "$3") REFERENCE=${4:+$(realpath "$4")}
rm -rf "$WORK" && mkdir -p "$WORK" && cd "$WORK"

# Settings that make one simplify take about a second.
QUICK=(--faces 40 --steps 2 --res 32 --views 1 --holdout-views 1 --maps none)

fail() { echo "FAIL: $*" >&2; exit 1; }

# expect_refusal EXPECTED_TEXT COMMAND...: a non-zero exit and one stderr line holding the text.
expect_refusal() {
  local expect=$1; shift
  local rc=0
  "$@" >out.txt 2>err.txt || rc=$?
  [ "$rc" -ne 0 ] || fail "exit 0 for: $*"
  [ "$(wc -l <err.txt)" -eq 1 ] || fail "stderr is not one line for: $*: $(cat err.txt)"
  grep -qF -- "$expect" err.txt || fail "stderr does not say '$expect' for: $*: $(cat err.txt)"
}
