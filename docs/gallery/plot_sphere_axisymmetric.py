"""
A sphere on a flat: an axisymmetric body against 3D Hertz
=========================================================

The most common tribological test is three-dimensional, but a rigid sphere pressed on an elastic half-space is
axisymmetric: ``model="axisymmetric"`` solves it on the meridian section, x the radius and y the axis (the
shipped scene ``sphere``: a cylinder of radius and height 20, the sphere of radius 1 pushed 0.01). Forces are on
the whole turn; λ_n is drawn against Hertz's 3D pressure of the same force, a³ = 3PR/(4E*), and the hoop
stress σ_θθ (``stress_zz``) under the contact, compressive like the radial one.
"""

import math

import matplotlib.pyplot as plt
import numpy as np

import tribo
import tribo.plot
from tribo.scene import load_scene, scene_path

problem = load_scene(scene_path("sphere")).build()
solution = problem.solve()
e_star = 200.0 / (1.0 - 0.3**2)
print(f"{problem.n_free} unknowns, P = {solution.normal_force:.5f} on the whole turn, "
      f"Hertz for δ = 0.01: {4.0 / 3.0 * e_star * 0.01**1.5:.5f}")
a = (3.0 * solution.normal_force / (4.0 * e_star)) ** (1.0 / 3.0)
print(f"contact radius {solution.contact_width:.4f}, Hertz {a:.4f}")

fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4))
tribo.plot.contact_pressure(problem, solution, ax=left)
points, triangles = np.asarray(problem.mesh.points), np.asarray(problem.mesh.triangles)
near = points[triangles].mean(axis=1)
keep = (near[:, 0] < 2.5 * a) & (near[:, 1] > -2.5 * a)
image = right.tripcolor(points[:, 0], points[:, 1], triangles[keep], facecolors=np.asarray(solution.stress_zz)[keep],
                        cmap="viridis")
right.set_xlim(0.0, 2.5 * a)
right.set_ylim(-2.5 * a, 0.0)
right.set_aspect("equal")
right.set_xlabel("r")
right.set_ylabel("z")
right.set_title(r"hoop stress $\sigma_{\theta\theta}$ under the sphere", fontsize="medium")
fig.colorbar(image, ax=right)
fig.tight_layout()
print(f"largest compressive hoop stress {-min(solution.stress_zz):.3g} against p0 = "
      f"{3.0 * solution.normal_force / (2.0 * math.pi * a * a):.3g}")
