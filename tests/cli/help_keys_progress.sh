#!/usr/bin/env bash
# Help, keys and progress: every subcommand has its own --help naming each of its options;
# `rockdem keys` lists exactly the keys --set accepts (checked both ways against the parser's
# own list); the long commands draw a progress line with an ETA on a terminal (script(1) gives
# them one) and nothing when stderr is a pipe or with -q.
set -eu
BIN=${RD_BIN:-bin/rockdem}; T=${RD_TMP:-$(mktemp -d)}/help; mkdir -p "$T"
need() { # subcommand, then the options its page must name
    local sub=$1; shift
    "$BIN" "$sub" --help > "$T/$sub.txt"
    head -1 "$T/$sub.txt" | grep -q "^usage: rockdem $sub" || { echo "$sub --help: no usage line"; exit 1; }
    for o in "$@"; do grep -q -- "$o" "$T/$sub.txt" || { echo "$sub --help lacks $o"; exit 1; }; done
}
need run -o --set -q
need check --set
need reference -o --set
need threshold --engine --lo --hi --rtol --steps --frequencies --set -q
need restitution --target --theta0 --set -q
need study --set -q
need sweep --axis --records --scales --directions -j --keep-runs -o -q
need keys --tsv
"$BIN" help sweep | cmp -s - "$T/sweep.txt"
"$BIN" sweep scenarios/default.dat --help | cmp -s - "$T/sweep.txt"   # --help anywhere
"$BIN" --help | grep -q "rockdem SUBCOMMAND --help"
# keys: the table's keys are the parser's keys
"$BIN" keys --tsv | tail -n +2 | cut -f1 > "$T/keys"
[ "$(wc -l < "$T/keys")" -ge 30 ]
for k in $(grep -v '^block\.' "$T/keys"); do
    if "$BIN" check scenarios/default.dat --set "$k=1" 2>&1 | grep -q "unknown key"; then
        echo "rockdem keys lists $k, which --set rejects"; exit 1; fi
done
for f in $(grep '^block\.' "$T/keys" | sed 's/^block\.<name>\.//'); do
    if "$BIN" check scenarios/default.dat --set "block.cask.$f=1" 2>&1 | grep -q "unknown key"; then
        echo "rockdem keys lists block.<name>.$f, which --set rejects"; exit 1; fi
done
for s in contact model motion output reference; do
    "$BIN" check scenarios/default.dat --set "$s.no-such-key=1" 2>&1 | sed -n 's/.*(expected \(.*\))$/\1/p' |
        tr ',' '\n' | sed 's/^ *//' > "$T/parser_$s"
    [ -s "$T/parser_$s" ]
    while read -r k; do grep -qx "$k" "$T/keys" || { echo "--set accepts $k; rockdem keys omits it"; exit 1; }; done < "$T/parser_$s"
done
"$BIN" check scenarios/default.dat --set block.cask.no-such=1 2>&1 | sed -n 's/.*(expected block\.cask\.\(.*\))$/\1/p' |
    sed 's/,\| or /\n/g' | sed 's/^ *//;/^$/d' | while read -r f; do
    grep -qx "block.<name>.$f" "$T/keys" || { echo "--set accepts block.<name>.$f; rockdem keys omits it"; exit 1; }; done
"$BIN" run scenarios/default.dat --set help | grep -q "^motion.amplitude "
# progress: on a terminal only, and not with -q
short=(--set model.duration=2.5 --set output.interval=0.05)
"$BIN" run scenarios/default.dat "${short[@]}" -o "$T/p.h5" 2> "$T/pipe.err" > /dev/null
if grep -q "ETA" "$T/pipe.err"; then echo "unexpected: ETA $T/pipe.err"; exit 1; fi
command -v script > /dev/null || { echo "skipped: script(1) (util-linux) not installed: no terminal for the progress check"; exit 77; }
script -qec "$BIN run scenarios/default.dat ${short[*]} -o $T/p.h5" /dev/null > "$T/tty.txt" 2>&1
tr '\r' '\n' < "$T/tty.txt" | grep -q "^run: t = .* s (.*%), .* elapsed, ETA "
script -qec "$BIN run scenarios/default.dat ${short[*]} -q -o $T/p.h5" /dev/null > "$T/ttyq.txt" 2>&1
if grep -q "ETA" "$T/ttyq.txt"; then echo "unexpected: ETA $T/ttyq.txt"; exit 1; fi
script -qec "$BIN threshold tests/cli/data/sweep_brick.dat --engine dem --rtol 0.05 --steps 6" /dev/null > "$T/th.txt" 2>&1
tr '\r' '\n' < "$T/th.txt" | grep -q "^threshold: run [0-9]* of ~[0-9]*, t = .*ETA"
echo "help pages, keys and progress ok ($(wc -l < "$T/keys") keys)"
