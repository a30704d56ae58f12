"""The parameter values of a sweep study, from its config entry. Kept free of heavy imports:
the workflow reads it on every parse (workflow/rules/common.smk)."""

from collections.abc import Mapping


def sweep_grid(sweep: Mapping) -> list[float]:
    """The values of a sweep: its ``values`` as given, or ``range: [start, stop, count]``,
    ``count`` evenly spaced values from ``start`` to ``stop`` inclusive (both exactly)."""
    if "values" in sweep:
        return list(sweep["values"])
    start, stop, count = sweep["range"]
    return [start + (stop - start) * k / max(count - 1, 1) for k in range(count)]
