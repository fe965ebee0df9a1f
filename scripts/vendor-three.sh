#!/usr/bin/env bash
# Copies the three.js files the viewer uses from npm (the version pinned in
# tests/js/package-lock.json) into crates/poinav-viewer/web/vendor/three, which the binary
# embeds. Run after changing the three.js version; the test `vendored_three_matches_npm`
# (crates/poinav-viewer/tests/assets.rs) fails while the copies differ from the npm package.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
src="$root/tests/js/node_modules/three"
if [[ ! -d $src ]]; then
    npm ci --prefix "$root/tests/js" --no-audit --no-fund
fi
dst="$root/crates/poinav-viewer/web/vendor/three"
rm -rf "$dst"
mkdir -p "$dst"
while read -r from to; do
    mkdir -p "$(dirname "$dst/$to")"
    cp "$src/$from" "$dst/$to"
done < "$root/crates/poinav-viewer/web/vendor.txt"
