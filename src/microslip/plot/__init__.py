"""Every figure of the program (matplotlib, an optional extra), labelled with units.

:mod:`~microslip.plot.core` holds the style, figure sizes, atomic saving and the loop plots
(``microslip loop --plot``); :mod:`~microslip.plot.paper` the paper's figures (Figs 1, 10-12,
the coupling figure) and the one-case planar figure (``microslip planar --plot``);
:mod:`~microslip.plot.sweep` the summary figures of ``microslip sweep``;
:mod:`~microslip.plot.fit` the figure of ``microslip fit``; :mod:`~microslip.plot.dynamics`
the figures of ``microslip joint``, ``modal`` and ``frf`` and the reduced joint against the
FE (Fig. 13 of the reproduction); :mod:`~microslip.plot.validation` Figs 8 and 9 of
``microslip validate``; :mod:`~microslip.plot.report` the SVG figures of ``microslip report``.
The callers compute, these modules only draw; no module outside this package imports
matplotlib (tests/test_plot_home.py). This package may import the computing packages
(results, planar, the sweep specification) and :mod:`microslip.io`, never the job runners
(reproduce, report, validate, cli); matplotlib is imported only when a figure is drawn, so
``import microslip`` never imports it. Only the basics are imported here; import the figures
from their modules.
"""

from .core import COLOURS, new_figure, plot_damping, plot_loops, pyplot, save_figure

__all__ = ["COLOURS", "new_figure", "plot_damping", "plot_loops", "pyplot", "save_figure"]
