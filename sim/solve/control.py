"""The step-size controller's constants that the integration loop (`sim.solve.stepping`) and
both methods share; a method's own (DOPRI5's PI gains, generalized-α's growth rule) are in
its module. Values of Hairer's code DOPRI5 (Hairer, Nørsett & Wanner, Solving ODEs I, II.4)
unless stated."""

FAC_MIN, FAC_MAX = 0.2, 10.0
"""The next step is at least FAC_MIN and at most FAC_MAX times this one: one error estimate
must not move the step size by orders of magnitude."""
ERR_MIN = 1e-10
"""Floor of a step's scaled error in the step-size ratio: an exact step (error 0) must not
divide by zero; FAC_MAX bounds the growth anyway."""
ERR_OLD_MIN = 1e-4
"""Floor of the previous accepted step's error that the PI control remembers (DOPRI5's
facold), and its value before the first step: a nearly exact step must not make the next
ones grow unchecked."""
T_ROUNDOFF = 1e-12
"""Relative round-off of a time: times within T_ROUNDOFF · max(1 s, |t|) are the same (the
run's end reached, a sample or a section on a step's end), so that sums of step sizes
neither drop a sample nor leave a sliver step."""
