#!/usr/bin/env bash
# The library's folders call only the folders docs/ARCHITECTURE.md's table allows (issue 14):
# every undefined symbol of a folder's objects that another folder defines is an edge, read
# with nm as the linker sees it. An edge outside the table fails, naming the symbols; so does
# a cycle (each allowed edge points down the order base < geometry, records < scenario <
# engine < io < reference < ensembles, so the allowed graph has none). The CLI is checked by
# the link itself: it links the static library, whose internal symbols are local.
set -eu
export LC_ALL=C   # sort and join must agree on the order of symbol names
OBJ=${RD_BUILD:-build}/obj
[ -d "$OBJ/engine" ] || { echo "FAIL: no objects in $OBJ (build first)"; exit 1; }
declare -A allowed=(
    [base]=""
    [geometry]="base"
    [records]="base"
    [scenario]="base geometry records"
    [engine]="base geometry records scenario"
    [io]="base records engine"
    [reference]="base records engine io"
    [ensembles]="base records scenario engine reference io"
    [assess]="base records scenario engine io"
)
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
# a folder's objects: those of its sources now (a stale object of a moved file is no edge)
objs() { for c in src/"$1"/*.c; do f=${c#src/}; echo "$OBJ/${f%.c}.o"; done; }
for d in "${!allowed[@]}"; do
    nm --defined-only -g $(objs "$d") | awk -v d="$d" 'NF == 3 {print $3, d}'
done | sort -u > "$T/defined"
bad=0; edges=0
for d in "${!allowed[@]}"; do
    nm -u $(objs "$d") | awk 'NF == 2 {print $2}' | sort -u | join - "$T/defined" |
        awk -v d="$d" '$2 != d {print $2, $1}' | sort > "$T/edges"
    for to in $(cut -d' ' -f1 "$T/edges" | uniq); do
        edges=$((edges + 1))
        case " ${allowed[$d]} " in
            *" $to "*) ;;
            *) echo "FAIL: $d -> $to: $(awk -v t="$to" '$1 == t {print $2}' "$T/edges" | paste -sd ' ')"
               bad=1 ;;
        esac
    done
done
[ "$bad" -eq 0 ] || exit 1
echo "layers: $edges folder edges, all allowed by docs/ARCHITECTURE.md, no cycle"
