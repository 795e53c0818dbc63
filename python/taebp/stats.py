"""Statistics of taebp's results, in pure Python (no compiled module needed).

The one Wilson interval of the Python code: the ``taebp`` module, ``tools/plot``
and ``tools/readme-check`` use this function (the tools load this file by its
path, so they run without the built module). Its C++ twin is
``taebp::Wilson`` (report/include/taebp/report/report.h); both are tested
against the same published values (tests/report/wilson_test.cc,
tests/python/test_stats.py).
"""

import math

__all__ = ["Z95", "Z999", "wilson"]

# Two-sided standard normal quantiles: 95 % (what every output reports) and
# 99.9 % (a measured rate against its theory, where a false alarm should be rare).
Z95 = 1.959963984540054
Z999 = 3.2905267314919255


def wilson(k, n, z=Z95):
    """The Wilson score interval (low, high) for k successes out of n at normal
    quantile z (Wilson 1927; Newcombe 1998, method 3, no continuity correction).

    Edges: n = 0 gives (0, 1); k = 0 gives low exactly 0; k = n gives high
    exactly 1; always inside [0, 1]. Needs 0 <= k <= n."""
    if not 0 <= k <= n:
        raise ValueError("wilson: need 0 <= k <= n, got k=%r, n=%r" % (k, n))
    if n == 0:
        return 0.0, 1.0
    p = k / n
    z2 = z * z
    d = 1 + z2 / n
    c = (p + z2 / (2 * n)) / d
    h = z * math.sqrt(p * (1 - p) / n + z2 / (4 * n * n)) / d
    return (0.0 if k == 0 else max(0.0, c - h)), (1.0 if k == n else min(1.0, c + h))
