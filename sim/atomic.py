"""Writing a file so that no reader ever sees it half-written."""

import os
import tempfile
from collections.abc import Callable
from pathlib import Path

#: the permissions a file created by open() gets under this process's umask (read once, at
#: import: os.umask can only be read by setting it)
_UMASK = os.umask(0)
os.umask(_UMASK)
FILE_MODE = 0o666 & ~_UMASK


def write_atomically(target: Path, write: Callable[[Path], object]) -> None:
    """Call ``write(temporary)`` for a temporary file beside ``target``, then move it into
    place with ``os.replace``: a reader never sees a half-written ``target``, and a failed
    write leaves nothing behind. The temporary is ``.<name>.<random>.tmp``; ``write`` must not
    rely on the file name's extension. The file gets the permissions an ordinary write would
    give it (``FILE_MODE``)."""
    handle, temporary = tempfile.mkstemp(
        dir=target.parent, prefix=f".{target.name}.", suffix=".tmp"
    )
    os.close(handle)
    try:
        write(Path(temporary))
        os.chmod(temporary, FILE_MODE)  # mkstemp creates it readable by its owner alone
        os.replace(temporary, target)
    except BaseException:
        os.unlink(temporary)
        raise
