"""Plots of every shape (issue 12): the drawing reads only the chain, so every shape, a chain
on piers and a limit-analysis figure render (oracle: the figure holds one patch per block plus
the two supports, and the hinges drawn are the analysis's)."""

import math

import matplotlib.pyplot as plt
import pytest

from archquake.geometry import SHAPES, Arch, OnPiers, Piers, ShapedArch
from archquake.limit import limit_analysis
from archquake.plotting.arch import plot_arch, plot_limit_analysis, plot_shapes

RISE = {"circular": 5.0, "segmental": 3.0, "pointed": 7.0, "elliptical": 3.5,
        "three-centred": 3.5, "parabolic": 4.0, "catenary": 4.0}


@pytest.mark.parametrize("shape", SHAPES)
def test_every_shape_draws_one_patch_per_block(shape):
    arch = ShapedArch(shape, 10.0, RISE[shape], 0.6, 9, "vertical")
    ax = plot_arch(arch)
    assert len(ax.patches) == arch.voussoirs + 2
    plt.close(ax.figure)


def test_piers_limit_analysis_figure_and_gallery(tmp_path):
    res = limit_analysis(OnPiers(Arch(5.0, 0.75, math.pi, 21), Piers(4.0, 1.5, 4)))
    ax = plot_limit_analysis(res)
    marked = [line for line in ax.lines if line.get_label() == "hinges"][0]
    assert list(marked.get_xdata()) == pytest.approx([h.x for h in res.mechanism.hinges])
    assert "piers" in ax.get_title()
    plt.close(ax.figure)
    fig = plot_shapes([Arch(5.0, 0.6, math.pi, 9), ShapedArch("pointed", 10.0, 7.0, 0.6, 9)])
    fig.savefig(tmp_path / "g.png")
    plt.close(fig)
