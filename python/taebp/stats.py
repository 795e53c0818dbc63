"""Statistics of taebp's results, in pure Python (no compiled module needed).

``mean_interval`` is the 95 % interval of a mean over seeds (Student's t) that
the README's efficiency tables report; ``student_t_quantile`` its quantile.

The one Wilson interval of the Python code and the intervals clustered by HV
and run that every per-encounter rate is reported with (``clustered_rate``,
``pooled_rate``, ``encounter_rate``; docs/metrics.md): the ``taebp`` module,
``tools/plot`` and ``tools/readme-check`` use these functions (the tools load
this file by its path, so they run without the built module). Their C++ twins
are ``taebp::Wilson`` (report/include/taebp/report/report.h) and
``taebp::ClusteredRate`` / ``PooledRate`` (report/clustered.h); they are tested
against the same published values and against the C++ outputs
(tests/report/wilson_test.cc, clustered_test.cc, tests/python/test_stats.py).
"""

import math

__all__ = ["Z95", "Z999", "MIN_CLUSTERS", "wilson", "wilson_at", "clustered_rate", "pooled_rate",
           "encounter_rate", "normal_quantile", "bonferroni_level", "rate_difference",
           "student_t_quantile", "mean_interval", "mean_interval_of", "welch_interval"]

# Two-sided standard normal quantiles: 95 % (what every output reports) and
# 99.9 % (a measured rate against its theory, where a false alarm should be rare).
Z95 = 1.959963984540054
Z999 = 3.2905267314919255


def wilson(k, n, z=Z95):
    """The Wilson score interval (low, high) for k successes out of n at normal
    quantile z (Wilson 1927; Newcombe 1998, method 3, no continuity correction).

    Edges: n = 0 gives (0, 1); k = 0 gives low exactly 0; k = n gives high
    exactly 1; always inside [0, 1]. Needs 0 <= k <= n.

    ``k`` and ``n`` may be numpy arrays, pandas Series or lists (numpy's
    broadcasting rules): then (low, high) are two float arrays of their
    broadcast shape, element by element the same numbers as for scalars,
    e.g. ``lo, hi = taebp.stats.wilson(df.collisions, df.encounters)``."""
    if _is_array(k) or _is_array(n) or _is_array(z):
        return _wilson_arrays(k, n, z)
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



def _is_array(v):
    return not isinstance(v, (str, bytes)) and (hasattr(v, "__len__") or getattr(v, "ndim", 0) > 0)



def _wilson_arrays(k, n, z):
    """wilson() element by element over broadcast arrays (the same formula)."""
    import numpy as np
    k, n, z = np.broadcast_arrays(np.asarray(k, dtype=float), np.asarray(n, dtype=float),
                                  np.asarray(z, dtype=float))
    bad = ~((0 <= k) & (k <= n))
    if bad.any():
        i = np.argwhere(bad)[0]
        raise ValueError("wilson: need 0 <= k <= n, got k=%r, n=%r at index %s"
                         % (k[tuple(i)].item(), n[tuple(i)].item(), tuple(int(x) for x in i)))
    with np.errstate(divide="ignore", invalid="ignore"):
        p = k / n
        z2 = z * z
        d = 1 + z2 / n
        c = (p + z2 / (2 * n)) / d
        h = z * np.sqrt(p * (1 - p) / n + z2 / (4 * n * n)) / d
        low = np.where(k == 0, 0.0, np.maximum(0.0, c - h))
        high = np.where(k == n, 1.0, np.minimum(1.0, c + h))
    empty = n == 0
    return np.where(empty, 0.0, low), np.where(empty, 1.0, high)


# Below this many clusters (HVs met, or runs) no interval can account for
# their dependence (report/include/taebp/report/clustered.h kMinClusters).
MIN_CLUSTERS = 5


def wilson_at(p, n, z=Z95):
    """Wilson's interval (low, high) for a proportion p from an effective
    sample size n > 0 (real-valued): wilson(k, n) at p = k / n."""
    if not n > 0:
        return 0.0, 1.0
    z2 = z * z
    d = 1 + z2 / n
    c = (p + z2 / (2 * n)) / d
    h = z * math.sqrt(p * (1 - p) / n + z2 / (4 * n * n)) / d
    return (0.0 if p <= 0 else max(0.0, c - h)), (1.0 if p >= 1 else min(1.0, c + h))


def _adjusted(deff, df, z):
    """The design effect an interval uses: its estimated excess over 1 scaled by
    (t_df / z)^2 (clustered.h); 1 where none was estimated."""
    if df < 1 or not deff > 1:
        return 1.0
    t = student_t_quantile(int(round(df)), math.erf(z / math.sqrt(2.0)))
    return 1.0 + (deff - 1.0) * (t / z) ** 2


def _finish(y, n, levels, z):
    if not n > 0:
        return {"rate": 0.0, "low": 0.0, "high": 1.0, "deff": 1.0, "clusters": 0,
                "few_clusters": True}
    used, adj = levels[0], _adjusted(*levels[0][:2], z)
    for level in levels[1:]:
        a = _adjusted(*level[:2], z)
        if a > adj:
            used, adj = level, a
    p = y / n
    lo, hi = wilson_at(p, n / adj, z)
    return {"rate": p, "low": lo, "high": hi, "deff": used[0], "clusters": used[2],
            "few_clusters": used[2] < MIN_CLUSTERS}


def clustered_rate(y, n, z=Z95):
    """The interval of sum(y) / sum(n) whose trials come in clusters (y[i]
    successes in n[i] trials of cluster i, e.g. one HV's encounters): Wilson's
    at the effective sample size n / deff, the design effect from the
    cluster-robust variance (CR1) with its excess over 1 scaled by
    (t_{G-1} / z)^2. A dict: rate, low, high, deff, clusters, few_clusters.
    The C++ twin is taebp::ClusteredRate (report/clustered.h); docs/metrics.md
    says why."""
    pairs = [(float(a), float(b)) for a, b in zip(y, n) if float(b) > 0]
    g = len(pairs)
    ys, ns = sum(a for a, _ in pairs), sum(b for _, b in pairs)
    p = ys / ns if ns > 0 else 0.0
    binomial = p * (1 - p) / ns if ns > 0 else 0.0
    deff = 1.0
    if g >= 2 and binomial > 0:
        ss = sum((a - p * b) ** 2 for a, b in pairs)
        deff = g / (g - 1) * ss / (ns * ns) / binomial
    return _finish(ys, ns, [(deff, g - 1, g)], z)


def pooled_rate(y, n, deff, clusters, z=Z95):
    """A rate pooled over independent runs (a sweep's seeds), from each run's
    successes y, trials n, design effect and clusters as its summary reports
    them: the larger of two levels, the HVs (each run's clustered variance)
    and the runs (CR1 over their totals). The dict of clustered_rate; the C++
    twin is taebp::PooledRate."""
    runs = [(float(a), float(b), float(d) if d == d else 1.0, int(c))
            for a, b, d, c in zip(y, n, deff, clusters) if float(b) > 0]
    r = len(runs)
    ys, ns = sum(x[0] for x in runs), sum(x[1] for x in runs)
    p = ys / ns if ns > 0 else 0.0
    binomial = p * (1 - p) / ns if ns > 0 else 0.0
    g_hv = sum(x[3] for x in runs)
    df_hv = sum(max(x[3] - 1, 0) for x in runs)
    deff_hv, deff_run = 1.0, 1.0
    if binomial > 0:
        v_hv = sum(d * (a / b) * (1 - a / b) * b for a, b, d, _ in runs)
        deff_hv = v_hv / (ns * ns) / binomial
        if r >= 2:
            ss = sum((a - p * b) ** 2 for a, b, _, _ in runs)
            deff_run = r / (r - 1) * ss / (ns * ns) / binomial
    return _finish(ys, ns, [(deff_hv, df_hv, g_hv), (deff_run, r - 1, r)], z)


def encounter_rate(rows, hit, run=lambda r: "", hv=lambda r: r["hv"], z=Z95):
    """The rate of `hit` over encounter rows (encounters.csv dicts) with its
    interval clustered as the outputs' are: by HV within each run (`run`
    names a row's run, e.g. its seed in a sweep's pooled file) and, over
    several runs, by run (pooled_rate). The dict of clustered_rate."""
    by_run = {}
    for r in rows:
        c = by_run.setdefault(run(r), {}).setdefault(hv(r), [0, 0])
        c[0] += 1 if hit(r) else 0
        c[1] += 1
    ys, ns, deffs, gs = [], [], [], []
    for hvs in by_run.values():
        one = clustered_rate([c[0] for c in hvs.values()], [c[1] for c in hvs.values()], z)
        ys.append(sum(c[0] for c in hvs.values()))
        ns.append(sum(c[1] for c in hvs.values()))
        deffs.append(one["deff"])
        gs.append(one["clusters"])
    return pooled_rate(ys, ns, deffs, gs, z)


def normal_quantile(level):
    """The two-sided standard normal quantile z: P(|Z| < z) = level (Z95 at 0.95)."""
    if not 0 < level < 1:
        raise ValueError("normal_quantile: level must be in (0, 1), got %r" % (level,))
    lo, hi = 0.0, 40.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if math.erf(mid / math.sqrt(2.0)) < level:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def bonferroni_level(m, level=0.95):
    """The level of each of m intervals (tests) on one question so that all hold
    together at `level` (Bonferroni): 1 - (1 - level) / m."""
    return 1.0 - (1.0 - level) / m


def rate_difference(a, b):
    """The difference a - b of two rates measured on different samples (e.g. two
    policies' games, not paired), from their intervals as clustered_rate /
    pooled_rate / encounter_rate give them (dicts with rate, low, high, at one
    level): the MOVER interval (Zou and Donner 2008; Newcombe's method 10 when
    both are Wilson's). (difference, low, high)."""
    d = a["rate"] - b["rate"]
    lo = d - math.sqrt((a["rate"] - a["low"]) ** 2 + (b["high"] - b["rate"]) ** 2)
    hi = d + math.sqrt((a["high"] - a["rate"]) ** 2 + (b["rate"] - b["low"]) ** 2)
    return d, lo, hi


def _t_two_sided(t, df):
    """P(|T| < t) for Student's t with integer df (Abramowitz & Stegun 26.7.3-4)."""
    th = math.atan(t / math.sqrt(df))
    c2 = math.cos(th) ** 2
    if df % 2 == 1:
        total, term = 0.0, math.cos(th)
        for k in range(1, (df - 1) // 2 + 1):
            total += term
            term *= (2.0 * k) / (2.0 * k + 1.0) * c2
        return 2.0 / math.pi * (th + math.sin(th) * total)
    total, term = 1.0, 1.0
    for k in range(1, (df - 2) // 2 + 1):
        term *= (2.0 * k - 1.0) / (2.0 * k) * c2
        total += term
    return math.sin(th) * total


def student_t_quantile(df, level=0.95):
    """The two-sided Student t quantile: P(|T| < t) = level, for integer df >= 1
    (bisection on the exact distribution function; 12.7062 for df 1 at 95 %)."""
    if int(df) != df or df < 1:
        raise ValueError("student_t_quantile: df must be a whole number >= 1, got %r" % (df,))
    if not 0 < level < 1:
        raise ValueError("student_t_quantile: level must be in (0, 1), got %r" % (level,))
    lo, hi = 0.0, 1.0
    while _t_two_sided(hi, int(df)) < level:
        hi *= 2.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if _t_two_sided(mid, int(df)) < level:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def mean_interval(values, level=0.95):
    """(mean, low, high): the mean of independent values (e.g. one per seed)
    and its Student t interval; low = high = mean for one value (no spread
    known) and (None, None, None) for none."""
    xs = [float(v) for v in values]
    n = len(xs)
    if n == 0:
        return None, None, None
    mean = sum(xs) / n
    if n == 1:
        return mean, mean, mean
    sd = math.sqrt(sum((x - mean) ** 2 for x in xs) / (n - 1))
    half = student_t_quantile(n - 1, level) * sd / math.sqrt(n)
    return mean, mean - half, mean + half


def mean_interval_of(mean, sd, n, level=0.95):
    """(low, high): the Student t interval of a mean over n independent
    values (one per seed) given their sample sd, as aggregate.csv holds them
    (NAME, NAME_sd, runs_ok); (None, None) for n < 2 or no sd."""
    if mean is None or sd is None or n is None or n < 2:
        return None, None
    half = student_t_quantile(int(n) - 1, level) * sd / math.sqrt(n)
    return mean - half, mean + half



def welch_interval(a, b, level=0.95):
    """(difference, low, high): mean(a) - mean(b) of two independent samples
    (e.g. two policies' runs, not paired by seed) and its Welch interval, the
    Welch-Satterthwaite degrees of freedom rounded down (a slightly wider,
    conservative interval; student_t_quantile takes whole numbers). Needs at
    least two values in each sample and some spread; (None, None, None) otherwise."""
    xs, ys = [float(v) for v in a], [float(v) for v in b]
    if len(xs) < 2 or len(ys) < 2:
        return None, None, None
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    vx = sum((x - mx) ** 2 for x in xs) / (len(xs) - 1) / len(xs)
    vy = sum((y - my) ** 2 for y in ys) / (len(ys) - 1) / len(ys)
    if vx + vy == 0:
        return None, None, None
    df = (vx + vy) ** 2 / (vx ** 2 / (len(xs) - 1) + vy ** 2 / (len(ys) - 1))
    half = student_t_quantile(max(1, int(math.floor(df + 1e-9))), level) * math.sqrt(vx + vy)
    return mx - my, mx - my - half, mx - my + half
