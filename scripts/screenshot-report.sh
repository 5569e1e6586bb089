#!/usr/bin/env bash
# Render the HTML report in headless Chromium and save PNG screenshots (to look at what a reader
# sees). Needs `scripts/setup-debian.sh --browser`. Usage: scripts/screenshot-report.sh [report] [out]
set -euo pipefail
report="${1:-report}"; out="${2:-report/screenshots}"
mkdir -p "$out"
profile=$(mktemp -d)
trap 'rm -rf "$profile"' EXIT
for page in "$report"/*.html; do
  name=$(basename "$page" .html)
  timeout 120 chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
    --disable-background-networking --disable-component-update --disable-sync \
    --user-data-dir="$profile" --window-size=1280,2400 \
    --screenshot="$out/$name.png" "file://$(realpath "$page")" 2>/dev/null
  echo "screenshot: $out/$name.png"
done
