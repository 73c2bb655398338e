#!/usr/bin/env bash
# Vendors the run viewer's JavaScript libraries from the npm registry into
# assets/viewer/vendor/: three.js (the renderer, the glTF and OBJ loaders, the orbit
# controls and the two utilities the glTF loader imports) and uPlot (the fitness curves),
# each with its licence and a VERSION file. Files are stored gzipped (`gzip -n -9`, so the
# same package gives the same bytes) and embedded in the binary as they are.
#
# Usage: scripts/vendor-viewer.sh [THREE_VERSION] [UPLOT_VERSION]
set -euo pipefail
cd "$(dirname "$0")/.."
three="${1:-0.187.0}"
uplot="${2:-1.6.32}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
(cd "$work" && npm pack --silent "three@$three" "uplot@$uplot" >/dev/null)
mkdir -p "$work/three" "$work/uplot"
tar xzf "$work/three-$three.tgz" -C "$work/three" --strip-components=1
tar xzf "$work/uplot-$uplot.tgz" -C "$work/uplot" --strip-components=1

out=assets/viewer/vendor
rm -rf "$out"
mkdir -p "$out/three/addons/loaders" "$out/three/addons/controls" "$out/three/addons/utils" "$out/uplot"
pack() { gzip -n -9 -c "$1" >"$2.gz"; }
pack "$work/three/build/three.module.js" "$out/three/three.module.js"
pack "$work/three/build/three.core.js" "$out/three/three.core.js"
for f in loaders/GLTFLoader.js loaders/OBJLoader.js controls/OrbitControls.js \
  utils/BufferGeometryUtils.js utils/SkeletonUtils.js; do
  pack "$work/three/examples/jsm/$f" "$out/three/addons/$f"
done
cp "$work/three/LICENSE" "$out/three/LICENSE"
echo "three $three (npm registry: npm pack three@$three)" >"$out/three/VERSION"
pack "$work/uplot/dist/uPlot.iife.min.js" "$out/uplot/uPlot.iife.min.js"
pack "$work/uplot/dist/uPlot.min.css" "$out/uplot/uPlot.min.css"
cp "$work/uplot/LICENSE" "$out/uplot/LICENSE"
echo "uplot $uplot (npm registry: npm pack uplot@$uplot)" >"$out/uplot/VERSION"
du -sh "$out"
