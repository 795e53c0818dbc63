"""The game's theory from Python: theory(), design(), predict() (the C++
library's, as ``taebp theory --json`` prints it), their arguments under the
config's names, broadcast over arrays and lists (a pandas DataFrame, one row
per point)."""

import json

from . import _taebp
from .errors import InvalidArgument
from .results import _flatten, _pandas

# The arguments' defaults: the C++ request's (runner/theory.h TheoryRequest),
# under the config's names (model.prior_go, model.collision_penalty, ...).
_DEFAULTS = dict(_taebp.theory_defaults())
# Old keyword names (taebp < 0.3), accepted with a DeprecationWarning.
_OLD_NAMES = {"prior": "prior_go", "penalty": "collision_penalty"}
# The C++ messages name the program's options; Python names the arguments.
_OPTION_NAMES = [("--trust theta", "trust"), ("--trust", "trust"), ("--prior", "prior_go"),
                 ("--penalty", "collision_penalty"), ("--assumed-trust", "assumed_trust"),
                 ("--s-max", "s_max"), ("prior lambda", "prior_go lambda"),
                 ("penalty r", "collision_penalty r")]
_NUMERIC = ("prior_go", "collision_penalty", "trust", "assumed_trust", "s_max", "steepness",
            "midpoint")



def _arguments(function, given, old):
    for name, value in old.items():
        if name not in _OLD_NAMES:
            raise TypeError("%s() got an unexpected keyword argument %r (arguments: %s)"
                            % (function, name, ", ".join(list(given))))
        import warnings
        warnings.warn("%s(%s=...) is deprecated: use %s=... (the config's name)"
                      % (function, name, _OLD_NAMES[name]), DeprecationWarning, stacklevel=3)
        given[_OLD_NAMES[name]] = value
    return given


def _is_many(v):
    return not isinstance(v, (str, bytes)) and (hasattr(v, "__len__") or hasattr(v, "shape")) \
        and getattr(v, "ndim", 1) != 0


def _points(args):
    """The arguments broadcast (numpy rules) to one dict per point, and
    whether any argument was an array or a list."""
    import numpy as np
    many = {k: v for k, v in args.items() if _is_many(v)}
    if not many:
        return [args], False
    shape = np.broadcast_shapes(*[np.shape(v) for v in many.values()])
    cols = {k: np.broadcast_to(np.asarray(v, dtype=object), shape).ravel()
            for k, v in many.items()}
    n = int(np.prod(shape)) if shape else 1
    return [{k: (cols[k][i] if k in cols else v) for k, v in args.items()} for i in range(n)], True


def _call(function, point, call):
    try:
        return call()
    except InvalidArgument as e:
        message = str(e)
        for option, name in _OPTION_NAMES:
            message = message.replace(option, name)
        shown = ", ".join("%s=%r" % (k, v) for k, v in point.items() if v is not None)
        raise InvalidArgument("%s(%s): %s" % (function, shown, message)) from None


def _number(function, point, name):
    """An argument as a float, or InvalidArgument naming it: a number (numpy's
    included), never a string or a bool (the config loader's rule)."""
    v = point[name]
    bad = isinstance(v, (str, bytes, bool)) or (hasattr(v, "dtype") and v.dtype.kind in "bUSO")
    if not bad:
        try:
            return float(v)
        except (TypeError, ValueError):
            bad = True
    shown = ", ".join("%s=%r" % (k, x) for k, x in point.items() if x is not None)
    raise InvalidArgument("%s(%s): %s must be a number, got %r%s" % (
        function, shown, name, v, " (a string: write the number itself)"
        if isinstance(v, (str, bytes)) else ""))


def _request(p, function="theory"):
    num = lambda name: _number(function, p, name)  # noqa: E731
    likelihood = p["likelihood"]
    if not isinstance(likelihood, str):
        raise InvalidArgument("%s(likelihood=%r): likelihood must be the name of a "
                              "likelihood (e.g. 'linear')" % (function, likelihood))
    assumed = p["assumed_trust"]
    if assumed is None or (isinstance(assumed, float) and assumed != assumed):
        assumed = None
    else:
        assumed = num("assumed_trust")
        assumed = None if assumed != assumed else assumed
    return (num("prior_go"), num("collision_penalty"), num("trust"), assumed, num("s_max"),
            likelihood, num("steepness"), num("midpoint"))


def _frame(points, rows):
    pd = _pandas()
    out = []
    for p, r in zip(points, rows):
        flat = {}
        _flatten("", r, flat)
        out.append(dict(p, **{k: v for k, v in flat.items() if k not in p}))
    return pd.DataFrame(out)


def theory(prior_go=_DEFAULTS["prior_go"], collision_penalty=_DEFAULTS["collision_penalty"],
           trust=_DEFAULTS["trust"], assumed_trust=None, s_max=_DEFAULTS["s_max"],
           likelihood=_DEFAULTS["likelihood"], steepness=_DEFAULTS["steepness"],
           midpoint=_DEFAULTS["midpoint"], **old):
    """The TA-EBP design and predicted outcomes: the object ``taebp theory --json`` prints.

    Arguments have the config's names (model.prior_go, model.collision_penalty,
    model.trust, model.assumed_trust, model.likelihood.{type, s_max,
    steepness, midpoint}); their defaults are the C++ request's
    (runner/theory.h). Numbers give a dict with keys prior_go,
    collision_penalty, trust, assumed_trust, likelihood, s_max, p_star,
    theta_star, persuadable, s_star, a, b, p_nudge, dc_rate, collision_rate
    (the TA-EBP design's), and policies.<no_ebp | no_trust | ta_ebp |
    full_reveal>.{dc_rate, collision_rate, nudge_rate}. Arrays or lists
    broadcast (numpy rules) and give a pandas DataFrame, one row per point,
    the inputs then those keys flattened (``policies.ta_ebp.dc_rate``):

        >>> taebp.theory(prior_go=np.linspace(0.05, 0.5, 46)[:, None],
        ...              collision_penalty=np.linspace(0.5, 5, 46)[None, :])

    ``assumed_trust`` is the trust the AV designs for (default: ``trust``).
    ``prior=`` and ``penalty=`` (the old names) still work, with a
    DeprecationWarning."""
    args = _arguments("theory", dict(prior_go=prior_go, collision_penalty=collision_penalty,
                                     trust=trust, assumed_trust=assumed_trust, s_max=s_max,
                                     likelihood=likelihood, steepness=steepness,
                                     midpoint=midpoint), old)
    points, many = _points(args)
    rows = [_call("theory", p, lambda r=_request(p): json.loads(_taebp.theory_json(*r)))
            for p in points]
    return _frame(points, rows) if many else rows[0]


def design(prior_go=_DEFAULTS["prior_go"], collision_penalty=_DEFAULTS["collision_penalty"],
           trust=_DEFAULTS["trust"], s_max=_DEFAULTS["s_max"], likelihood=_DEFAULTS["likelihood"],
           steepness=_DEFAULTS["steepness"], midpoint=_DEFAULTS["midpoint"], **old):
    """The TA-EBP design for an AV that assumes trust ``trust`` (paper Sec. IV-C).

    Returns persuadable, theta_star, p_star, s_star, a, b, p_nudge (a dict;
    a DataFrame, one row per point, when an argument is an array or list).
    Arguments as theory()."""
    args = _arguments("design", dict(prior_go=prior_go, collision_penalty=collision_penalty,
                                     trust=trust, assumed_trust=None, s_max=s_max,
                                     likelihood=likelihood, steepness=steepness,
                                     midpoint=midpoint), old)
    points, many = _points(args)
    rows = []
    for p in points:
        r = _request(p, "design")
        rows.append(_call("design", p, lambda r=r: dict(_taebp.design(*(r[:3] + r[4:])))))
    for p in points:
        p.pop("assumed_trust")
    return _frame(points, rows) if many else rows[0]


def predict(policy, prior_go=_DEFAULTS["prior_go"],
            collision_penalty=_DEFAULTS["collision_penalty"], trust=_DEFAULTS["trust"],
            assumed_trust=None, s_max=_DEFAULTS["s_max"], likelihood=_DEFAULTS["likelihood"],
            steepness=_DEFAULTS["steepness"], midpoint=_DEFAULTS["midpoint"], **old):
    """Predicted rates per AV-HV encounter of ``policy`` ({game_policies}:
    the game's policies; {no_game} plays none) for an HV of trust ``trust`` when the
    AV designs for ``assumed_trust`` (default ``trust``; no_trust designs
    for 1).

    Returns dc_rate, collision_rate, nudge_rate, av_first_rate (a dict; a
    DataFrame, one row per point, when an argument, ``policy`` included, is
    an array or list). Arguments as theory()."""
    args = _arguments("predict", dict(policy=policy, prior_go=prior_go,
                                      collision_penalty=collision_penalty, trust=trust,
                                      assumed_trust=assumed_trust, s_max=s_max,
                                      likelihood=likelihood, steepness=steepness,
                                      midpoint=midpoint), old)
    points, many = _points(args)
    rows = [_call("predict", p, lambda p=p, r=_request(p, "predict"):
                  dict(_taebp.predict(str(p["policy"]), *r)))
            for p in points]
    return _frame(points, rows) if many else rows[0]
