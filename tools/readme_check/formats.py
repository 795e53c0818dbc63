"""Numbers and pictures as the pages write them: rates, fractions, wall
times, a PNG's size, the same file."""

import struct
from fractions import Fraction


def f3(x):
    return "%.3f" % x


def md(x):
    """A rate as the README's markdown tables write it: 0, 1 or 3 decimals."""
    return "0" if x == 0 else ("1" if x == 1 else "%.3f" % x)


def tens(x):
    return "%d" % int(round(x, -1))


def frac(x):
    f = Fraction(x).limit_denominator(64)
    return "%d/%d" % (f.numerator, f.denominator) if abs(float(f) - x) < 1e-9 else repr(x)


def fixed(x, d=3):
    """A rate with d decimals (0 and 1 as they are)."""
    if x == 0 or x == 1:
        return "%d" % x
    while round(x, d) == 0:  # a small nonzero bound keeps a significant digit
        d += 1
    return "%.*f" % (d, x)


def rate_ci(row, name, d=3):
    """A rate and its 95 % interval (NAME, NAME_lo, NAME_hi of summary.json or a sweep's CSV)."""
    v = [float(row[name + suffix]) for suffix in ("", "_lo", "_hi")]
    return "%s [%s, %s]" % (fixed(v[0], d), fixed(v[1], d), fixed(v[2], d))


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    return struct.unpack(">II", head[16:24])


def same_file(a, b):
    with open(a, "rb") as fa, open(b, "rb") as fb:
        return fa.read() == fb.read()


def strip_lines(text):
    return "\n".join(l.rstrip() for l in text.strip("\n").splitlines())


def seconds(claimed, measured):
    """The README's 'about N s' stays when measured is within [N/2, 2N]."""
    c = float(claimed)
    return claimed if c / 2 <= measured <= 2 * c else "%.0f" % measured
