#!/usr/bin/env bash
# ctest docs.site: the manual builds with `mkdocs build --strict` (no broken
# link, no page missing from the nav's files, no warning), and the built site
# has every config key the loader knows (`taebp config --reference`) and every
# metric (`taebp metrics`). Skips visibly (exit 77) only when mkdocs is not
# installed (tools/setup.sh installs it).
# Usage: site_test.sh SOURCE_DIR TAEBP_BINARY WORK_DIR
set -euo pipefail
src=$1 taebp=$2 work=$3
fail() { echo "FAIL: $*" >&2; exit 1; }
if ! command -v mkdocs >/dev/null; then
  echo "SKIP: mkdocs is not installed (tools/setup.sh installs mkdocs and mkdocs-material)"
  exit 77
fi
rm -rf "$work" && mkdir -p "$work"
if ! (cd "$src" && mkdocs build --strict --site-dir "$work/site") >"$work/mkdocs.log" 2>&1; then
  if grep -q "Unrecognised theme name: 'material'" "$work/mkdocs.log"; then
    echo "SKIP: mkdocs-material is not installed (tools/setup.sh installs it)"
    exit 77
  fi
  cat "$work/mkdocs.log"
  fail "mkdocs build --strict failed"
fi
if grep -E 'WARNING|ERROR' "$work/mkdocs.log"; then fail "mkdocs warned"; fi
for page in index getting-started paper networks encounters reference/config reference/commands metrics \
            beyond/derivations beyond/major-road sumo-facts changelog; do
  [[ -s $work/site/$page.html ]] || fail "the site has no $page.html"
done
# Every key and every metric, as their sources list them, on the built pages.
/usr/bin/python3 - "$taebp" "$work/site" <<'PY'
import html, json, re, subprocess, sys
taebp, site = sys.argv[1], sys.argv[2]
def text(page):
    return html.unescape(re.sub(r"<[^>]+>", "", open("%s/%s" % (site, page), encoding="utf-8").read()))
keys = [k["key"] for k in json.loads(subprocess.run([taebp, "config", "--reference", "--format", "json"],
        check=True, capture_output=True, text=True).stdout)["keys"]]
metrics = [m["name"] for m in json.loads(subprocess.run([taebp, "metrics", "--print", "json"],
           check=True, capture_output=True, text=True).stdout)["metrics"]]
config, table = text("reference/config.html"), text("metrics.html")
missing = [k for k in keys if k not in config] + [m for m in metrics if m not in table]
if missing:
    sys.exit("FAIL: not on the site: %s" % ", ".join(missing))
print("the site has all %d config keys and %d metrics" % (len(keys), len(metrics)))
# Every link to a section of a page lands on a heading of that page (mkdocs
# 1.4 checks the pages, not their anchors).
import glob, os
ids, broken = {}, []
pages = sorted(glob.glob(site + "/**/*.html", recursive=True))
for p in pages:
    ids[os.path.normpath(p)] = set(re.findall(r'id="([^"]+)"', open(p, encoding="utf-8").read()))
for p in pages:
    for href in re.findall(r'href="([^"#:]*\.html)#([^"]+)"', open(p, encoding="utf-8").read()):
        target = os.path.normpath(os.path.join(os.path.dirname(p), href[0]))
        if target in ids and href[1] not in ids[target]:
            broken.append("%s -> %s#%s" % (os.path.relpath(p, site), href[0], href[1]))
if broken:
    sys.exit("FAIL: links to no heading: %s" % "; ".join(sorted(set(broken))))
PY
echo "mkdocs build --strict: ok ($(find "$work/site" -name '*.html' | wc -l) HTML pages)"
