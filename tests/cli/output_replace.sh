#!/usr/bin/env bash
# What `rockdem run -o` may write over, and how (issue 47):
#   1. it refuses a symbolic link, a file that is not HDF5 (a user's CSV), an HDF5 file rockdem
#      did not write, a sweep table and a checkpoint: exit 2, one line naming the file, the file
#      unchanged (before: exit 0, the file, or the link's target, overwritten);
#   2. it replaces an earlier run file only once the new run has succeeded: a run killed
#      (SIGKILL at the fault points of src/base/fault.h) after any flush, or just before its
#      rename, or interrupted (SIGINT), leaves the earlier file as it was, and the new output,
#      a valid HDF5 file with what it had, in <file>.tmp-<pid>; a run that ends replaces it;
#   3. --overwrite writes over the earlier file in place (a kill leaves the new run's part);
#      --force (the step budget's) does not: a kill leaves the earlier file;
#   4. a new file is written in place: a kill after any flush leaves a valid file with every
#      flushed sample and the root status "running".
set -eu
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/output_replace; rm -rf "$T"; mkdir -p "$T"
SCN=scenarios/default.dat            # 6 s at 0.005 s: 1201 samples, flushed every 256
short=(--set model.duration=0.5)     # 101 samples
"$BIN" run "$SCN" -q "${short[@]}" -o "$T/earlier.h5" > /dev/null
sum() { sha256sum "$1" | cut -d' ' -f1; }
killed() {   # killed POINT ARGS...: the exit status of `run ARGS` with RD_FAULT=POINT
    RD_FAULT=$1 sh -c 'shift; "$@" > /dev/null 2>&1; echo $?' sh "$@"
}

# 1. refused, named, unchanged
printf 'x,y\n1,2\n' > "$T/user.csv"
/usr/bin/python3 -c "import h5py,sys; h5py.File(sys.argv[1],'w').attrs['who']='someone'" "$T/other.h5"
"$BIN" sweep tests/cli/data/sweep_brick.dat --set model.duration=0.05 --set model.settle=off --scales 0.01g -q -o "$T/table.h5"
printf 'model save "%s"\n' "$T/state.h5" | cat "$SCN" - > "$T/save.dat"
"$BIN" run "$T/save.dat" -q "${short[@]}" -o "$T/saved_run.h5" > /dev/null
ln -s "$T/earlier.h5" "$T/link.h5"
for f in link.h5:"symbolic link" user.csv:"not an HDF5 file" other.h5:"rockdem did not write" \
         table.h5:"sweep table" state.h5:"checkpoint"; do
    p=$T/${f%%:*}; why=${f#*:}; before=$(sum "$p")
    rc=0; "$BIN" run "$SCN" -q "${short[@]}" -o "$p" > /dev/null 2> "$T/refused.err" || rc=$?
    [ "$rc" -eq 2 ] && [ "$(wc -l < "$T/refused.err")" -eq 1 ] &&
        grep -q "^$p: cannot write the output there: .*$why" "$T/refused.err" && [ "$(sum "$p")" = "$before" ] ||
        { echo "FAIL -o ${f%%:*}: exit $rc"; cat "$T/refused.err"; exit 1; }
    echo "CHECK run -o ${f%%:*} is refused ($why), the file unchanged"
done
[ "$(sum "$T/earlier.h5")" = "$(sum "$T/link.h5")" ]
# check says the same before any work
rc=0; "$BIN" check "$SCN" -q -o "$T/user.csv" > /dev/null 2> "$T/check.err" || rc=$?
[ "$rc" -eq 2 ] && grep -q "$T/user.csv: cannot write the output there: .*not an HDF5 file" "$T/check.err"

# 2. an earlier run file is replaced only by a run that succeeds
ntime() { /usr/bin/python3 -c "import h5py,sys; print(h5py.File(sys.argv[1],'r')['time'].shape[0])" "$1"; }
status() { /usr/bin/python3 -c "import h5py,sys; s=h5py.File(sys.argv[1],'r').attrs['status']; print(s.decode() if isinstance(s,bytes) else s)" "$1"; }
for p in run-flush@1 run-flush@3 run-rename; do
    cp "$T/earlier.h5" "$T/r.h5"; rm -f "$T"/r.h5.tmp-*; before=$(sum "$T/r.h5")
    rc=$(killed "$p" "$BIN" run "$SCN" -q -o "$T/r.h5")
    tmp=$(ls "$T"/r.h5.tmp-* 2> /dev/null || true)
    [ "$rc" -eq 137 ] && [ "$(sum "$T/r.h5")" = "$before" ] && [ -n "$tmp" ] && h5dump -A "$tmp" > /dev/null ||
        { echo "FAIL replace killed at $p: exit $rc, earlier file kept: $([ "$(sum "$T/r.h5")" = "$before" ] && echo yes || echo no), temporary '$tmp'"; exit 1; }
    echo "CHECK a run killed at $p leaves the earlier file and its own valid part ($(ntime "$tmp") samples, status $(status "$tmp")) beside it"
done
# interrupted (SIGINT): the earlier file stays, the message names both files
cp "$T/earlier.h5" "$T/i.h5"; before=$(sum "$T/i.h5")
"$BIN" run "$SCN" --set model.duration=600 -o "$T/i.h5" > /dev/null 2> "$T/i.err" &
pid=$!; sleep 1.5; kill -INT "$pid"; rc=0; wait "$pid" || rc=$?
[ "$rc" -eq 130 ] && [ "$(sum "$T/i.h5")" = "$before" ] &&
    grep -q "interrupted at t = .*; $T/i.h5.tmp-$pid holds everything so far ($T/i.h5 keeps the earlier run)" "$T/i.err" &&
    [ "$(status "$T/i.h5.tmp-$pid")" = interrupted ] || { echo "FAIL interrupted replacement: exit $rc"; cat "$T/i.err"; exit 1; }
echo "CHECK an interrupted run leaves the earlier file; its own output is named"
# a run that succeeds replaces it, and leaves no temporary
cp "$T/earlier.h5" "$T/ok.h5"
"$BIN" run "$SCN" -q -o "$T/ok.h5" > /dev/null
[ "$(ntime "$T/ok.h5")" -eq 1201 ] && [ "$(status "$T/ok.h5")" = done ] && ! ls "$T"/ok.h5.tmp-* 2> /dev/null ||
    { echo "FAIL a successful run did not replace the earlier file"; exit 1; }
echo "CHECK a successful run replaces the earlier file, no temporary left"

# 3. --overwrite: in place; --force lifts the step budget only
cp "$T/earlier.h5" "$T/f.h5"
rc=$(killed run-flush@2 "$BIN" run "$SCN" -q --overwrite -o "$T/f.h5")
[ "$rc" -eq 137 ] && [ "$(ntime "$T/f.h5")" -eq 256 ] && ! ls "$T"/f.h5.tmp-* 2> /dev/null ||
    { echo "FAIL --overwrite: exit $rc"; exit 1; }
echo "CHECK --overwrite writes over the earlier file in place"
cp "$T/earlier.h5" "$T/g.h5"; rm -f "$T"/g.h5.tmp-*; before=$(sum "$T/g.h5")
rc=$(killed run-flush@2 "$BIN" run "$SCN" -q --force -o "$T/g.h5")
[ "$rc" -eq 137 ] && [ "$(sum "$T/g.h5")" = "$before" ] && ls "$T"/g.h5.tmp-* > /dev/null 2>&1 ||
    { echo "FAIL --force wrote over the earlier file: exit $rc"; exit 1; }
echo "CHECK --force alone leaves the earlier file to a killed run (it lifts the step budget only)"
rc=0; "$BIN" check "$SCN" -q --overwrite > /dev/null 2> "$T/ow.err" || rc=$?
[ "$rc" -eq 2 ] || { echo "FAIL check --overwrite: exit $rc (check writes nothing)"; exit 1; }
echo "CHECK check refuses --overwrite (it writes nothing): $(head -1 "$T/ow.err")"

# 4. a new file, killed after each of its first flushes: valid, status running
for k in 1 2 3 4; do
    rm -f "$T/new.h5"
    rc=$(killed "run-flush@$k" "$BIN" run "$SCN" -q -o "$T/new.h5")
    n=$(ntime "$T/new.h5")
    [ "$rc" -eq 137 ] && [ "$(status "$T/new.h5")" = running ] && [ "$n" -eq $(( (k - 1) * 256 )) ] ||
        { echo "FAIL new file killed after flush $k: exit $rc, $n samples"; exit 1; }
done
echo "CHECK a new run file killed after flushes 1-4 holds 0/256/512/768 samples, status running"

# 5. a checkpoint (model save) is written beside and renamed: killed before the rename, the
#    earlier checkpoint stays as it was
before=$(sum "$T/state.h5")
rc=$(killed checkpoint-rename "$BIN" run "$T/save.dat" -q "${short[@]}" -o "$T/saved_run.h5")
[ "$rc" -eq 137 ] && [ "$(sum "$T/state.h5")" = "$before" ] || { echo "FAIL checkpoint killed before its rename: exit $rc"; exit 1; }
rm -f "$T"/state.h5.tmp-*
"$BIN" run "$T/save.dat" -q "${short[@]}" -o "$T/saved_run.h5" > /dev/null
! ls "$T"/state.h5.tmp-* 2> /dev/null
echo "CHECK a checkpoint killed before its rename leaves the earlier one; a whole save replaces it"
