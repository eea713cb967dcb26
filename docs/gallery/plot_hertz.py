"""
Hertz: the pressure against the half-space solution
=====================================================

A rigid cylinder (R = 1) pressed 0.01 into the block (−2, 2) × (−2, 0), frictionless: the shipped scene
``hertz.toml``, its mesh graded down to h_min = 0.0025 at the contact zone (the scene file says 0.04). The
multiplier λ_n is drawn with the plane-strain Hertz pressure of the computed force; the study pages
measure the error against a converged reference.
"""

import matplotlib.pyplot as plt

import tribo
import tribo.plot
from tribo.scene import parse_scene, read_scene_data, scene_path

data = read_scene_data(scene_path("hertz"))
data["discretization"]["h_min"] = 0.0025
problem, solution = parse_scene(data).solve()
print(f"{problem.n_free} unknowns, P = {solution.normal_force:.5f}, status {solution.report.status}")

fig, ax = plt.subplots(figsize=(7, 4))
tribo.plot.contact_pressure(problem, solution, ax=ax)
fig.tight_layout()
