"""
Cattaneo–Mindlin: a stick zone that shrinks as two bodies are sheared
=====================================================================

Two equal elastic blocks meet along a parabolic gap (two-body Hertz); the upper one is pressed down by its
top, then moved along x (Coulomb friction, μ = 0.3) in a loading history. For equal materials the normal
and tangential problems uncouple (Dundurs' β = 0), and the central stick zone shrinks as Cattaneo and
Mindlin's c/a = √(1 − Q/μP) says; study 9 measures it against the mesh. The friction stress λ_t is drawn
against its bound μλ_n at three steps.
"""

import matplotlib.pyplot as plt
import numpy as np

import tribo
import tribo.plot


def block(y: tuple[float, float], side: str) -> tribo.Mesh:
    return tribo.Mesh.graded_rectangle((-2.0, 2.0), y, side=side, segment=(-0.15, 0.15), h_max=0.5,
                                       h_min=0.0025)


lower = tribo.Body("lower", block((-2.0, 0.0), "top"), young=200.0, poisson=0.3, clamped="bottom")
upper = tribo.Body("upper", block((0.0, 1.0), "bottom"), young=200.0, poisson=0.3,
                   supports=tribo.Support.displacement("top", x=0.0, y=-0.01))
problem = tribo.Problem.two_bodies(lower, upper, secondary="lower.top", primary="upper.bottom",
                                   gap=tribo.Obstacle.parabola(1.0))
x = np.linspace(0.0, 0.0036, 7)
history = problem.solve_history(displacements={"upper.top.x": x}, mu=0.3)
print(f"{len(history)} steps, status {history.status}")
for k in range(1, len(history)):
    ratio = abs(history.tangential_force[k]) / (0.3 * history.normal_force[k])
    c_over_a = np.ptp(history.stick_zone[k]) / np.ptp(history.contact_zone[k])
    print(f"Q/μP = {ratio:.2f}: c/a = {c_over_a:.2f}, Cattaneo–Mindlin {np.sqrt(1.0 - ratio):.2f}")

fig, ax = plt.subplots(figsize=(7, 4))
tribo.plot.history_tractions(history, [2, 4, 6], ax=ax, problem=problem)
ax.set_xlim(-0.15, 0.15)
fig.tight_layout()
