#!/usr/bin/env bash
# The pytest suite of the Python binding (tests/python/, tools/rockdem over build/librockdem.so)
# under /usr/bin/python3: one "CHECK name" or "FAIL name: why" line per test case (pytest's JUnit
# report read back), so tests/run.sh counts each case; a pytest skip prints "SKIP: name: why"
# (not counted), an expected failure "XFAIL: name". Skipped as a whole (exit 77) only when
# pytest is not installed (Debian python3-pytest, tools/install-deps.sh).
set -u
T=${RD_TMP:-$(mktemp -d)}/pytest; mkdir -p "$T"
PY=/usr/bin/python3
$PY -c 'import pytest' 2>/dev/null || { echo "SKIP: pytest is not installed (Debian python3-pytest)"; exit 77; }
LIB=${RD_BUILD:-build}/librockdem.so
[ -f "$LIB" ] || { echo "FAIL pytest: no $LIB"; exit 1; }
export ROCKDEM_LIB=$(cd "$(dirname "$LIB")" && pwd)/librockdem.so
export ROCKDEM_BIN=$(cd "$(dirname "${RD_BIN:-bin/rockdem}")" && pwd)/$(basename "${RD_BIN:-bin/rockdem}")
# a sanitizer build (make asan): Python is not instrumented, so its runtime is loaded first
if nm -D "$LIB" 2>/dev/null | grep -q __asan_init; then
    export LD_PRELOAD="$(${CC:-cc} -print-file-name=libasan.so) $(${CC:-cc} -print-file-name=libubsan.so)"
    export ASAN_OPTIONS=detect_leaks=0${ASAN_OPTIONS:+:$ASAN_OPTIONS}
fi
$PY -m pytest -q -p no:cacheprovider --basetemp="$T/tmp" --junitxml="$T/junit.xml" tests/python \
    > "$T/pytest.txt" 2>&1
rc=$?
[ -f "$T/junit.xml" ] || { tail -20 "$T/pytest.txt"; echo "FAIL pytest: no report (exit $rc)"; exit 1; }
$PY - "$T/junit.xml" <<'PY'
import sys
import xml.etree.ElementTree as ET
for case in ET.parse(sys.argv[1]).iter("testcase"):
    name = "%s::%s" % (case.get("classname", "").rsplit(".", 1)[-1], case.get("name"))
    bad = case.find("failure") if case.find("failure") is not None else case.find("error")
    skip = case.find("skipped")
    if bad is not None:
        why = (bad.get("message") or "").splitlines()
        print("FAIL %s: %s" % (name, why[0][:200] if why else "failed"))
    elif skip is not None and skip.get("type") == "pytest.xfail":
        print("XFAIL: %s (%s)" % (name, skip.get("message", "")))
    elif skip is not None:
        print("SKIP: %s: %s" % (name, skip.get("message", "")))
    else:
        print("CHECK " + name)
PY
tail -1 "$T/pytest.txt"
[ "$rc" -eq 0 ]
