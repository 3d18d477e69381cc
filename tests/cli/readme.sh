#!/usr/bin/env bash
# The README says what the program does: its quick-start output block is what `make run`
# prints (every line but perf: and output:, which vary with the machine and the path), its
# scenario block is scenarios/default.dat without comments, its tutorial scenario passes
# `check`, and the tutorial's sweep and fragility commands run as written (each case shortened).
# A change of results or syntax that leaves the README stale fails here.
set -u
. "$(dirname "$0")/lib/check.sh"
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}
fail=0
# block N: the N-th fenced block (1-based) after the heading line $1 of README.md
block() {
    awk -v h="$1" -v n="$2" '$0 == h { on = 1; next } on && /^## / { exit }
        on && /^ *```/ { if (inblk) { inblk = 0; if (++k == n) exit; next } inblk = 1; next }
        on && inblk && k == n - 1 { sub(/^   /, ""); print }' README.md
}
judge() { if [ "$2" = ok ]; then echo "CHECK $1"; else echo "FAIL $1: $2"; fail=1; fi; }

# 1. the quick start's output (its first block)
block '## Quick start' 1 > "$T/readme_out.txt"
( cd "$T" && "$BIN" run "$OLDPWD/scenarios/default.dat" -o "$T/default.h5" ) 2>&1 |
    grep -v -E '^(perf|output): ' > "$T/run_out.txt"
if diff -u "$T/readme_out.txt" "$T/run_out.txt" > "$T/diff.txt"; then judge readme-run-output ok
else cat "$T/diff.txt"; judge readme-run-output "README's quick-start output differs from make run's"; fi

# 2. the quick start's scenario is the shipped one
block '## Quick start' 2 > "$T/readme_dat.txt"
grep -v -E '^(;|[[:space:]]*$)' scenarios/default.dat > "$T/default_lines.txt"
if diff -u "$T/readme_dat.txt" "$T/default_lines.txt" > "$T/diff.txt"; then judge readme-scenario ok
else cat "$T/diff.txt"; judge readme-scenario "README's scenario differs from scenarios/default.dat"; fi

# 3. the tutorial's scenario passes check --strict (beside the shipped rock's mesh, as the tutorial says)
block '## Tutorial: your own scanned rock' 1 > "$T/myrock.dat"
cp scenarios/pbr.obj "$T/pbr.obj"
if out=$("$BIN" check --strict "$T/myrock.dat" 2>&1) && [ -s "$T/myrock.dat" ]; then judge readme-tutorial-check ok
else printf '%s\n' "$out"; judge readme-tutorial-check "the tutorial's scenario fails check"; fi
# 4. the tutorial's sweep and fragility commands as written, each case cut to 0.5 s (the
#    README's full 8 s sweep is 60 runs: a minute or so on two cores)
block '## Tutorial: your own scanned rock' 2 | tr -d '\\\n' | sed 's/  */ /g' > "$T/sweep_cmd.txt"
frag=$(awk '/^## Tutorial/ { on = 1 } on && /^## Scene/ { exit } on' README.md | tr '\n' ' ' |
    grep -o '`/usr/bin/python3 tools/rdfragility.py [^`]*`' | tr -d '`' | sed 's/  */ /g')
mkdir -p "$T/tut/scenarios"
cp "$T/myrock.dat" "$T/tut/scenarios/myrock.dat"; cp scenarios/pbr.obj "$T/tut/scenarios/pbr.obj"
REPO=$(pwd)
ABSBIN=$(cd "$(dirname "$BIN")" && pwd)/$(basename "$BIN")
sweep=$(sed "s|^bin/rockdem |$ABSBIN |" "$T/sweep_cmd.txt")
if (cd "$T/tut" && eval "$sweep --set model.duration=0.5 -q" > sweep.txt 2>&1) &&
    [ -s "$T/tut/myrock_sweep.h5" ]
then judge readme-tutorial-sweep ok
else
    tail -3 "$T/tut/sweep.txt"
    judge readme-tutorial-sweep "the tutorial's sweep command fails: $sweep"
fi
if [ -n "$frag" ] && (cd "$T/tut" && eval "${frag/tools\//$REPO/tools/}" > frag.txt 2>&1) &&
    [ -s "$T/tut/myrock_fragility.png" ]
then judge readme-tutorial-fragility ok
else
    tail -3 "$T/tut/frag.txt" 2>/dev/null
    judge readme-tutorial-fragility "the tutorial's fragility command fails: '$frag'"
fi
exit $fail
