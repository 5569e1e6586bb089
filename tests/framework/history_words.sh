#!/usr/bin/env bash
# Repository text describes the project, not its history: no "session N", "this session", "issue N"
# and no machine paths in case files, findings, READMEs, paper-resolution records and reference
# metadata, and no history words in code comments or strings. History belongs in commit messages.
set -u
root="$1"
cd "$root" || exit 2
pattern='[Ss]ession[ -]?[0-9]|[Tt]his session|[Ii]ssues?[ -]?#?[0-9]|/work/|/home/|/tmp/|/root/'
files=$(git ls-files --cached --others --exclude-standard -- '*.toml' '*.md' 'reports/full_tier/*/*.json' \
          'reference_data/*.csv' 'reference_data/*/inventory' | grep -v '^tests/data/')
hits=$(grep -nE "$pattern" $files /dev/null || true)
# code and scripts: no history words (paths are theirs to use)
code=$(git ls-files --cached --others --exclude-standard -- '*.cpp' '*.hpp' '*.h' '*.py' '*.sh' '*.cmake' \
          '*CMakeLists.txt' | grep -v '^tests/framework/history_words.sh$')
hits+=$(grep -nE '[Ss]ession[ -]?[0-9]|[Tt]his session|[Ii]ssues?[ -]?#?[0-9]' $code /dev/null || true)
if [[ -n "$hits" ]]; then
  echo "history words or machine paths in repository text (describe the project; history goes to commit messages):"
  echo "$hits" | head -n 40
  echo "$(echo "$hits" | wc -l) lines"
  exit 1
fi
echo "ok: $(echo "$files" | wc -w) files free of history words and machine paths"
