#!/usr/bin/env bash
# Check that every C++ file git tracks is formatted with the project's
# .clang-format (deal.II's style). Prints the files to reformat and the
# command that does it; exit code 1 if there are any.
#   bash tools/check_format.sh
set -euo pipefail
cd "$(dirname "$0")/.."
format=$(command -v clang-format-14 || command -v clang-format || true)
if [ -z "$format" ]; then
  echo "check_format: clang-format is not installed (apt-get install clang-format)" >&2
  exit 1
fi
bad=()
while IFS= read -r f; do
  "$format" --dry-run --Werror "$f" > /dev/null 2>&1 || bad+=("$f")
done < <(git ls-files '*.cc' '*.h')
if [ ${#bad[@]} -gt 0 ]; then
  echo "check_format: ${#bad[@]} file(s) are not formatted with .clang-format:"
  printf '  %s\n' "${bad[@]}"
  echo "Reformat them with:  clang-format -i ${bad[*]}"
  exit 1
fi
echo "check_format: all $(git ls-files '*.cc' '*.h' | wc -l) C++ files are formatted."
