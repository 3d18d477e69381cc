#!/usr/bin/env bash
# The C sources keep the style of .clang-format (make format applies it): a change that is not
# formatted fails here with the first lines clang-format would change. Skipped without
# clang-format (Debian clang-format, installed by tools/install-deps.sh).
set -u
command -v clang-format > /dev/null || { echo "SKIP: clang-format not installed"; exit 77; }
files=$(make --no-print-directory -s -f - print-format-files <<'MK'
include Makefile
print-format-files: ; @echo $(FORMAT_FILES)
MK
)
[ -n "$files" ] || { echo "FAIL format: no files listed"; exit 1; }
# shellcheck disable=SC2086
if out=$(clang-format --dry-run -Werror $files 2>&1); then
    echo "CHECK format: $(echo $files | wc -w) files follow .clang-format"
else
    printf '%s\n' "$out" | head -20
    echo "FAIL format: run 'make format'"
    exit 1
fi
