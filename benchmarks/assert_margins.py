"""Survey of the test suite's numerical bounds: how far each passing comparison is from failing.

A bound that passes by less than a factor 1.5 on one machine may fail on another (other library
versions, other round-off). This pytest plugin records every passing assertion of the form
``value < bound`` or ``value <= bound`` (and the mirrored ``>``, ``>=``) on finite, non-zero
numbers, and prints those whose margin bound / value (or value / bound for lower bounds) is
below ``--margin`` (default 1.5), with the test and the line::

    python -m pytest -p benchmarks.assert_margins -o enable_assertion_pass_hook=true \
        -o addopts="" -m "not slow" -q [--margin 1.5]

Each listed bound must be derived and justified in the test, or the test's settings changed so
the margin exists (docs/testing.md). Counts of equal values (``==``) are not margins and are
not listed; neither are comparisons of integers within 1 of each other.
"""

import math
import re

import pytest

#: "<left> <op> <right>" as pytest's explanation writes a comparison, each side a number or
#: simple arithmetic on numbers (e.g. "(0.15 * 0.0714)")
_COMPARISON = re.compile(
    r"^(?P<left>[-+0-9.eE*/() ]+?) (?P<op><=|<|>=|>) (?P<right>[-+0-9.eE*/() ]+)$"
)
_ARITHMETIC = re.compile(r"^[-+0-9.eE*/() ]+$")
#: numpy scalars as their repr shows them, "np.float64(0.5)"
_NUMPY_SCALAR = re.compile(r"np\.(?:float|int)(?:16|32|64)\(([^()]*)\)")


def _evaluate(text: str) -> float:
    """A side of a comparison: arithmetic on literal numbers only (checked by the pattern)."""
    if not _ARITHMETIC.match(text):
        raise ValueError(text)
    return float(eval(text, {"__builtins__": {}}))  # safe: digits and operators only


_records: list[tuple[float, str, str]] = []


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption(
        "--margin", type=float, default=1.5, help="list bounds met by less than this factor"
    )


def margin(left: float, op: str, right: float) -> float | None:
    """How many times over the comparison holds: bound / value for an upper bound, value /
    bound for a lower one; None when the ratio is meaningless (signs differ, zero, infinite)."""
    value, bound = (left, right) if op in ("<", "<=") else (right, left)
    if not (math.isfinite(value) and math.isfinite(bound)) or value == 0 or bound == 0:
        return None
    if (value > 0) != (bound > 0):
        return None
    ratio = bound / value if value > 0 else value / bound
    return ratio


def pytest_assertion_pass(item: pytest.Item, lineno: int, orig: str, expl: str) -> None:
    first = _NUMPY_SCALAR.sub(r"\1", expl.splitlines()[0].strip()) if expl else ""
    match = _COMPARISON.match(first)
    if not match:
        return
    try:
        left, right = _evaluate(match["left"]), _evaluate(match["right"])
    except (ValueError, SyntaxError, ZeroDivisionError):
        return
    if left.is_integer() and right.is_integer() and abs(left - right) <= 1:
        return
    ratio = margin(left, match["op"], right)
    if ratio is not None:
        _records.append((ratio, f"{item.nodeid} line {lineno}", f"{orig}  [{first}]"))


def pytest_terminal_summary(terminalreporter, config: pytest.Config) -> None:
    limit = config.getoption("--margin")
    tight = sorted(r for r in _records if r[0] < limit)
    terminalreporter.section(f"bounds met by less than a factor {limit}")
    terminalreporter.write_line(f"{len(_records)} numerical comparisons recorded")
    for ratio, where, what in tight:
        terminalreporter.write_line(f"{ratio:7.3f}  {where}: {what}")
