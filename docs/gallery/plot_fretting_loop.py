"""
A fretting loop
===============

The shipped scene ``fretting.toml``: the cylinder pressed, then moved back and forth along the block with
Coulomb friction (μ = 0.3). The friction force Q traces a hysteresis loop against the obstacle's position:
partial slip, then back through stick when the motion reverses.
"""

import matplotlib.pyplot as plt

import tribo
import tribo.plot
from tribo.scene import scene_path

problem, history = tribo.load_scene(scene_path("fretting")).solve_history()
print(f"{len(history)} steps, status {history.status}")

fig, ax = plt.subplots(figsize=(6, 4.5))
tribo.plot.history_loop(history, ax=ax)
fig.tight_layout()
