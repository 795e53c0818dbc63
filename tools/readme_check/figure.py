"""A figure of the pages (Figure: its name, tier, pattern, commands, values)
and the check of one figure where a page holds it."""

import re

from .context import CommandFailed


def flexible(pattern):
    """A pattern's literal spaces (outside [...]) match any whitespace run, so
    that re-wrapping a README paragraph does not break its figure."""
    out, in_class, escaped = [], False, False
    for ch in pattern:
        if escaped:
            out.append(ch)
            escaped = False
        elif ch == "\\":
            out.append(ch)
            escaped = True
        elif ch == "[":
            in_class = True
            out.append(ch)
        elif ch == "]":
            in_class = False
            out.append(ch)
        elif ch == " " and not in_class:
            out.append(r"\s+")
        else:
            out.append(ch)
    return "".join(out)


def same(readme_text, value):
    """Equal figures; a one-line value ignores how the README wraps it."""
    if "\n" in value:
        return readme_text == value
    return " ".join(readme_text.split()) == " ".join(value.split())


class Figure:
    def __init__(self, name, tier, pattern, commands, values, flags=re.S, page=None,
                 failed_tasks=False):
        self.name = name
        self.tier = tier
        # A picture's path as README.md writes it (docs/img/) or a site page (img/, ../img/).
        pattern = pattern.replace("docs/img/", r"(?:docs/|(?:\.\./)*)img/")
        self.pattern = re.compile(flexible(pattern), flags)
        self.commands = commands
        self.values = values  # (ctx, match) -> {group: expected text}
        self.page = page  # the page that holds it, or None: every page that matches
        # A sweep whose failed tasks the figure counts itself (Context.run).
        self.failed_tasks = failed_tasks


def check(ctx, f, page, m):
    """Checks one figure where it was found; prints ok/STALE/FAILED; returns
    'ok', 'stale' or 'failed'."""
    where = "%s, %s" % (f.name, page)
    missing = [c for c in f.commands if c not in ctx.pages[page]]
    if missing:
        print("STALE  %s: the page does not show the command(s) %s" % (where, missing))
        return "stale"
    try:
        for c in f.commands:
            ctx.run(c, failed_tasks=f.failed_tasks)
        expected = f.values(ctx, m)
    except (CommandFailed, OSError, KeyError, ValueError, IndexError) as e:
        print("FAILED %s: %s" % (where, e))
        return "failed"
    wrong = [(g, m.group(g), v) for g, v in expected.items() if not same(m.group(g), v)]
    if wrong:
        print("STALE  %s (%s):" % (where, " && ".join(f.commands) or "static"))
        for g, said, fresh in wrong:
            print("         %s: the page says %r, now %r" % (g, said, fresh))
        return "stale"
    print("ok     %s" % where)
    return "ok"
