"""What runs the simulator for a study, beyond one run.

- :mod:`sim.studies.sweep`: a scene simulated over a parameter's values (``sim sweep``),
  optionally each value continued from its neighbour's end.
- :mod:`sim.studies.model_lyapunov`: the model-based largest Lyapunov exponent of a linkage
  scene (Benettin on the run's own compiled integrator).
- :mod:`sim.studies.fidelity`: the accuracy of a run against a reference run of the same scene
  (the work–precision study's measures).
"""
