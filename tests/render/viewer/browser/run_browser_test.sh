#!/usr/bin/env bash
# The viewer in a real browser: parses the bundled example, starts `render --serve` on a free
# port and drives the page with headless Chromium (viewer_browser_test.mjs, puppeteer-core).
# Usage: run_browser_test.sh BIN_DIR [SCREENSHOT.png]
# Exit 77 (ctest: skipped) when Node, Chromium or the npm packages are not installed; the line
# before says which. scripts/install-deps.sh ci installs all three.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=$(cd "$1" && pwd)
screenshot=${2:-}
root=$(cd "$here/../../../.." && pwd)

skip() { echo "SKIP: $1"; exit 77; }
command -v node >/dev/null || skip "no node (apt-get install nodejs npm)"
[ -x /usr/bin/chromium ] || skip "no /usr/bin/chromium (apt-get install chromium)"
[ -d "$here/node_modules/puppeteer-core" ] || skip "no puppeteer-core (cd $here && npm ci)"

work=$(mktemp -d)
server=
cleanup() {
  [ -n "$server" ] && kill "$server" 2>/dev/null && wait "$server" 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT

"$bin/osmparse" "$root/examples/neukolln.osm.bz2" -q -o "$work/city.scene"
mkdir "$work/saved"
"$bin/render" "$work/city.scene" --serve 0 --serve-out "$work/saved" --procedural -q > "$work/url" &
server=$!
for _ in $(seq 300); do
  grep -q "http://" "$work/url" 2>/dev/null && break
  kill -0 "$server" 2>/dev/null || { echo "render --serve ended early"; exit 1; }
  sleep 0.1
done
url=$(grep -o 'http://[^ ]*' "$work/url")
echo "# $url"
args=(--url "$url" --render "$bin/render" --scene "$work/city.scene" --out "$work")
[ -n "$screenshot" ] && args+=(--screenshot "$screenshot")
node "$here/viewer_browser_test.mjs" "${args[@]}"
