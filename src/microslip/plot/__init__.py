"""Every figure of the program (matplotlib, an optional extra), labelled with units.

:mod:`~microslip.plot.core` holds the style, figure sizes, atomic saving and the loop plots
(``microslip loop --plot``); :mod:`~microslip.plot.paper` the paper's figures (Figs 1, 10-12,
the coupling figure) and the one-case planar figure (``microslip planar --plot``);
:mod:`~microslip.plot.sweep` the summary figures of ``microslip sweep``. This package may
import the computing packages (results, planar, the sweep specification) and
:mod:`microslip.io`, never the job runners (reproduce, cli); matplotlib is imported only when
a figure is drawn, so ``import microslip`` never imports it. Only the basics are imported
here; import the figures from their modules.
"""

from .core import COLOURS, new_figure, plot_damping, plot_loops, pyplot, save_figure

__all__ = ["COLOURS", "new_figure", "plot_damping", "plot_loops", "pyplot", "save_figure"]
