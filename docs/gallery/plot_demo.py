"""
The demo: a cylinder indenting a block with Coulomb friction
=============================================================

``tribo demo`` runs ``scenes/demo.toml``: a rigid cylinder (R = 1) pushed 0.01 into a block and shifted
0.004 along it, Coulomb friction μ = 0.3, the mesh refined adaptively until the estimated error of the
contact tractions is below 1 %. The same from Python, with the contact pressure and the friction stress
against its bound μλ_n.
"""

import matplotlib.pyplot as plt

import tribo
import tribo.plot
from tribo.scene import demo_scene_path

scene = tribo.load_scene(demo_scene_path())
adaptive = scene.solve_adaptive()
problem, solution = adaptive.problem, adaptive.solution
print(f"{len(adaptive.levels)} levels, {problem.n_free} unknowns, status {solution.report.status}")
print(f"estimated relative error of the tractions: {adaptive.levels[-1].relative:.3f}")

fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
tribo.plot.contact_pressure(problem, solution, ax=top)
tribo.plot.tangential(problem, solution, ax=bottom)
fig.tight_layout()
