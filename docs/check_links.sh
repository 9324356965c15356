#!/usr/bin/env bash
# Every relative link ](target) and image in README.md and docs/**/*.md must name an existing file.
# Usage: docs/check_links.sh [REPO_ROOT]   (prints each broken link; silent when all resolve)
cd "${1:-$(dirname "$0")/..}"
fail=0
for f in README.md $(find docs -name '*.md'); do
  dir=$(dirname "$f")
  grep -oE '\]\([^)]+\)' "$f" | sed -E 's/^\]\(//; s/\)$//' | while read -r t; do
    case "$t" in http*|mailto:*) continue;; esac
    path=${t%%#*}
    [ -z "$path" ] && continue
    [ -e "$dir/$path" ] || { echo "$f: broken link $t"; }
  done
done
