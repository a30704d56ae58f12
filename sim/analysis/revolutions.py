"""Per-revolution peaks of an ensemble, and their distributions with bootstrap intervals.

A run's `revolution_peak_*` variables (sim.results) hold, for each crank revolution, the
largest value over every accepted integrator step and sample: impacts last microseconds, so
the 200 samples per revolution alone would miss them. One maximum over a chaotic run is a
noisy statistic (measured: 15 % between runs a hair apart); the distribution of the
per-revolution peaks over revolutions and ensemble members is not.

Intervals come from a two-stage (hierarchical) bootstrap: resample the members with
replacement, then within each drawn member resample its revolutions in moving blocks
(Davison & Hinkley, "Bootstrap Methods and their Application", Cambridge 1997, sect. 3.8 for
the two stages; Künsch, Ann. Statist. 17, 1989, for the moving blocks). Blocks, because the
peaks of consecutive revolutions are correlated (one revolution's impacts set the next one's
start); members, because they are the independent units. Percentile intervals (Efron &
Tibshirani, "An Introduction to the Bootstrap", Chapman & Hall 1993, ch. 13). The maximum is
shown without an interval: a bootstrap resample can never exceed the sample's maximum, so its
percentile interval says nothing (Efron & Tibshirani 1993, sect. 7.4).
"""

import zlib
from dataclasses import dataclass

import numpy as np
import pandas as pd
import xarray as xr

from sim.results import output_series

#: per-revolution quantities (columns of `revolution_table`) and their units
SLIDER_ACCELERATION = "slider_acceleration"
DRIVE_TORQUE = "drive_torque"
CONTACT_EVENTS = "contact_events"
UNITS = {SLIDER_ACCELERATION: "m/s²", DRIVE_TORQUE: "N·m", CONTACT_EVENTS: "per revolution"}
STATISTICS = ("median", "p95")


def contact_force(joint: str) -> str:
    """Column of the per-revolution peak contact force of a clearance joint (N)."""
    return f"contact_force_{joint}"


def unit_of(quantity: str) -> str:
    return UNITS.get(quantity, "N")


def revolution_table(run: xr.Dataset, case: str, transient: int) -> pd.DataFrame:
    """One row per revolution after the first `transient` revolutions of a run: its case,
    ensemble member and seed, revolution, and peak |acceleration| of the scene's output
    channel (m/s²; `output`, by default the slider along its guide), peak |drive torque|
    (N·m), peak contact force of each clearance joint (N) and number of contact events
    (onsets and separations)."""
    first = max(int(transient), 0) + 1  # revolution 0 is the initial state, not a revolution
    sel = {"revolution": slice(first, None)}
    columns = {
        SLIDER_ACCELERATION: output_series(run, "revolution_peak_acceleration"),
        DRIVE_TORQUE: run.revolution_peak_drive_torque,
        CONTACT_EVENTS: run.revolution_contact_events,
    }
    for joint in run.joint.values:
        columns[contact_force(str(joint))] = run.revolution_peak_normal_force.sel(joint=joint)
    table = pd.DataFrame({name: values.isel(sel).values for name, values in columns.items()})
    table.insert(0, "revolution", run.revolution.isel(sel).values)
    table.insert(0, "seed", int(run.attrs.get("ensemble_seed", -1)))
    table.insert(0, "member", int(run.attrs.get("ensemble_member", 0)))
    table.insert(0, "case", case)
    return table


@dataclass(frozen=True)
class Bootstrap:
    """Settings of the two-stage bootstrap: resamples, interval level, seed, and the
    moving-block length in revolutions (None: n^(1/3) of a member's revolutions, the order
    that minimises the error of a block bootstrap's variance estimate: Hall, Horowitz & Jing,
    Biometrika 82, 1995)."""

    resamples: int = 2000
    level: float = 0.95
    seed: int = 0
    block: int | None = None

    def rng(self, *key: str) -> np.random.Generator:
        """A generator for one named resampling, independent of the order of the calls."""
        words = [zlib.crc32(part.encode()) for part in key]
        return np.random.default_rng([self.seed, *words])

    def block_length(self, revolutions: int) -> int:
        if self.block is not None:
            return max(1, min(self.block, revolutions))
        return max(1, min(revolutions, round(revolutions ** (1.0 / 3.0))))


def members_matrix(table: pd.DataFrame, quantity: str) -> np.ndarray:
    """The values of one quantity as (members, revolutions), members in index order; members
    with fewer revolutions are cut to the shortest."""
    groups = [group[quantity].to_numpy(float) for _, group in table.groupby("member", sort=True)]
    if not groups:
        raise ValueError(f"no revolutions of {quantity!r} to summarise")
    shortest = min(len(g) for g in groups)
    if shortest == 0:
        raise ValueError(f"a member has no revolutions of {quantity!r} after the transient")
    return np.stack([g[:shortest] for g in groups])


def resample(values: np.ndarray, boot: Bootstrap, rng: np.random.Generator) -> np.ndarray:
    """Two-stage bootstrap resamples of (members, revolutions) values: (resamples, members ×
    revolutions), members drawn with replacement, then each drawn member's revolutions in
    moving blocks of `boot.block_length` consecutive revolutions."""
    n_members, n_revs = values.shape
    length = boot.block_length(n_revs)
    n_blocks = -(-n_revs // length)
    chosen = rng.integers(0, n_members, size=(boot.resamples, n_members))
    starts = rng.integers(0, n_revs - length + 1, size=(boot.resamples, n_members, n_blocks))
    revs = (starts[..., None] + np.arange(length)).reshape(boot.resamples, n_members, -1)
    revs = revs[..., :n_revs]
    return values[chosen[..., None], revs].reshape(boot.resamples, -1)


def statistic(values: np.ndarray, name: str, axis: int = -1) -> np.ndarray:
    """The median or the 95th percentile ("p95", linear interpolation) along `axis`."""
    if name == "median":
        return np.median(values, axis=axis)
    if name == "p95":
        return np.quantile(values, 0.95, axis=axis)
    raise ValueError(f"unknown statistic {name!r}: use one of {STATISTICS}")


def interval(samples: np.ndarray, level: float) -> tuple[float, float]:
    """Percentile interval of bootstrap replicates at `level` (Efron & Tibshirani 1993)."""
    tail = (1.0 - level) / 2.0
    low, high = np.quantile(samples, [tail, 1.0 - tail])
    return float(low), float(high)


def replicates(
    table: pd.DataFrame, case: str, quantity: str, name: str, boot: Bootstrap
) -> np.ndarray:
    """Bootstrap replicates of statistic `name` of `quantity` in one case (resamples,)."""
    values = members_matrix(table[table.case == case], quantity)
    draws = resample(values, boot, boot.rng(case, quantity, name))
    return statistic(draws, name, axis=1)


def summarise(table: pd.DataFrame, boot: Bootstrap) -> pd.DataFrame:
    """Per case and quantity: members, revolutions, median and 95th percentile of the
    per-revolution peaks with their bootstrap intervals, and the maximum."""
    quantities = [c for c in table.columns if c not in ("case", "member", "seed", "revolution")]
    rows = []
    for case in dict.fromkeys(table.case):
        part = table[table.case == case]
        for quantity in quantities:
            values = members_matrix(part, quantity)
            row = {
                "case": case,
                "quantity": quantity,
                "unit": unit_of(quantity),
                "members": values.shape[0],
                "revolutions_per_member": values.shape[1],
            }
            for name in STATISTICS:
                low, high = interval(replicates(table, case, quantity, name, boot), boot.level)
                row[name] = float(statistic(values.ravel(), name))
                row[f"{name}_low"], row[f"{name}_high"] = low, high
            row["max"] = float(values.max())
            rows.append(row)
    return pd.DataFrame(rows)
