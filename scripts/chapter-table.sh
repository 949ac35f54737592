#!/usr/bin/env bash
# Prints the chapter map as a Markdown table, read from the chapters' own first lines
# ("/// \page chNN Title" and "/// \builds_on chMM"), for README.md:
#
#   bash scripts/chapter-table.sh
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

echo "| Chapter | Builds on | What it adds |"
echo "|:--|:--|:--|"
for dir in "$root"/chapters/[0-9][0-9]-*/; do
  [[ -d "$dir" ]] || continue
  name="$(basename "$dir")"
  program="$dir/${name#??-}.cpp"
  if [[ ! -f "$program" ]]; then
    program="$(grep -l '^[[:space:]]*///[[:space:]]*\\page' "$dir"*.cpp 2>/dev/null |
                 head -n 1 || true)"
  fi
  [[ -n "$program" && -f "$program" ]] || continue
  title="$(sed -n 's|^[[:space:]]*///[[:space:]]*\\page[[:space:]]*[^[:space:]]*[[:space:]]*||p' \
             "$program" | head -n 1)"
  builds="$(sed -n 's|^[[:space:]]*///[[:space:]]*\\builds_on[[:space:]]*||p' "$program" |
              tr ',\n' '  ' | xargs)"
  builds="$(for page in $builds; do printf '%s ' "${page#ch}"; done | xargs | sed 's/ /, /g')"
  echo "| [$title](chapters/$name/) | ${builds:-—} | |"
done
