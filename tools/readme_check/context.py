"""The scratch directory the pages' commands run in (Context: each command run
once, its output kept), and the pages read (README.md, docs/**/*.md)."""

import csv
import glob
import json
import os
import subprocess
import time


# The repository: tools/readme_check/ is two folders below it.
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


class Context:
    """The scratch directory the commands run in, with cached results."""

    def __init__(self, build, work, pages):
        self.build = build
        self.work = work
        self.pages = pages
        self.done = {}
        links = {name: os.path.join(ROOT, name) for name in ("configs", "tools", "sumo_net", "python")}
        links["build"] = build
        for name, target in links.items():
            link = os.path.join(work, name)
            if os.path.islink(link):  # --resume: a kept directory
                os.remove(link)
            os.symlink(target, link)
        os.makedirs(os.path.join(work, "docs", "img"), exist_ok=True)
        os.makedirs(os.path.join(work, "results"), exist_ok=True)

    def run(self, command, failed_tasks=False):
        """Runs a README command (bash, in the scratch directory) once; its
        CompletedProcess with .seconds (wall time). failed_tasks: a sweep
        whose failed tasks the figure counts itself (exit code 1 accepted;
        ssm_aborts() checks why they failed)."""
        if command not in self.done:
            env = dict(os.environ, TAEBP_BUILD_DIR=self.build)
            env.setdefault("SUMO_HOME", "/usr/share/sumo")
            env.pop("DISPLAY", None)
            start = time.monotonic()
            r = subprocess.run(["bash", "-c", command], cwd=self.work, capture_output=True,
                               text=True, env=env)
            r.seconds = time.monotonic() - start
            if r.returncode != 0 and not (failed_tasks and r.returncode == 1):
                raise CommandFailed("%s: exit code %d\n%s" % (command, r.returncode,
                                                             r.stderr[-2000:]))
            self.done[command] = r
        return self.done[command]

    def path(self, *rel):
        return os.path.join(self.work, *rel)

    def json(self, *rel):
        with open(self.path(*rel), encoding="utf-8") as f:
            return json.load(f)

    def csv(self, *rel):
        with open(self.path(*rel), newline="", encoding="utf-8") as f:
            return list(csv.DictReader(f))


class CommandFailed(Exception):
    pass


def load_pages(replaced):
    """{page: text}: README.md and docs/**/*.md (not symbolic links), each
    read from `replaced[page]` when given there."""
    names = ["README.md"] + sorted(
        os.path.relpath(p, ROOT) for p in glob.glob(os.path.join(ROOT, "docs", "**", "*.md"), recursive=True)
        if not os.path.islink(p))
    unknown = sorted(set(replaced) - set(names))
    if unknown:
        raise SystemExit("tools/readme-check: no such page: %s (pages: README.md, docs/**/*.md)" % ", ".join(unknown))
    pages = {}
    for name in names:
        with open(replaced.get(name, os.path.join(ROOT, name)), encoding="utf-8") as f:
            pages[name] = f.read()
    return pages
