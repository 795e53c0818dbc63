"""Swept values that are maps, in pure Python: a trust distribution such as
``{dist: beta, alpha: 12, beta: 8}`` (model.trust's forms, config.h TrustSpec:
a number, ``{dist: uniform, low, high}``, ``{dist: beta, alpha, beta}``,
``{dist: discrete, values, weights}``) read from a results table's cell, its
mean and standard deviation, and a label that says what it is
("Beta mean 0.6 sd 0.11").

The sweep tables (results.csv, aggregate.csv, ...) hold a swept value as the
YAML text the config gave; ``value`` reads that text back (YAML flow maps and
lists of numbers and words, as taebp's grid values are written).
"""

import math
import re

__all__ = ["value", "describe", "label", "is_distribution"]

_NUMBER = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$")


class _Reader:
    def __init__(self, text):
        self.text, self.i = text, 0

    def peek(self):
        while self.i < len(self.text) and self.text[self.i] in " \t":
            self.i += 1
        return self.text[self.i] if self.i < len(self.text) else ""

    def expect(self, c):
        if self.peek() != c:
            raise ValueError("expected %r at %d in %r" % (c, self.i, self.text))
        self.i += 1

    def node(self):
        c = self.peek()
        if c == "{":
            self.i += 1
            out = {}
            while self.peek() != "}":
                key = self.scalar(":")
                self.expect(":")
                out[str(key)] = self.node()
                if self.peek() == ",":
                    self.i += 1
            self.expect("}")
            return out
        if c == "[":
            self.i += 1
            out = []
            while self.peek() != "]":
                out.append(self.node())
                if self.peek() == ",":
                    self.i += 1
            self.expect("]")
            return out
        return self.scalar(",}]")

    def scalar(self, stops):
        self.peek()
        start = self.i
        if self.i < len(self.text) and self.text[self.i] in "\"'":
            q = self.text[self.i]
            end = self.text.index(q, self.i + 1)
            self.i = end + 1
            return self.text[start + 1:end]
        while self.i < len(self.text) and self.text[self.i] not in stops:
            self.i += 1
        word = self.text[start:self.i].strip()
        if _NUMBER.match(word):
            v = float(word)
            return int(v) if re.match(r"^[+-]?\d+$", word) else v
        return {"true": True, "false": False, "null": None, "~": None}.get(word, word)


def value(text):
    """A swept value's YAML text as Python: a number, a word, a dict or a list
    (``"{dist: beta, alpha: 12, beta: 8}"`` -> {"dist": "beta", "alpha": 12,
    "beta": 8}). A value that is already not a string is returned as is."""
    if not isinstance(text, str):
        return text
    r = _Reader(text.strip())
    out = r.node()
    if r.peek() != "":
        raise ValueError("unexpected text after the value: %r" % text)
    return out


def is_distribution(v):
    return isinstance(v, dict) and "dist" in v


def describe(v):
    """(name, mean, sd) of a trust value: a number is ("fixed", v, 0); a
    distribution its own; anything else (None, None, None)."""
    v = value(v) if isinstance(v, str) else v
    if isinstance(v, bool) or v is None:
        return None, None, None
    if isinstance(v, (int, float)):
        return "fixed", float(v), 0.0
    if not is_distribution(v):
        return None, None, None
    kind = str(v["dist"])
    if kind == "fixed" and "value" in v:
        return "fixed", float(v["value"]), 0.0
    if kind == "beta":
        a, b = float(v.get("alpha", 1.0)), float(v.get("beta", 1.0))
        return kind, a / (a + b), math.sqrt(a * b / ((a + b) ** 2 * (a + b + 1)))
    if kind == "uniform":
        lo, hi = float(v.get("low", 0.0)), float(v.get("high", 1.0))
        return kind, (lo + hi) / 2, (hi - lo) / math.sqrt(12.0)
    if kind == "discrete":
        xs = [float(x) for x in v.get("values", [])]
        ws = [float(w) for w in v.get("weights", [1.0] * len(xs))]
        total = sum(ws)
        if not xs or total <= 0:
            return kind, None, None
        mean = sum(w * x for w, x in zip(ws, xs)) / total
        return kind, mean, math.sqrt(sum(w * (x - mean) ** 2 for w, x in zip(ws, xs)) / total)
    return kind, None, None


def label(v):
    """A swept value as a reader names it: 0.6 -> "0.6"; Beta(12, 8) ->
    "Beta mean 0.6 sd 0.11"; another map or list -> its text."""
    parsed = value(v) if isinstance(v, str) else v
    if is_distribution(parsed):
        kind, mean, sd = describe(parsed)
        if mean is not None:
            return "%s mean %.2g sd %.2g" % (kind.capitalize(), mean, sd)
        return str(v)
    if isinstance(parsed, float):
        return "%g" % parsed
    return str(v)
