#!/usr/bin/env bash
# Regenerates every golden scene in tests/golden from the fixtures in tests/data.
# This is a reviewed act: run it only when a change is MEANT to alter scene contents, look
# at the --diff output it prints against the old goldens, and say in the commit message
# that goldens were regenerated and why. See tests/golden/README.md.
set -euo pipefail
cd "$(dirname "$0")/../.."
osmparse=build/bin/osmparse
[ -x "$osmparse" ] || { echo "regenerate.sh: build first ($osmparse missing)" >&2; exit 1; }
for fixture in tests/data/*.osm; do
    name=$(basename "$fixture" .osm)
    golden=tests/golden/$name.scene
    fresh=$(mktemp --suffix=.scene)
    "$osmparse" --quiet "$fixture" -o "$fresh"
    if [ -f "$golden" ] && "$osmparse" --diff "$golden" "$fresh" > /dev/null; then
        echo "unchanged  $name"
    else
        if [ -f "$golden" ]; then
            echo "CHANGED    $name:"
            "$osmparse" --diff "$golden" "$fresh" | sed 's/^/    /' | head -40 || true
        else
            echo "NEW        $name"
        fi
    fi
    mv "$fresh" "$golden"
    chmod 644 "$golden"
done
# Goldens whose fixture is gone.
for golden in tests/golden/*.scene; do
    [ -f "tests/data/$(basename "$golden" .scene).osm" ] || { echo "REMOVED    $golden"; rm "$golden"; }
done
