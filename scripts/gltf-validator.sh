#!/usr/bin/env bash
# Installs the Khronos glTF validator (the npm package `gltf-validator`, pinned) into
# the target folder, where tests/gltf_validator.rs finds it: every exported .glb must
# pass it with no errors. Needs node and npm (apt-get install nodejs npm).
#
# Usage: scripts/gltf-validator.sh [VERSION]
# Installs into $CARGO_TARGET_DIR/gltf-validator, or target/gltf-validator without it;
# the test also takes the package folder from SHAPEGEN_GLTF_VALIDATOR.
set -euo pipefail
cd "$(dirname "$0")/.."
version="${1:-2.0.0-dev.3.10}"
out="${CARGO_TARGET_DIR:-target}/gltf-validator"
mkdir -p "$out"
installed() {
  node -p "try { require(require('path').resolve(process.argv[1], 'node_modules/gltf-validator/package.json')).version } catch { '' }" "$out" 2>/dev/null
}
if [ "$(installed)" = "$version" ]; then
  echo "gltf-validator $version already in $out"
  exit 0
fi
# A package.json of its own, so that npm installs here and not in a folder above.
[ -f "$out/package.json" ] || echo '{ "private": true }' >"$out/package.json"
npm install --prefix "$out" --no-audit --no-fund --save-exact --loglevel=error "gltf-validator@$version"
[ "$(installed)" = "$version" ] || { echo "gltf-validator $version did not install into $out"; exit 1; }
echo "gltf-validator $version in $out"
