"""
A half model on a symmetry line
===============================

The Hertz block cut along its symmetry line x = 0: the right half, with a roller on the cut (u·n = 0, the
symmetry condition), pressed by the same cylinder. Its contact force is half the full model's to
round-off (the graded meshes match), at half the unknowns.
"""

import matplotlib.pyplot as plt

import tribo
import tribo.plot


def graded(x: tuple[float, float], segment: tuple[float, float]) -> tribo.Mesh:
    return tribo.Mesh.graded_rectangle(x, (-2.0, 0.0), side="top", segment=segment, h_max=0.5, h_min=0.005)


cylinder = tribo.Obstacle.circle(1.0)
common = dict(young=200.0, poisson=0.3, contact="top", obstacle=cylinder, approach=0.01)
full = tribo.Problem(graded((-2.0, 2.0), (-0.3, 0.3)), clamped="bottom", **common)
half = tribo.Problem(graded((0.0, 2.0), (0.0, 0.3)),
                     supports=[tribo.Support.clamp("bottom"), tribo.Support.roller("left")], **common)
p_full, p_half = full.solve().normal_force, half.solve().normal_force
print(f"full: {full.n_free} unknowns, P = {p_full:.8f}; half: {half.n_free} unknowns, 2 P = {2 * p_half:.8f}")

solution = half.solve()
fig, ax = plt.subplots(figsize=(7, 4))
tribo.plot.von_mises(half, solution, ax=ax, scale=1.0, window=(0.0, 0.3, -0.25, 0.02), obstacle=True)
fig.tight_layout()
