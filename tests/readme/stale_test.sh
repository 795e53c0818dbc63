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

# One number changed: the stop-1.7 No Trust collision rate, read from the
# README itself (so the test does not go stale with the figure).
rate=$(grep -o 'SUMO reports [0-9.]* collisions per encounter' "$src/README.md" | head -n 1 | awk '{print $3}')
[[ -n $rate ]] || fail "the figure is not in README.md"
other=$(awk -v r="$rate" 'BEGIN { printf "%.3f", r + 0.001 }')
sed "s/SUMO reports $rate collisions per encounter/SUMO reports $other collisions per encounter/" \
  "$src/README.md" >"$work/README.md"
set +e
"${check[@]}" --readme "$work/README.md" >"$work/stale.out" 2>&1
code=$?
set -e
cat "$work/stale.out"
[[ $code -eq 1 ]] || fail "exit code $code, expected 1"
grep -q "STALE  stop distance 1.7" "$work/stale.out" || fail "the stale figure is not named"
grep -q "no_trust: the README says '$other', now '$rate'" "$work/stale.out" || fail "values not shown"

# A printed table changed in one cell fails too: the upper end of that rate's
# interval in the printout.
cell=$(grep -o "$rate \[[0-9.]*,[0-9.]*\] th 0.200 !" "$src/README.md" | head -n 1)
[[ -n $cell ]] || fail "the printed table row is not in README.md"
hi=$(echo "$cell" | sed 's/.*,\([0-9.]*\)\].*/\1/')
hi2=$(awk -v r="$hi" 'BEGIN { printf "%.3f", r + 0.001 }')
sed "s/${cell//[/\\[}/${cell/$hi/$hi2}/" "$src/README.md" >"$work/README2.md"
cmp -s "$src/README.md" "$work/README2.md" && fail "the table cell was not changed"
set +e
"${check[@]}" --readme "$work/README2.md" >"$work/stale2.out" 2>&1
code=$?
set -e
[[ $code -eq 1 ]] || { cat "$work/stale2.out"; fail "a changed table cell passed (exit $code)"; }
echo "readme-check: the shipped README passes, a changed number and a changed table cell fail"
