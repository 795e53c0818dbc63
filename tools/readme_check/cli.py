"""The command line (`tools/readme-check --help`): the tiers chosen, the
pages read, every figure found and checked, the exit code (0 ok, 1 stale,
2 failed)."""

import argparse
import os
import shutil
import sys
import tempfile

from . import __doc__ as DOC
from .context import Context, ROOT, load_pages
from .figure import check
from .figures import FIGURES


TIERS = ["fast", "sweeps", "studies", "beyond", "timings", "bench"]


def parser():
    ap = argparse.ArgumentParser(prog="tools/readme-check", description=DOC.split("\n")[0])
    ap.add_argument("--tier", action="append", choices=TIERS)
    ap.add_argument("--readme", metavar="FILE", help="read FILE in place of README.md")
    ap.add_argument("--page", action="append", default=[], metavar="PAGE=FILE",
                    help="read FILE in place of PAGE (e.g. docs/paper.md=/tmp/copy.md)")
    ap.add_argument("--build", default=os.environ.get("TAEBP_BUILD_DIR") or os.path.join(ROOT, "build"))
    ap.add_argument("--keep", metavar="DIR", help="run in DIR and keep it (default: a temporary directory)")
    ap.add_argument("--resume", action="store_true",
                    help="with --keep: do not clear DIR; a sweep there resumes from its journal")
    ap.add_argument("--list", action="store_true", help="print the table of figures and commands")
    ap.add_argument("--only", metavar="TEXT", help="only the figures whose name contains TEXT")
    return ap


def usable(args):
    """The build to run and the --keep folder as asked, or a message (exit 2) why not."""
    build = os.path.abspath(args.build)
    if not os.access(os.path.join(build, "taebp"), os.X_OK):
        print("tools/readme-check: %s/taebp is not built (tools/test or tools/run builds it)" % build,
              file=sys.stderr)
        return None
    if args.resume and not (args.keep and os.path.isdir(args.keep)):
        print("tools/readme-check: --resume needs --keep DIR naming a directory an earlier "
              "--keep left (%s)" % (args.keep or "no --keep given"), file=sys.stderr)
        return None
    return build


def check_all(ctx, figures, pages):
    """Every figure checked on every page that holds it: {ok, stale, failed: count}."""
    counts = {"ok": 0, "stale": 0, "failed": 0}
    for f in figures:
        found = [(p, f.pattern.search(pages[p])) for p in ([f.page] if f.page else pages)]
        found = [(p, m) for p, m in found if m]
        if not found:
            print("STALE  %s: its text is on no page (%s; pattern %s)"
                  % (f.name, f.page or "README.md, docs/**/*.md", f.pattern.pattern[:120]))
            counts["stale"] += 1
            continue
        for page, m in found:
            counts[check(ctx, f, page, m)] += 1
    return counts


def main(argv=None):
    args = parser().parse_args(argv)
    tiers = args.tier or ["fast"]
    replaced = dict(p.split("=", 1) for p in args.page)
    if args.readme:
        replaced["README.md"] = args.readme
    pages = load_pages(replaced)
    figures = [f for f in FIGURES if f.tier in tiers and (not args.only or args.only in f.name)]
    if args.list:
        for f in FIGURES:
            print("%-8s %-52s %s" % (f.tier, f.name, " && ".join(f.commands) or "(static)"))
        return 0
    build = usable(args)
    if build is None:
        return 2
    work = args.keep or tempfile.mkdtemp(prefix="readme-check.")
    if args.keep and not args.resume:
        shutil.rmtree(work, ignore_errors=True)
        os.makedirs(work)
    ctx = Context(build, os.path.abspath(work), pages)
    try:
        counts = check_all(ctx, figures, pages)
    finally:
        if not args.keep:
            shutil.rmtree(work, ignore_errors=True)
    print("%d figures checked (%s) on %d pages: %d stale, %d failed"
          % (len(figures), ", ".join(tiers), len(pages), counts["stale"], counts["failed"]))
    return 2 if counts["failed"] else (1 if counts["stale"] else 0)
