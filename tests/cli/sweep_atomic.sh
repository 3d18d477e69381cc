#!/usr/bin/env bash
# A sweep table is never left silently wrong (issue 47):
#   1. the final reordering of a table whose rows finished out of order is killed (SIGKILL, the
#      fault points of src/base/fault.h) at every step: before and after each column of the
#      sorted copy, before and after its rename. Each kill leaves a table whose every row is
#      whole (its swept values are its case's), and the same command then completes it equal to
#      the uninterrupted table. (Reordered in place, as before, a kill between two columns left
#      rows whose scale and direction were another case's, and resume took them: exit 0.)
#   2. a table whose rows hold another case's swept values is refused with one line, exit 2.
set -eu
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/sweep_atomic; rm -rf "$T"; mkdir -p "$T"
S=tests/cli/data/sweep_brick.dat
args=(--set model.duration=0.05 --set model.settle=off --directions 0,30 --scales 0.01g,0.02g,0.03g -j 1 -q)
"$BIN" sweep "$S" "${args[@]}" -o "$T/full.h5"
# the same rows in the order a parallel sweep may leave them: 5 3 0 4 1 2
/usr/bin/python3 - "$T/full.h5" "$T/shuffled.h5" <<'PY'
import sys, shutil, h5py
shutil.copy(sys.argv[1], sys.argv[2])
g = h5py.File(sys.argv[2], "r+")["sweep"]
order = [5, 3, 0, 4, 1, 2]
for k in g:
    if k != "body":
        g[k][...] = g[k][()][order]
PY
cmp_tables() {   # $1 reference, $2 table: the same rows in case order
    /usr/bin/python3 - "$1" "$2" <<'PY'
import sys, h5py, numpy as np
a, b = h5py.File(sys.argv[1], "r")["sweep"], h5py.File(sys.argv[2], "r")["sweep"]
assert list(b["case"][()]) == list(range(len(a["case"]))), b["case"][()]
for k in a:
    if k not in ("wall_seconds", "body"):
        assert np.array_equal(a[k][()], b[k][()]), k
PY
}
rows_whole() {   # every row of $2 is the row of its case in the reference $1
    /usr/bin/python3 - "$1" "$2" <<'PY'
import sys, h5py, numpy as np
a, b = h5py.File(sys.argv[1], "r")["sweep"], h5py.File(sys.argv[2], "r")["sweep"]
k = b["case"][()]
assert sorted(k) == list(range(len(a["case"]))), k
for c in a:
    if c not in ("wall_seconds", "body"):
        assert np.array_equal(a[c][()][k], b[c][()]), c
PY
}
ncols=$(/usr/bin/python3 -c "import h5py,sys; print(sum(1 for k in h5py.File(sys.argv[1],'r')['sweep'] if k != 'body'))" "$T/full.h5")
points=()
for ((c = 1; c <= ncols; c++)); do points+=("sweep-sort-column@$c"); done
points+=(sweep-sort-rename sweep-sort-renamed)
for p in "${points[@]}"; do
    cp "$T/shuffled.h5" "$T/k.h5"
    rc=$(RD_FAULT=$p sh -c '"$@" 2> "$0"; echo $?' "$T/k.err" "$BIN" sweep "$S" "${args[@]}" -o "$T/k.h5")
    [ "$rc" -eq 137 ] || { echo "FAIL kill at $p: exit $rc"; cat "$T/k.err"; exit 1; }
    rows_whole "$T/full.h5" "$T/k.h5" || { echo "FAIL kill at $p: a row is not whole"; exit 1; }
    "$BIN" sweep "$S" "${args[@]}" -o "$T/k.h5" > "$T/resume.out" 2>&1 ||
        { echo "FAIL kill at $p: resume"; cat "$T/resume.out"; exit 1; }
    cmp_tables "$T/full.h5" "$T/k.h5" || { echo "FAIL kill at $p: resumed table differs"; exit 1; }
    echo "CHECK kill at $p: the table stays whole and resumes to the uninterrupted one"
done
rm -f "$T"/k.h5.tmp-*

# 2. rows 0 and 1 swap their direction (what the in-place reordering left): refused
cp "$T/full.h5" "$T/bad.h5"
/usr/bin/python3 - "$T/bad.h5" <<'PY'
import sys, h5py
g = h5py.File(sys.argv[1], "r+")["sweep"]
name = [k for k in g if g[k].attrs.get("long_name") in (b"swept value", "swept value")][0]
v = g[name][()]
v[[0, 3]] = v[[3, 0]]
g[name][...] = v
PY
rc=0; "$BIN" sweep "$S" "${args[@]}" -o "$T/bad.h5" 2> "$T/bad.err" || rc=$?
[ "$rc" -eq 2 ] || { echo "FAIL damaged table: exit $rc"; cat "$T/bad.err"; exit 1; }
[ "$(wc -l < "$T/bad.err")" -eq 1 ] && grep -q "rockdem sweep: $T/bad.h5 is damaged: row 0 (case 0) holds a '.*' value of another case" "$T/bad.err" ||
    { echo "FAIL damaged table: message"; cat "$T/bad.err"; exit 1; }
echo "CHECK a table with another case's swept values is refused, one line, exit 2"
