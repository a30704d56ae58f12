"""sim: planar linkages with joint clearances and flexible links.

Simulation of planar multibody linkages (rigid bodies, ANCF beams, ideal and
clearance joints), chaos analyses of the responses, and the pipeline that
reproduces the six-bar press study.
"""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("sim")
except PackageNotFoundError:  # running from a source tree without installation
    __version__ = "0.0.0+unknown"
