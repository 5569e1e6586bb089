#!/usr/bin/env bash
# Render the HTML report in headless Chromium and save PNG screenshots of what a reader sees: the
# index, the opening of one paper page (its item table), one case with a plot, and that paper's
# findings page. Needs `scripts/setup-debian.sh --browser`.
#   scripts/screenshot-report.sh [report] [out] [paper] [item]
#     report  the report directory (default: report)
#     out     where the PNGs go; keep it outside git (default: build/report-screenshots)
#     paper   the paper page (default: the first paper page with a case that has a plot)
#     item    the case to show, an item id of that paper such as fig05 (default: its first case with a plot)
set -euo pipefail
report="${1:-report}"; out="${2:-build/report-screenshots}"; paper="${3:-}"; item="${4:-}"
browser=$(command -v chromium || command -v chromium-browser || true)
[[ -n "$browser" ]] || { echo "screenshot-report: no chromium (scripts/setup-debian.sh --browser)" >&2; exit 2; }
[[ -f "$report/index.html" ]] || { echo "screenshot-report: no $report/index.html (cutbench report)" >&2; exit 2; }
report=$(realpath "$report")
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# the cases that have a plot carry data-plots="N" (N > 0) in their <div class="case">
first_case_with_plot() { grep -o 'class="case" id="[^"]*" data-plots="[1-9][0-9]*"' "$1" | head -n 1 |
                         sed 's/.*id="\([^"]*\)".*/\1/' || true; }
if [[ -z "$paper" ]]; then
  for page in "$report"/*.html; do
    name=$(basename "$page" .html)
    [[ "$name" == index || "$name" == findings-* ]] && continue
    if [[ -n $(first_case_with_plot "$page") ]]; then paper="$name"; break; fi
  done
fi
[[ -n "$paper" && -f "$report/$paper.html" ]] || { echo "screenshot-report: no paper page found" >&2; exit 2; }
[[ -n "$item" ]] || item=$(first_case_with_plot "$report/$paper.html")

shoot() {  # shoot NAME URL WIDTH HEIGHT
  # a fresh profile per shot; --screenshot captures the window (a URL #fragment is not honoured by
  # headless screenshots, so a case is shown through a wrapper page whose iframe scrolls to it)
  local profile; profile=$(mktemp -d "$work/profile.XXXX")
  timeout 120 "$browser" --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
    --disable-background-networking --disable-component-update --disable-sync \
    --user-data-dir="$profile" --allow-file-access-from-files --hide-scrollbars --run-all-compositor-stages-before-draw \
    --virtual-time-budget=5000 --window-size="$3,$4" --screenshot="$out/$1.png" "$2" >/dev/null 2>&1
  [[ -s "$out/$1.png" ]] || { echo "screenshot-report: $1 failed" >&2; return 1; }
  echo "screenshot: $out/$1.png"
}
frame() {  # frame PAGE#ANCHOR -> a wrapper page showing it scrolled to the anchor
  local f="$work/frame-$RANDOM.html"
  printf '<!DOCTYPE html><html><body style="margin:0;overflow:hidden"><iframe src="file://%s" ' "$1" >"$f"
  printf 'style="border:0;width:100vw;height:100vh"></iframe></body></html>\n' >>"$f"
  echo "file://$f"
}

shoot index "file://$report/index.html" 1400 1100
shoot "$paper" "file://$report/$paper.html" 1400 1600
if [[ -n "$item" ]]; then
  shoot "$paper-$item" "$(frame "$report/$paper.html#$item")" 1400 2200
else
  echo "screenshot-report: no case with a plot on $paper.html" >&2
fi
if [[ -f "$report/findings-$paper.html" ]]; then
  shoot "findings-$paper" "file://$report/findings-$paper.html" 1400 1400
fi
