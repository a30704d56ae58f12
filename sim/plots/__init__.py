"""Figures and tables of the workflow, one module per kind, one shared style (style.py).

- responses: slider responses and driving torque against the ideal mechanism
- trajectories: clearance-joint centre trajectories inside the clearance circle or band
- chaos: phase portraits, Poincaré maps, the Lyapunov table (Table 3)
- bifurcation: bifurcation diagrams with the Lyapunov exponent beneath
- headline: the front page's figures of the paper's claims (exponents per case, the sweeps)
- tables: peak tables (Tables 4, 5), work–precision, extremes
- experiment: measured (or synthetic) against simulated acceleration
"""
