#!/usr/bin/env bash
# ctest readme.catches_a_stale_figure: tools/readme-check fails on a README
# whose figure no longer matches its command (one number changed), naming the
# figure, the README's value and the fresh one; the shipped README passes the
# same figure. Usage: stale_test.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -euo pipefail
src=$1 build=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }
check=(/usr/bin/python3 "$src/tools/readme-check" --build "$build" --only "stop distance 1.7")

"${check[@]}" >"$work/shipped.out" 2>&1 || { cat "$work/shipped.out"; fail "the shipped README fails"; }
grep -q "^ok     stop distance 1.7" "$work/shipped.out" || fail "the figure was not checked"

# One number changed: the stop-1.7 No Trust collision rate.
grep -q "SUMO reports 0.461 collisions per encounter" "$src/README.md" || fail "the figure is not in README.md"
sed 's/SUMO reports 0.461 collisions per encounter/SUMO reports 0.462 collisions per encounter/' \
  "$src/README.md" >"$work/README.md"
set +e
"${check[@]}" --readme "$work/README.md" >"$work/stale.out" 2>&1
code=$?
set -e
cat "$work/stale.out"
[[ $code -eq 1 ]] || fail "exit code $code, expected 1"
grep -q "STALE  stop distance 1.7" "$work/stale.out" || fail "the stale figure is not named"
grep -q "no_trust: the README says '0.462', now '0.461'" "$work/stale.out" || fail "values not shown"

# A printed table changed in one cell fails too.
sed 's/0.461 \[0.419,0.503\] th 0.200 !/0.461 [0.419,0.504] th 0.200 !/' "$src/README.md" >"$work/README2.md"
set +e
"${check[@]}" --readme "$work/README2.md" >"$work/stale2.out" 2>&1
code=$?
set -e
[[ $code -eq 1 ]] || { cat "$work/stale2.out"; fail "a changed table cell passed (exit $code)"; }
echo "readme-check: the shipped README passes, a changed number and a changed table cell fail"
