#!/usr/bin/env bash
# Installs what poinav-export's 3D export tests run: the Khronos glTF-Validator (npm, pinned in
# package-lock.json, into tests/js/node_modules) and assimp's command-line tool (Debian package
# assimp-utils, for `assimp info`; needs root, skipped when `assimp` is already on PATH).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
npm ci --prefix "$here" --no-audit --no-fund
if ! command -v assimp >/dev/null; then
    apt-get update
    apt-get install -y assimp-utils
fi
