"""Tier fast, checks that run nothing: the pages against the repository
(configs' comments, tools/setup.sh's packages, tools/bench's targets, the
layout's configs, README's links and five steps)."""

import glob
import os
import re

from .context import ROOT


def times_consistent(ctx, m):
    """The sweep times in the README and in the configs' header comments agree."""
    out = {}
    for name in ("trust", "mismatch", "penetration"):
        with open(os.path.join(ROOT, "configs", "sweep_%s.yaml" % name), encoding="utf-8") as f:
            c = re.search(r"about (\d+) s with --jobs 2", f.read())
        out[name] = c.group(1) if c else "(no 'about N s with --jobs 2' in the config)"
    return out


def dependencies(ctx, m):
    with open(os.path.join(ROOT, "tools", "setup.sh"), encoding="utf-8") as f:
        text = f.read()
    listed = " ".join(re.search(name + r"=\((.*?)\)", text, re.S).group(1)
                      for name in ("TAEBP_PACKAGES", "TAEBP_OPTIONAL_PACKAGES"))
    for tool in ("fuzz", "docs"):  # what these install on demand
        with open(os.path.join(ROOT, "tools", tool), encoding="utf-8") as f:
            listed += " " + re.search(r"taebp_missing_packages ([^)]*)\)", f.read()).group(1)
    packages = sorted(set(re.sub(r"#.*", "", listed).split()))
    table = m.group("table")
    documented = sorted(set(re.findall(r"`([a-z0-9][a-z0-9+.-]+)`", "\n".join(
        l.split("|")[1] for l in table.splitlines() if l.startswith("| `")))))
    return {"table": table if documented == packages else
            "packages of tools/setup.sh %s vs the table's %s" % (packages, documented)}


def bench_targets(ctx, m):
    with open(os.path.join(ROOT, "tools", "bench"), encoding="utf-8") as f:
        text = f.read()
    return {"overhead": re.search(r"overhead_target=([\d.]+)", text).group(1),
            "grid": re.search(r"grid_target=([\d.]+)", text).group(1),
            "osm": re.search(r"osm_target=([\d.]+)", text).group(1),
            "sweep": re.search(r"sweep_target=([\d.]+)", text).group(1)}


def logical_commands(block):
    """A shell block's commands: continued lines joined, comments dropped."""
    joined = re.sub(r"\\\n\s*", " ", block)
    out = []
    for line in joined.splitlines():
        line = re.sub(r"\s+# .*$", "", line).strip()
        if line and not line.startswith("#"):
            out.append(" ".join(line.split()))
    return out


def five_steps(ctx, m):
    """README's five steps are commands of the runnable block of Getting started
    (which the figure "your own network, step by step" runs and checks)."""
    full = re.search(r"## Your own network, step by step.*?```sh\n(.*?)```",
                     ctx.pages["docs/getting-started.md"], re.S)
    if not full:
        return {"block": "(docs/getting-started.md has no 'Your own network, step by step' block)"}
    known = logical_commands(full.group(1))
    # The block there writes the config with a heredoc; its lines are not commands.
    extra = [c for c in logical_commands(m.group("block")) if c not in known]
    return {"block": m.group("block") if not extra else
            "commands that are not Getting started's: %s" % extra}


def braces(text):
    """Shell brace expansion of the names in a text: a_{x,y}.yaml -> a_x.yaml a_y.yaml."""
    m = re.search(r"\{([^{}]*)\}", text)
    if not m:
        return {text}
    return set().union(*(braces(text[:m.start()] + alt + text[m.end():]) for alt in m.group(1).split(",")))


def layout_configs(ctx, m):
    """The layout's configs/ line names every config the repository ships."""
    named = set()
    for word in re.findall(r"[\w{},/*]+\.yaml", m.group("configs")):
        named |= braces(word)
    shipped = sorted(os.path.relpath(p, os.path.join(ROOT, "configs"))
                     for p in glob.glob(os.path.join(ROOT, "configs", "**", "*.yaml"), recursive=True))
    missing = [c for c in shipped if c not in named]
    return {"configs": m.group("configs") if not missing else "configs not named: %s" % missing}


def readme_links(ctx, m):
    """Every relative link of README.md names a file of the repository."""
    broken = []
    for target in re.findall(r"\]\(([^)\s]+)\)", ctx.pages["README.md"]):
        if re.match(r"^[a-z]+:", target) or target.startswith("#"):
            continue
        if not os.path.exists(os.path.join(ROOT, target.split("#")[0])):
            broken.append(target)
    return {"table": m.group("table") if not broken else "broken links: %s" % broken}
