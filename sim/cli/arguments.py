"""Arguments and checks shared by the subcommands of `sim`."""

import argparse
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path


def add_scene_arguments(parser: argparse.ArgumentParser) -> None:
    """The scene name or path and the repeatable --set overrides."""
    parser.add_argument(
        "scene", help="built-in scene name (sixbar, fourbar, slider-crank) or YAML path"
    )
    parser.add_argument(
        "--set",
        dest="overrides",
        action="append",
        default=[],
        metavar="KEY=VALUE",
        help="override a scene key, e.g. joints.A.clearance=0.5e-3 (repeatable)",
    )


def check_output(option: str, path: str | Path, *, directory: bool = False) -> None:
    """Raise ValueError, before any computation, when an output given to `option` is the wrong
    kind of thing: a directory where a file is written, or a file where a directory is."""
    path = Path(path)
    if directory and path.exists() and not path.is_dir():
        raise ValueError(f"{option} '{path}' is a file; give a directory (created if missing)")
    if not directory and path.is_dir():
        raise ValueError(f"{option} '{path}' is a directory; give a file name")


@contextmanager
def interrupted_while(what: str) -> Iterator[None]:
    """Ctrl-C inside the block raises sim.run.Interrupted saying it came ``while`` doing
    ``what`` (and, from a run, at which simulated time)."""
    from sim.run import Interrupted

    try:
        yield
    except KeyboardInterrupt as stop:
        at = f" ({stop.where})" if isinstance(stop, Interrupted) else ""
        raise Interrupted(f"while {what}{at}") from None
