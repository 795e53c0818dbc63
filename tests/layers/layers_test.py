#!/usr/bin/env python3
"""The house's layers, checked on the includes: no arrow runs back up; no
source file of the tree over 600 lines (C++, Python, the scripts in tools/,
CMake), none in sweep/ or controller/ (nor report/src/report.cc) over 500; and
one writer: no file outside rundir/src/ renames a file into place (every file
taebp puts in place goes through rundir/'s synced writer, fsync included:
rundir/synced_file.h's SyncedWriter, PutInPlace, PutFolderInPlace).

Each library folder may include its own headers and those of the layers listed
for it below, nothing else; libsumo and libtraci only in the SUMO adapter.
Fails naming the file, the line and the rule it breaks (a newcomer who adds
`#include "taebp/config/config.h"` to junction/ learns why here)."""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# Bottom up (README "Layout"). junction/ is right of way only: no config, no report.
# base/ is the floor under all: numbers as text, exit codes, the config error;
# it includes nothing of the project. The program (cli/) stands on top.
ALLOWED = {
    "base": {"base"},
    "persuasion": {"persuasion", "base"},
    "config": {"config", "persuasion", "base"},
    "rundir": {"rundir", "config", "base"},  # config: the policy table only
    "report": {"report", "config", "persuasion", "base"},  # config: the policy table only
    "encounter": {"encounter", "persuasion", "config", "report", "base"},
    "junction": {"junction", "encounter", "persuasion", "base"},
    "scenario": {"scenario", "rundir", "config", "persuasion", "base"},  # rundir: the synced writer
    "controller": {"controller", "junction", "encounter", "scenario", "report", "rundir",
                   "config", "persuasion", "base"},
    "runner": {"runner", "controller", "encounter", "scenario", "report", "rundir", "config",
               "persuasion", "base"},
    "sweep": {"sweep", "runner", "controller", "scenario", "report", "rundir", "config",
              "persuasion", "base"},
    "cli": {"cli", "sweep", "runner", "controller", "junction", "encounter", "scenario", "report", "rundir", "config",
            "persuasion", "base"},
}
# A layer that may include only some headers of another (report/ reads the
# policy table of config/, not the config).
ONLY = {("report", "config"): {"taebp/config/policies.h"},
        ("rundir", "config"): {"taebp/config/policies.h"},
        ("scenario", "rundir"): {"taebp/rundir/synced_file.h"}}
SUMO_ADAPTER = {"controller/src/sumo_adapter.cc", "controller/src/sumo_adapter_libtraci.cc"}
# Files that do one job (issue 27): no source file in these folders, and not
# these files, over MAX_LINES lines.
MAX_LINES = 500
SIZE_FOLDERS = ("sweep", "controller")
SIZE_FILES = ("report/src/report.cc",)
# Rooms of a readable size (issue 46): no source file anywhere over
# MAX_ANY_LINES lines. Sources: C++ (.h, .cc, .inc, .cpp), Python (.py), CMake
# (CMakeLists.txt, .cmake), shell (.sh) and the executable scripts of tools/
# and tests/ (a #! first line); everything outside build trees and .git.
MAX_ANY_LINES = 600
SOURCE_SUFFIXES = (".h", ".cc", ".inc", ".cpp", ".py", ".cmake", ".sh")
SKIP_DIRS = {".git", "node_modules", "__pycache__", "site"}
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]')
# The one writer: a rename puts a file in place; only rundir/src/ may.
WRITER_FOLDER = "rundir/src/"
RENAME = re.compile(r'(\bfs::rename|std::filesystem::rename|::rename(at2?)?|\brename(at2?)?)\s*\(')
WRITER_SCAN = ("base", "persuasion", "config", "rundir", "report", "encounter", "junction", "scenario",
               "controller", "runner", "sweep", "cli", "python/src", "bench")


def check_includes(problems):
    """Each layer includes only what it stands on; returns the files read."""
    checked = 0
    for layer, allowed in ALLOWED.items():
        for base, _, files in os.walk(os.path.join(ROOT, layer)):
            for name in files:
                if not name.endswith((".h", ".cc", ".inc")):
                    continue
                path = os.path.join(base, name)
                rel = os.path.relpath(path, ROOT)
                checked += 1
                with open(path, encoding="utf-8") as f:
                    for n, line in enumerate(f, 1):
                        m = INCLUDE.match(line)
                        if m:
                            check_include(layer, allowed, rel, n, m.group(1), problems)
    return checked


def check_include(layer, allowed, rel, n, target, problems):
    parts = target.split("/")
    if parts[0] == "taebp" and len(parts) > 2 and parts[1] not in allowed:
        problems.append("%s:%d: %s/ includes %s (allowed: %s)" % (
            rel, n, layer, target, ", ".join(sorted(allowed))))
    only = ONLY.get((layer, parts[1] if len(parts) > 2 else ""))
    if parts[0] == "taebp" and only is not None and target not in only:
        problems.append("%s:%d: %s/ includes %s (of %s/ only %s)" % (
            rel, n, layer, target, parts[1], ", ".join(sorted(only))))
    if parts[0] in ("libsumo", "libtraci") and rel not in SUMO_ADAPTER:
        problems.append("%s:%d: %s outside the SUMO adapter (%s)" % (
            rel, n, target, ", ".join(sorted(SUMO_ADAPTER))))


def check_writer(problems):
    """Only rundir/src/ renames a file into place."""
    renames = 0
    for folder in WRITER_SCAN:
        for base, _, files in os.walk(os.path.join(ROOT, folder)):
            for name in files:
                if not name.endswith((".h", ".cc", ".inc", ".cpp")):
                    continue
                rel = os.path.relpath(os.path.join(base, name), ROOT)
                with open(os.path.join(ROOT, rel), encoding="utf-8") as f:
                    for n, line in enumerate(f, 1):
                        code = line.split("//", 1)[0]
                        if not RENAME.search(code):
                            continue
                        if rel.startswith(WRITER_FOLDER):
                            renames += 1
                        else:
                            problems.append(
                                "%s:%d: renames a file into place outside %s: use rundir/"
                                "synced_file.h (SyncedWriter, PutInPlace, PutFolderInPlace), "
                                "which fsyncs first" % (rel, n, WRITER_FOLDER))
    if renames == 0:
        problems.append("no rename found in %s: the writer rule's pattern is stale" % WRITER_FOLDER)


def line_count(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        return sum(1 for _ in f)


def is_script(path):
    with open(path, "rb") as f:
        return f.read(2) == b"#!"


def check_sizes(problems):
    """The 500-line rule of sweep/ and controller/, the 600-line rule of the tree."""
    sized = 0
    for rel in SIZE_FILES + tuple(
            os.path.relpath(os.path.join(base, name), ROOT)
            for folder in SIZE_FOLDERS for base, _, files in os.walk(os.path.join(ROOT, folder))
            for name in files if name.endswith((".h", ".cc", ".inc"))):
        sized += 1
        lines = line_count(os.path.join(ROOT, rel))
        if lines > MAX_LINES:
            problems.append("%s: %d lines, over %d: split it into files that do one job each" % (
                rel, lines, MAX_LINES))
    if sized < 20:
        problems.append("only %d files checked for size: wrong root?" % sized)
    sized_any = 0
    for base, dirs, files in os.walk(ROOT):
        dirs[:] = [d for d in dirs if d not in SKIP_DIRS and not d.startswith("build")]
        for name in files:
            path = os.path.join(base, name)
            if not (name.endswith(SOURCE_SUFFIXES) or name == "CMakeLists.txt" or is_script(path)):
                continue
            sized_any += 1
            lines = line_count(path)
            if lines > MAX_ANY_LINES:
                problems.append("%s: %d lines, over %d: split it into files that do one job "
                                "each" % (os.path.relpath(path, ROOT), lines, MAX_ANY_LINES))
    if sized_any < 300:
        problems.append("only %d source files checked for the %d-line rule: wrong root?" % (
            sized_any, MAX_ANY_LINES))
    return sized_any


def main():
    problems = []
    checked = check_includes(problems)
    check_writer(problems)
    sized_any = check_sizes(problems)
    if checked < 50:
        problems.append("only %d source files found under %s: wrong root?" % (checked, ROOT))
    for p in problems:
        print(p, file=sys.stderr)
    print("layers: %d files (%d sized), %d problems" % (checked, sized_any, len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
