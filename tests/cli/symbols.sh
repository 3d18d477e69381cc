#!/usr/bin/env bash
# The library boundary: librockdem.so and librockdem.a export exactly the functions the public
# headers (include/rockdem/*.h) declare, every one marked RD_API and carrying the rd_ prefix
# (REBOUND's CI check); no helper of a folder leaks into a user's namespace, and no CLI code
# (rd_cli_*) is in the library. Reads the libraries next to the test binaries.
set -eu
build=${RD_BUILD:-build}
for lib in "$build/librockdem.a" "$build/librockdem.so"; do
    [ -f "$lib" ] || { echo "no library at $lib"; exit 1; }
done
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
# every function prototype at the start of a line in the public headers, with or without RD_API
grep -hE '^(RD_API )?[A-Za-z_][A-Za-z_0-9 *]*\brd_[a-z0-9_]+\(' include/rockdem/*.h |
    grep -vE '^(typedef|static)' > "$tmp/protos"
grep -v '^RD_API ' "$tmp/protos" > "$tmp/unmarked" || true
[ -s "$tmp/unmarked" ] && { echo "public functions without RD_API:"; cat "$tmp/unmarked"; exit 1; }
sed -E 's/^.*\b(rd_[a-z0-9_]+)\(.*$/\1/' "$tmp/protos" | sort -u > "$tmp/declared"
nm -D --defined-only "$build/librockdem.so" | awk '$2 ~ /[TDBR]/ { print $3 }' | sort -u > "$tmp/so"
nm -g --defined-only "$build/librockdem.a" | awk 'NF == 3 && $2 ~ /[TDBR]/ && $3 !~ /^__(odr_)?asan/ { print $3 }' |
    sort -u > "$tmp/a"  # sanitizer builds add __odr_asan.*
n=$(wc -l < "$tmp/declared")
[ "$n" -gt 50 ] || { echo "only $n public functions found in include/rockdem/"; exit 1; }
for lib in so a; do
    if ! diff "$tmp/declared" "$tmp/$lib" > "$tmp/diff"; then
        echo "librockdem.$lib exports differ from the public headers (< declared only, > exported only):"
        cat "$tmp/diff"; exit 1
    fi
done
echo "librockdem.so and librockdem.a export the $n public functions"
