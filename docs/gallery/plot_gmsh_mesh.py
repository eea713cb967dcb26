"""
A Gmsh mesh through meshio
==========================

Any mesh meshio reads (Gmsh ``.msh``, VTK, XDMF, MED…) is a body: ``tribo.read_mesh`` takes its
triangles and the line elements tagged with physical names as edge sets. Here a mesh is written as a
Gmsh 2.2 file and read back, as one from Gmsh would be, then pressed 0.002 down over its whole top by a
rigid flat (Coulomb, μ = 0.2; clamped at the bottom): the figure shows the von Mises stress, highest at
the corners, where the clamped bottom and the friction on the top hold back the block's sideways expansion.
"""

from pathlib import Path
from tempfile import TemporaryDirectory

import matplotlib.pyplot as plt
import meshio
import numpy as np

import tribo
import tribo.plot

mesh = tribo.Mesh.rectangle((0.0, 2.0), (0.0, 1.0), 24, 12, diagonal="alternating")
names = sorted(mesh.edge_sets)
lines = np.vstack([mesh.edge_sets[n] for n in names])
tags = np.concatenate([np.full(len(mesh.edge_sets[n]), k + 1) for k, n in enumerate(names)])
msh = meshio.Mesh(
    np.column_stack([mesh.points, np.zeros(mesh.n_nodes)]),
    [("triangle", np.asarray(mesh.triangles)), ("line", lines)],
    cell_data={"gmsh:physical": [np.zeros(mesh.n_triangles, int), tags],
               "gmsh:geometrical": [np.zeros(mesh.n_triangles, int), tags]},
    field_data={n: np.array([k + 1, 1]) for k, n in enumerate(names)},
)
with TemporaryDirectory() as tmp:
    path = Path(tmp) / "block.msh"
    meshio.write(path, msh, file_format="gmsh22", binary=False)
    body = tribo.read_mesh(path)
print(f"read {body.n_nodes} nodes, {body.n_triangles} triangles, edge sets {sorted(body.edge_sets)}")

problem = tribo.Problem(body, young=200.0, poisson=0.3, clamped="bottom", contact="top",
                        obstacle=tribo.Obstacle.flat(), approach=0.002)
solution = problem.solve(mu=0.2)
fig, ax = plt.subplots(figsize=(7, 4))
tribo.plot.von_mises(problem, solution, ax=ax)
fig.tight_layout()
