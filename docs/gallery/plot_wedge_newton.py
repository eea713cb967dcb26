"""
Where the Coulomb fixed point fails: a wedge forced into a groove
=================================================================

A wedge of half-angle α = 20° is pushed into a rigid V-groove of the same angle by a load on its top, and held by
nothing else (Coulomb friction, μ = 0.5). Sliding in, each flank balances the load with λ_n sin α + μ λ_n cos α;
the fixed point of the paper freezes the friction bound at the previous λ_n and multiplies its error by about
−μ cot α = −1.37: it two-cycles. The semismooth Newton method, whose bound follows λ_n, converges, and so does the
fixed point relaxed by ½ (``fp_relaxation``). The groove is a rigid ``Obstacle.profile``: the polyline from the
top of its left flank down to the tip and up its right flank, the groove on its right.
"""

import math

import matplotlib.pyplot as plt
import numpy as np

import tribo

n, alpha = 16, math.radians(20.0)
width = math.tan(alpha)
ids = {}
points = []
for j in range(n + 1):
    for i in range(j + 1):
        ids[i, j] = len(points)
        points.append((width * (2 * i - j) / n, j / n))
triangles = [t for j in range(n) for i in range(j + 1)
             for t in ([(ids[i, j], ids[i + 1, j + 1], ids[i, j + 1])]
                       + ([(ids[i, j], ids[i + 1, j], ids[i + 1, j + 1])] if i < j else []))]
flanks = [(ids[0, j + 1], ids[0, j]) for j in range(n)] + [(ids[j, j], ids[j + 1, j + 1]) for j in range(n)]
top = [(ids[i + 1, n], ids[i, n]) for i in range(n)]
mesh = tribo.Mesh(np.array(points), np.array(triangles), {"flanks": np.array(flanks), "top": np.array(top)})
groove = tribo.Obstacle.profile([(-math.sin(alpha), math.cos(alpha)), (0.0, 0.0), (math.sin(alpha), math.cos(alpha))])
problem = tribo.Problem(mesh, young=1.0, poisson=0.3, contact="flanks", obstacle=groove,
                        tractions={"top": (0.0, -1e-3)})

runs = {
    "fixed point": problem.solve(mu=0.5, coulomb="fixed_point", fp_max_iter=60),
    "fixed point relaxed by ½": problem.solve(mu=0.5, coulomb="fixed_point", fp_relaxation=0.5),
    "Newton": problem.solve(mu=0.5, coulomb="newton"),
}
fig, ax = plt.subplots(figsize=(7, 4))
for name, s in runs.items():
    r = s.report
    print(f"{name}: {r.status} after {r.iterations} iterations, P = {s.normal_force:.6f}")
    ax.semilogy(np.arange(1, len(r.residual_history) + 1), r.residual_history, marker=".", label=f"{name} ({r.status})")
ax.set_xlabel("iteration (QPs of the fixed point, steps of Newton)")
ax.set_ylabel("report.residual_history")
ax.legend(fontsize="small")
fig.tight_layout()
