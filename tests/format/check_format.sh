#!/usr/bin/env bash
# Every C++ file of the tree (.cpp, .h) is formatted by the committed
# .clang-format: clang-format-14 --dry-run -Werror over the tracked files
# (every .cpp/.h under the tree when it is not a git checkout).
# Left out: the generated ltc_ggx_table.cpp (libaaf/trace/shading/ltc_ggx_table.cpp),
# written by scripts/ltc_fit: its 4,096 table rows are the generator's
# output, one cell a line, and regenerating the file must reproduce it byte
# for byte, so it is not reflowed by hand.
# Usage: check_format.sh SOURCE_DIR. Exit 0 when all are formatted, 1 with
# the unformatted files named (and the command that formats them).
set -euo pipefail
root="$1"
cd "$root"
clang_format=clang-format-14
command -v "$clang_format" >/dev/null ||
  { echo "check_format: $clang_format not found (scripts/deps.sh installs it)" >&2; exit 1; }
[ -f .clang-format ] || { echo "check_format: no .clang-format in $root" >&2; exit 1; }
if git -C "$root" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  mapfile -t files < <(git ls-files -- '*.cpp' '*.h')
else
  mapfile -t files < <(find . -path ./build -prune -o \( -name '*.cpp' -o -name '*.h' \) -type f -print | sed 's|^\./||' | sort)
fi
checked=()
for f in "${files[@]}"; do
  case "$f" in
    */ltc_ggx_table.cpp) ;;
    *) [ -f "$f" ] && checked+=("$f") ;;
  esac
done
[ ${#checked[@]} -gt 0 ] || { echo "check_format: no C++ files found under $root" >&2; exit 1; }
# One clang-format run over every file: it reports each unformatted one as
# FILE:LINE:COL: error: code should be clang-formatted.
status=0
report=$("$clang_format" --dry-run -Werror --style=file "${checked[@]}" 2>&1) || status=$?
mapfile -t unformatted < <(printf '%s\n' "$report" | grep -oE '^[^:]+:[0-9]+:[0-9]+: error' | cut -d: -f1 | sort -u)
if [ "$status" -ne 0 ] && [ ${#unformatted[@]} -eq 0 ]; then
  echo "check_format: $clang_format failed: $(printf '%s\n' "$report" | head -1)" >&2
  exit 1
fi
if [ ${#unformatted[@]} -gt 0 ]; then
  echo "check_format: ${#unformatted[@]} of ${#checked[@]} C++ files are not formatted by .clang-format:" >&2
  printf '  %s\n' "${unformatted[@]}" >&2
  echo "check_format: format them with: $clang_format -i FILE..." >&2
  exit 1
fi
echo "check_format: ${#checked[@]} C++ files formatted"
