#!/usr/bin/env bash
# What the web decoder's build and tests need beside Debian's binary packages, fetched once into
# git-ignored folders (each step skipped when its result is there):
#   DEPS/{opensubdiv,draco,zstd,xxhash}  Debian's source packages (apt-get source, Debian's patches
#                                        applied), compiled to WebAssembly by apps/web/wasm
#   apps/web/node_modules                three.js and playwright-core at the versions that
#                                        package-lock.json pins (npm ci)
# Usage: apps/web/setup.sh DEPS   (.ci/setup passes build/web-deps; `--target web` runs it too)
set -euo pipefail
web="$(cd "$(dirname "$0")" && pwd)"
deps="${1:?usage: setup.sh DEPS_DIR}"
mkdir -p "$deps"
deps="$(cd "$deps" && pwd)"

# Debian source package -> the folder name the wasm build reads.
declare -A folders=([opensubdiv]=opensubdiv [draco]=draco [libzstd]=zstd [xxhash]=xxhash)
for package in "${!folders[@]}"; do
  folder="$deps/${folders[$package]}"
  [ -f "$folder/.unpacked" ] && continue
  if ! apt-cache showsrc "$package" 2>/dev/null | grep "^Package: $package" >/dev/null; then
    echo "setup.sh: Debian's source package '$package' is not known to apt: run .ci/setup (it enables deb-src)" >&2
    exit 1
  fi
  work="$deps/.fetch-$package"
  rm -rf "$work" "$folder"
  mkdir -p "$work"
  (cd "$work" && apt-get source -qq --download-only "$package" >/dev/null 2>&1 &&
     dpkg-source --no-check -x ./*.dsc unpacked >/dev/null)
  mv "$work/unpacked" "$folder"
  rm -rf "$work"
  touch "$folder/.unpacked"
done

if [ ! -f "$web/node_modules/.package-lock.json" ] || [ "$web/package-lock.json" -nt "$web/node_modules/.package-lock.json" ]; then
  (cd "$web" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
fi
