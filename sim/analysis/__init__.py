"""Chaos analyses of simulated (or measured) responses: pure functions of data, which never
run the simulator (what does is in :mod:`sim.studies`).

Modules, one job each:

- :mod:`sim.analysis.lyapunov`: largest Lyapunov exponent from a model (Benettin), from a 1-D
  map, and from a scalar time series (Rosenstein).
- :mod:`sim.analysis.embedding`: delay-embedding parameters (mutual information, false nearest
  neighbours, mean period).
- :mod:`sim.analysis.zero_one`: the 0–1 test for chaos (Gottwald and Melbourne).
- :mod:`sim.analysis.poincare`: periodicity of Poincaré section points.
- :mod:`sim.analysis.classify`: periodic / quasi-periodic / chaotic verdict from the indicators.
- :mod:`sim.analysis.run`: all of the above applied to a simulation output dataset.
- :mod:`sim.analysis.revolutions`: per-revolution peaks of ensemble members, their
  distributions with two-stage bootstrap intervals.
- :mod:`sim.analysis.verdicts`: claims that compare settings, as tests on those distributions.
- :mod:`sim.analysis.bifurcation`: section samples of a parameter sweep in one dataset.
"""
