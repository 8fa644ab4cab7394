# Sourced by the CLI test scripts: `fail` counts a failure; `expect CODE TEXT -- ARGS...` runs
# "$subdfit" ARGS and wants exit CODE (any non-zero for "x"), one stderr line containing TEXT,
# done within 20 s.
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

expect() {
  local code=$1 text=$2
  shift 3
  local err
  err=$(timeout 20 "$subdfit" "$@" 2>&1 >/dev/null)
  local rc=$?
  if [ $rc -eq 124 ]; then fail "$*: took more than 20 s"; return; fi
  if [ "$code" = x ] && [ $rc -eq 0 ] || [ "$code" != x ] && [ $rc -ne "$code" ]; then fail "$*: exit $rc, expected $code"; fi
  if [ "$(printf '%s\n' "$err" | wc -l)" -ne 1 ]; then fail "$*: stderr is not one line: $err"; fi
  case $err in *"$text"*) ;; *) fail "$*: stderr does not name '$text': $err" ;; esac
}
