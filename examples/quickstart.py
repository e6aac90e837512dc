"""The README's example: a sphere's adhesive force to 2 %, and its pull-off curve's minimum.

Run it after `pip install ./python`:  python examples/quickstart.py
"""

import jkrbem

r = jkrbem.simulate(ratio=1, accuracy="2%", backend="cpu", fields="minimum")  # JKR says |min F̄| = 1/2
print(f"|min F̄| = {r.adhesive_force:.4f} ± {r.uncertainty:.4f} ({r.estimate}), JKR 0.5")
f = r.field_at_minimum  # pressure, gap, contact at the force minimum: 2-D numpy arrays [y, x]
print(f"pressure at the minimum: {f.pressure.shape}, from {f.pressure.min():.3f} to {f.pressure.max():.3f}")
assert abs(f.force - f.state["force"]) <= 1e-6 * abs(f.state["force"]), "Σ p Δx² is the state's force"
s = r.states  # numpy structured array, the states CSV's columns
i = s["f_bar"].argmin()
print(f"force minimum of the finest grid at d̄ = {s['d_bar'][i]:.4f}, c̄ = {s['c_bar'][i]:.4f}")
assert abs(r.adhesive_force - 0.5) <= r.uncertainty, "JKR's 1/2 lies within the stated uncertainty"
