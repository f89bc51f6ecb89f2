#!/usr/bin/env bash
# Refreshes the Leaflet files `netspec serve` embeds (src/serve/assets/vendor/leaflet/) from the
# npm registry: leaflet.js, leaflet.css and the licence of the pinned version, the source-map
# comment removed (the map is not shipped). Run by hand when the version changes.
set -euo pipefail
VERSION=1.9.4
here=$(cd "$(dirname "$0")/.." && pwd)
dest=$here/src/serve/assets/vendor/leaflet
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
(cd "$tmp" && npm pack -q "leaflet@$VERSION" > /dev/null && tar -xzf "leaflet-$VERSION.tgz")
mkdir -p "$dest"
sed '/^\/\/# sourceMappingURL=/d' "$tmp/package/dist/leaflet.js" > "$dest/leaflet.js"
cp "$tmp/package/dist/leaflet.css" "$dest/leaflet.css"
cp "$tmp/package/LICENSE" "$dest/LICENSE"
echo "Leaflet $VERSION in $dest"
