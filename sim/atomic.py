"""Writing a file so that no reader ever sees it half-written."""

import os
import tempfile
from collections.abc import Callable
from pathlib import Path


def write_atomically(target: Path, write: Callable[[Path], object]) -> None:
    """Call ``write(temporary)`` for a temporary file beside ``target``, then move it into
    place with ``os.replace``: a reader never sees a half-written ``target``, and a failed
    write leaves nothing behind. The temporary is ``.<name>.<random>.tmp``; ``write`` must not
    rely on the file name's extension."""
    handle, temporary = tempfile.mkstemp(
        dir=target.parent, prefix=f".{target.name}.", suffix=".tmp"
    )
    os.close(handle)
    try:
        write(Path(temporary))
        os.replace(temporary, target)
    except BaseException:
        os.unlink(temporary)
        raise
