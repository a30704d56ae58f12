"""Chaos analyses of simulated (or measured) responses.

Modules, one job each:

- :mod:`sim.analysis.lyapunov`: largest Lyapunov exponent from a model (Benettin), from a 1-D
  map, and from a scalar time series (Rosenstein).
- :mod:`sim.analysis.model_lyapunov`: the model-based exponent of a linkage scene (Benettin on
  the run's own compiled integrator).
- :mod:`sim.analysis.embedding`: delay-embedding parameters (mutual information, false nearest
  neighbours, mean period).
- :mod:`sim.analysis.zero_one`: the 0–1 test for chaos (Gottwald and Melbourne).
- :mod:`sim.analysis.poincare`: periodicity of Poincaré section points.
- :mod:`sim.analysis.classify`: periodic / quasi-periodic / chaotic verdict from the indicators.
- :mod:`sim.analysis.run`: all of the above applied to a simulation output dataset.
- :mod:`sim.analysis.bifurcation`: section samples of a parameter sweep in one dataset.
- :mod:`sim.analysis.sweep`: a scene simulated over a parameter's values (``sim sweep``).
- :mod:`sim.analysis.cli`: the ``sim analyze`` and ``sim sweep`` subcommands.
"""
