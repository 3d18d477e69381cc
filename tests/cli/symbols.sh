#!/usr/bin/env bash
# Every symbol the library exports carries the project prefix rd_ (REBOUND's CI check): no
# helper leaks into a user's namespace. Reads the static library next to the test binaries.
set -eu
lib=${RD_BUILD:-build}/librockdem.a
[ -f "$lib" ] || { echo "no library at $lib"; exit 1; }
n=$(nm -g --defined-only "$lib" | awk 'NF == 3 && $2 ~ /[TDBR]/' | wc -l)
bad=$(nm -g --defined-only "$lib" | awk 'NF == 3 && $2 ~ /[TDBR]/ && $3 !~ /^rd_/ && $3 !~ /^__(odr_)?asan/ { print $3 }')  # sanitizer builds add __odr_asan.*
[ "$n" -gt 50 ] || { echo "only $n exported symbols found in $lib"; exit 1; }
[ -z "$bad" ] || { echo "exported without the rd_ prefix:"; printf '%s\n' "$bad"; exit 1; }
