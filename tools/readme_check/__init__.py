"""Checks that the pages' figures are what the commands next to them give.

The pages are README.md and every markdown page of the site, docs/**/*.md
(symbolic links such as docs/changelog.md are not pages of their own). Every
figure of the pages (a number, a table, a printed block, a picture) has an
entry in FIGURES (figures.py): the text that holds it (a regular expression
whose named groups are the figures), the commands that regenerate it (each must
appear verbatim on the page that holds the figure), how the values are
computed from the commands' outputs, and optionally the page it is on
(page="docs/x.md"; without it every page is searched, and every page that
holds the text is checked; none holding it is STALE). The commands run as
written, in a scratch directory that looks like the repository (configs/,
build/, tools/, sumo_net/ linked; results/ and docs/img/ fresh), so
`build/taebp run configs/paper.yaml` writes results/paper/ there. A figure
that differs is reported as STALE with the page, its text and the fresh
value, and the exit code is 1. A picture is written docs/img/NAME.png on
README.md and img/NAME.png (../img/ from a subfolder) on the site's pages.

Tiers (--tier, several allowed; default: fast):
  fast     runs of configs/paper.yaml, the theory, the LP, the snapshot, and
           static checks (about a minute; ctest readme.fast)
  sweeps   the three shipped sweeps and their plots (a few minutes on 2
           cores; by hand, not in every CI run)
  studies  Table I over 40 seeds, the grid, efficiency and city studies, the
           OSM example (opt-in: tens of minutes; not run by ctest)
  beyond   the studies beyond the paper (configs/learned_trust.yaml,
           dynamic_trust.yaml, noise.yaml) and their plots (opt-in: about
           5 minutes on 2 cores; not run by ctest)
  timings  wall times the pages state (opt-in: the machine's load makes
           them noisy; a figure is stale when the measured time is outside
           half to twice the stated one)
  bench    runs tools/bench and checks that its targets are met (opt-in)

  tools/readme-check [--tier T]... [--readme FILE] [--page PAGE=FILE]...
                     [--build DIR] [--keep DIR [--resume]] [--list] [--only TEXT]

--readme FILE reads FILE in place of README.md, --page docs/x.md=FILE in
place of that page (a copy with one number changed must fail).

--keep DIR --resume runs in a DIR kept by an earlier --keep without
clearing it: a sweep resumes from its journal (the tasks done are not run
again), so the hour-long studies can be checked again against the same
results after the page is edited. Other commands run again as they would.

Adding a figure: a Figure(...) entry in figures.py with a name, the tier, the
pattern, the commands (commands.py), and a `values` function returning
{group: text} (in the module of its tier).

Modules, one job each: cli (the command line, the tiers, the run over the
figures), context (the scratch directory, running the commands, the pages),
figure (a figure's pattern and its check), figures (FIGURES: every figure of
the pages), commands (the commands the pages show), formats (numbers and
pictures as the pages write them), tables (reading the results: summaries,
seeds, intervals); the figures' values per tier: fast, static (checks that
run nothing), sweeps, studies, ssm (the SSM and Bologna studies), beyond,
timings.
"""
