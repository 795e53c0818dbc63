#!/usr/bin/env bash
# ctest readme.catches_a_stale_figure: tools/readme-check fails on a page
# (README.md or docs/**/*.md) whose figure no longer matches its command (one
# number changed), naming the figure, the page, the page's value and the fresh
# one; the shipped pages pass the same figure. Usage: stale_test.sh SOURCE_DIR
# BUILD_DIR WORK_DIR
set -euo pipefail
src=$1 build=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }
check=(/usr/bin/python3 "$src/tools/readme-check" --build "$build" --only "stop distance 1.7")

"${check[@]}" >"$work/shipped.out" 2>&1 || { cat "$work/shipped.out"; fail "the shipped pages fail"; }
grep -q "^ok     stop distance 1.7" "$work/shipped.out" || fail "the figure was not checked"

# The page that holds the figure, found by its text (so the test follows it
# when it moves between pages).
page=$(cd "$src" && grep -l 'SUMO reports [0-9.]* collisions per encounter' README.md docs/*.md docs/*/*.md | head -n 1)
[[ -n $page ]] || fail "no page holds the figure"
# One number changed: the stop-1.7 No Trust collision rate, read from the
# page itself (so the test does not go stale with the figure).
rate=$(grep -o 'SUMO reports [0-9.]* collisions per encounter' "$src/$page" | head -n 1 | awk '{print $3}')
other=$(awk -v r="$rate" 'BEGIN { printf "%.3f", r + 0.001 }')
sed "s/SUMO reports $rate collisions per encounter/SUMO reports $other collisions per encounter/" \
  "$src/$page" >"$work/page.md"
set +e
"${check[@]}" --page "$page=$work/page.md" >"$work/stale.out" 2>&1
code=$?
set -e
cat "$work/stale.out"
[[ $code -eq 1 ]] || fail "exit code $code, expected 1"
grep -q "STALE  stop distance 1.7.*, $page" "$work/stale.out" || fail "the stale figure and its page are not named"
grep -q "no_trust: the page says '$other', now '$rate'" "$work/stale.out" || fail "values not shown"

# A printed table changed in one cell fails too: the upper end of that rate's
# interval in the printout.
cell=$(grep -o "$rate \[[0-9.]*,[0-9.]*\] th 0.200 !" "$src/$page" | head -n 1)
[[ -n $cell ]] || fail "the printed table row is not in $page"
hi=$(echo "$cell" | sed 's/.*,\([0-9.]*\)\].*/\1/')
hi2=$(awk -v r="$hi" 'BEGIN { printf "%.3f", r + 0.001 }')
sed "s/${cell//[/\\[}/${cell/$hi/$hi2}/" "$src/$page" >"$work/page2.md"
cmp -s "$src/$page" "$work/page2.md" && fail "the table cell was not changed"
set +e
"${check[@]}" --page "$page=$work/page2.md" >"$work/stale2.out" 2>&1
code=$?
set -e
[[ $code -eq 1 ]] || { cat "$work/stale2.out"; fail "a changed table cell passed (exit $code)"; }

# A figure whose text is on no page any more is stale too (README.md and
# every page searched): the figure's sentence removed from its page.
grep -v 'SUMO reports' "$src/$page" >"$work/page3.md"
set +e
"${check[@]}" --page "$page=$work/page3.md" >"$work/stale3.out" 2>&1
code=$?
set -e
[[ $code -eq 1 ]] || { cat "$work/stale3.out"; fail "a figure on no page passed (exit $code)"; }
grep -q "STALE  stop distance 1.7[^,]*: its text is on no page" "$work/stale3.out" || fail "a missing figure is not named"
echo "readme-check: the shipped pages pass; a changed number, a changed table cell and a missing figure fail ($page)"
