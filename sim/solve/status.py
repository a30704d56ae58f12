"""Status codes of a right-hand side evaluation and of the integration loop, declared once.

A kernel returns OK or one of the failures below; `sim.run.diagnose` turns a failure into a
message naming the time, the joint and the likely cause.
"""

OK = 0
"""Success."""
SINGULAR = 1
"""The constraint Jacobian (or the Newton iteration matrix) lost rank."""
NONFINITE = 2
"""A derivative or the state became non-finite."""
MAX_STEPS = 3
"""solver.max_steps accepted and rejected steps were taken."""
STEP_COLLAPSE = 4
"""The step size fell below the smallest allowed (Options.hmin)."""
PENETRATION = 5
"""A clearance joint penetrated beyond its sane bound (Options.pen_bound)."""
VIOLATION = 6
"""The ideal constraints drifted beyond Options.violation_bound."""
