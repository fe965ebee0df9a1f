#!/usr/bin/env bash
# Installs what the JavaScript-side tests run: from npm (pinned in package-lock.json, into
# tests/js/node_modules) the Khronos glTF-Validator, three.js (the viewer's vendored copy is
# checked against it) and playwright-core; from Debian, assimp's command-line tool (for
# `assimp info`) and Chromium (the viewer's end-to-end test). The Debian packages need root and
# are skipped when already installed.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
npm ci --prefix "$here" --no-audit --no-fund
packages=()
command -v assimp >/dev/null || packages+=(assimp-utils)
[[ -x /usr/bin/chromium ]] || packages+=(chromium)
if ((${#packages[@]})); then
    apt-get update
    apt-get install -y --no-install-recommends "${packages[@]}"
fi
