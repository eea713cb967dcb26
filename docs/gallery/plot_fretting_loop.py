"""
A fretting loop
===============

The shipped scene ``fretting.toml``: the cylinder pressed, then moved back and forth along the block with
Coulomb friction (μ = 0.3). Here its amplitude is raised from 0.0045 to 0.0058, enough to reach gross
sliding (Q = μP) at the ends, and its mesh refined to h_min = 0.005. The friction force Q traces a hysteresis loop against the obstacle's
position: partial slip on the way out, stick again when the motion reverses, then slip the other way;
the area of the loop is the energy friction dissipates in a cycle.
"""

import matplotlib.pyplot as plt

import tribo
import tribo.plot
from tribo.scene import parse_scene, read_scene_data, scene_path

data = read_scene_data(scene_path("fretting"))
data["history"]["shift"] = [0.0, 0.0058, -0.0058, 0.0058]
data["discretization"]["h_min"] = 0.005
problem, history = parse_scene(data).solve_history()
ratio = max(abs(history.tangential_force)) / (0.3 * history.normal_force[-1])
print(f"{len(history)} steps, status {history.status}, Q/μP at most {ratio:.2f}")

fig, ax = plt.subplots(figsize=(6, 4.5))
tribo.plot.history_loop(history, ax=ax)
fig.tight_layout()
