"""tribo.plot: optional, not imported by tribo, every function takes ax=None and returns its Axes."""

from __future__ import annotations

import sys

import pytest

import tribo

pytest.importorskip("matplotlib")


def test_plot_is_not_imported_by_the_package() -> None:
    import subprocess

    code = "import sys, tribo; assert 'tribo.plot' not in sys.modules and 'matplotlib' not in sys.modules"
    subprocess.run([sys.executable, "-c", code], check=True)


def test_plots_return_axes(hertz: tribo.Problem) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from tribo import plot

    s = hertz.solve(mu=0.3)
    for draw in (plot.contact_pressure, plot.tangential, plot.von_mises):
        ax = draw(hertz, s)
        assert ax.has_data()
        _, given = plt.subplots()
        assert draw(hertz, s, given) is given
    ax = plot.von_mises(hertz, s, scale=1.0, window=(-0.2, 0.2, -0.2, 0.05), obstacle=True)
    assert ax.get_xlim() == (-0.2, 0.2)
    plt.close("all")
