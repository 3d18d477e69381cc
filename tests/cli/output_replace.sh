
# 5. a checkpoint (model save) is written beside and renamed: killed before the rename, the
#    earlier checkpoint stays as it was and still restores
before=$(sum "$T/state.h5")
rc=$(killed checkpoint-rename "$BIN" run "$T/save.dat" -q "${short[@]}" -o "$T/saved_run.h5")
[ "$rc" -eq 137 ] && [ "$(sum "$T/state.h5")" = "$before" ] || { echo "FAIL checkpoint killed before its rename: exit $rc"; exit 1; }
rm -f "$T"/state.h5.tmp-*
"$BIN" run "$T/save.dat" -q "${short[@]}" -o "$T/saved_run.h5" > /dev/null
! ls "$T"/state.h5.tmp-* 2> /dev/null
echo "CHECK a checkpoint killed before its rename leaves the earlier one; a whole save replaces it"
