"""What made an output: the versions of the interpreter and of the numerical libraries.

Every netCDF file the project writes carries :func:`library_versions` as its
``library_versions`` attribute (JSON text), so a number can be traced to the numpy, scipy,
numba and llvmlite that computed it. The versions installed by the README's commands are
pinned in ``requirements.txt``.
"""

import json
import platform
from importlib.metadata import PackageNotFoundError, version

#: distributions whose version can change a computed number or a written file
NUMERICAL_LIBRARIES = (
    "numpy",
    "scipy",
    "numba",
    "llvmlite",
    "xarray",
    "netCDF4",
    "pandas",
    "matplotlib",
)


def library_versions() -> dict[str, str]:
    """Python's version and each of :data:`NUMERICAL_LIBRARIES`' ("absent" if not installed)."""

    def installed(name: str) -> str:
        try:
            return version(name)
        except PackageNotFoundError:
            return "absent"

    return {"python": platform.python_version()} | {
        name: installed(name) for name in NUMERICAL_LIBRARIES
    }


def library_versions_json() -> str:
    """:func:`library_versions` as JSON text, the form netCDF attributes take."""
    return json.dumps(library_versions(), sort_keys=True)
