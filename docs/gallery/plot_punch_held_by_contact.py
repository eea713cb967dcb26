"""
A punch held only by the contact
================================

Two elastic blocks: the lower one clamped at its bottom, the upper one held sideways by a roller on its
left side and pushed down by a uniform traction on its top, with nothing holding it vertically but the
contact (``problem/floating.rs``). The contact carries the whole load; the pressure is close to two-body
Hertz for the combined modulus.
"""

import matplotlib.pyplot as plt

import tribo
import tribo.plot


def block(y: tuple[float, float], side: str) -> tribo.Mesh:
    return tribo.Mesh.graded_rectangle((-2.0, 2.0), y, side=side, segment=(-0.15, 0.15), h_max=0.5,
                                       h_min=0.005)


lower = tribo.Body("lower", block((-2.0, 0.0), "top"), young=200.0, poisson=0.3, clamped="bottom")
upper = tribo.Body("upper", block((0.0, 2.0), "bottom"), young=200.0, poisson=0.3,
                   supports=tribo.Support.roller("left"), tractions={"top": (0.0, -0.07)})
problem = tribo.Problem.two_bodies(lower, upper, secondary="lower.top", primary="upper.bottom",
                                   gap=tribo.Obstacle.parabola(1.0))
solution = problem.solve()
print(f"P = {solution.normal_force:.6f} (the load: {4 * 0.07:.6f}), QP by {solution.report.qp_methods}")

fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4))
tribo.plot.contact_pressure(problem, solution, ax=left)
tribo.plot.von_mises(problem, solution, ax=right, scale=1.0, window=(-0.25, 0.25, -0.2, 0.2))
fig.tight_layout()
