#!/usr/bin/env bash
# A short simplify of REFERENCE, then what a Blender user opens of it: `subdfit decode`'s default
# glb, the shipped asset.glb and asset.usdz, each through tests/blender/open_in_blender.py with the
# least PSNR its Cycles renders must reach against the reference's.
#   simplify_and_open.sh SUBDFIT BLENDER_PYTHON OUT REFERENCE MIN_GLB_DB MIN_USD_DB [SIMPLIFY OPTIONS...]
set -euo pipefail
subdfit=$1 python=$2 out=$3 reference=$4 min_glb=$5 min_usd=$6
shift 6
if [ ! -x "$python" ]; then
  echo "$python: no Blender (bpy) environment: run .ci/setup --tests"
  exit 1
fi
rm -rf "$out" && mkdir -p "$out"
"$subdfit" simplify "$reference" "$@" --out "$out/result" >"$out/simplify.log" 2>&1 || { tail -3 "$out/simplify.log"; exit 1; }
"$subdfit" decode "$out/result/asset.subd" --out "$out/decoded.glb" >"$out/decode.log" 2>&1 || { tail -3 "$out/decode.log"; exit 1; }
# Blender's own chatter (importer timings, render progress) goes to the log; the verdicts stay.
status=0
"$python" "$(dirname "$0")/open_in_blender.py" "$reference" --shots "$out/shots" \
  "$out/decoded.glb:$min_glb" "$out/result/asset.glb:$min_glb" "$out/result/asset.usdz:$min_usd" >"$out/blender.log" 2>&1 ||
  status=$?
grep -E "^($out/|Traceback|[A-Za-z]*Error)" "$out/blender.log" || tail -5 "$out/blender.log"
exit $status
