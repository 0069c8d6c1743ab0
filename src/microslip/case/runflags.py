"""The options of the option table that no case file sets: output, run control, numerics.

Part of the one option table (:mod:`.table` merges them into
:data:`~microslip.case.table.OPTIONS`): each :class:`~.table.Option` here has its name,
type, unit, range and meaning once, and every command that takes it adds it with
:func:`~.table.add_option` (giving its own default, or a sentence of its own after the shared
help). Options whose choices come from a library registry (``--poisson``, ``--history``, ...)
take them from there when a command adds them (``choices=``), so that the parser does not
import the library to build the table.

Units: N, mm, MPa, Hz, kg, kg/m^3, s.
"""

from __future__ import annotations

import argparse

from ..conventions import MAX_ROM_MODES
from .checks import Option, set_name

__all__ = ["EXIT_STATUS", "EXIT_UNSETTLED", "RUN_OPTIONS", "positive_int", "seed"]

#: The exit status of a run whose result did not settle (W per cycle still changing after
#: the last cycle): the figures are printed, but a script must not take them as converged.
#: ``--accept-unsettled`` makes it 0. (1: an error, 2: a usage mistake, 130: interrupted.)
EXIT_UNSETTLED = 3

#: The exit statuses of every command, as the help's epilog states them.
EXIT_STATUS = (f"exit status: 0 done; 1 an error (one line on stderr); 2 a usage mistake; "
               f"{EXIT_UNSETTLED} a result that did not settle (W per cycle still changing: "
               "fe --mesh FILE, its --convergence, validate --mesh FILE; --accept-unsettled "
               "makes it 0); 130 interrupted")



def positive_int(text: str) -> int:
    """argparse type: a whole number >= 1."""
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a whole number: {text!r}") from None
    if n < 1:
        raise argparse.ArgumentTypeError(f"must be >= 1, got {n}")
    return n


def seed(text: str) -> int:
    """argparse type: a random seed in [0, 2^63)."""
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a whole number: {text!r}") from None
    if not 0 <= n < 2**63:
        raise argparse.ArgumentTypeError(f"must be in [0, 2^63), got {n}")
    return n


def _flag(name: str, help: str, spelling: str | None = None) -> Option:
    """An on/off option (``store_true``)."""
    return Option(name, help, type=None, action="store_true", spelling=spelling, default=False)


RUN_OPTIONS: tuple[Option, ...] = (
    # -- output and run control (every command's own meaning of the file in its help)
    _flag("json", "print one JSON object"),
    Option("plot", "write a figure (.png, .pdf or .svg)", "", "a file name", type=None,
           metavar="FILE.png"),
    Option("csv", "write the table as CSV", "", "a file name", type=None, metavar="FILE.csv"),
    Option("out", "the output: a file or a directory, as the command says", "", "a path",
           type=None, metavar="PATH"),
    Option("case", "read the joint and load case from a TOML case file (microslip case new "
           "FILE.toml writes a template); options given here win", "", "a path", type=None,
           metavar="FILE.toml"),
    _flag("overwrite", "overwrite an existing file", spelling="--force"),
    _flag("no_progress", "no progress bar"),
    _flag("quiet", "no progress display"),
    Option("scheduler", "a dask.distributed scheduler (tcp://HOST:8786) to run on", "",
           "an address", type=None, metavar="ADDRESS"),
    Option("threads", "threads of the solver", "", ">= 1", type=int, metavar="N", default=1),
    Option("workers", "local processes for the amplitudes (independent runs)", "", ">= 1",
           type=int, metavar="N"),
    Option("timeout", "stop each solver run after S seconds", "s", "> 0", metavar="S"),
    _flag("reuse", "read job directories that already hold a run of the identical deck"),
    _flag("no_vtu", "do not write the VTU files"),
    # -- the clamp's preset and the 1-D models' reading
    Option("preset", "paper parameter set", "", "a preset of microslip.params", type=None,
           default="table1"),
    Option("tip_preset", "parameters of the tip model", "", "a preset", type=None,
           default="table2-tip"),
    Option("centre_preset", "parameters of the centre model", "", "a preset", type=None,
           default="table2-centre"),
    Option("tip_symmetry", "tip models in parallel in the whole clamp (2: the paper's tip model "
           "is one symmetric half)", "", ">= 1", type=int, metavar="K"),
    _flag("no_corrections", "switch off the Poisson and length updates (rigid-foundation "
           "limit)"),
    Option("poisson", "Poisson update of the cross-section", "", "a reading", type=None,
           default="consistent"),
    _flag("no_length_update", "keep the clamped length constant (no L + delta)"),
    Option("centre_reading", "centre model: physical (F/2 per half, a = F/2q, macroslip at "
           "mu F_N) or paper (Eq. 11 as printed, macroslip at 2 mu F_N)", "", "a reading",
           type=None, default="physical"),
    _flag("paper_literal", "every equation as printed (Eqs 6-7 total force, Eq. 15 sign, "
           "Eq. 11)"),
    Option("strain_energy", "definition of U in eta = W_d/(2 pi U)", "", "a definition",
           type=None),  # default: microslip.energy's (importing it here costs the models)
    Option("work_energy", "U of the combined motion in the work-based eta", "", "a definition",
           type=None),
    _flag("no_shear_lag", "leave out the body's through-thickness shear compliance (then a "
           "very large --stick-slope gives the rigid foundation exactly)"),
    Option("displacement_amplitude", "displacement amplitude d0 of the loaded section: the "
           "force amplitude is the one whose first loading reaches d0 (instead of "
           "--amplitude)", "mm", "> 0", metavar="MM"),
    Option("increments", "force increments of each first loading", "", ">= 10", type=int,
           metavar="N", default=1000),
    Option("levels", "how R maps onto the paper's amplitude levels", "", "a scheme",
           type=None, metavar="SCHEME", default="base"),
    Option("samples_per_cycle", "samples of the work-based cycle", "", ">= 1", type=int,
           metavar="N", default=2048),
    # -- the finite elements
    Option("fe_solver", "the FE solver", "", "builtin | calculix", type=None,
           default="builtin"),
    Option("substeps", "equal substeps over t = 0..1.25 s, a multiple of 5", "",
           "a multiple of 5", type=int, metavar="N", default=50),
    Option("element", "calculix: the 20-node brick with reduced integration (C3D20R)", "",
           "an element", type=None),
    Option("clamping_csv", "builtin: write the interface pressure after clamping (x_mm,"
           "pressure in MPa, the mean over the width per section)", "", "a file name",
           type=None, metavar="FILE"),
    Option("cycles", "load cycles to run", "", ">= 1", type=int, metavar="N"),
    Option("increments_per_cycle", "load increments per cycle", "", ">= 1", type=int,
           metavar="N", default=256),
    Option("cycle_tolerance", "relative change of W per cycle taken as settled", "", "> 0",
           metavar="X", default=1e-3),
    Option("load", "a load F(t) = A sin(2 pi t + phase) on a set of the mesh, as a uniform "
           "traction of total force A (N) along (DX, DY, DZ); repeat for several loads "
           "(planar: two loads at 90 degrees)", "", "SET:DX,DY,DZ:AMPLITUDE[:PHASE_DEG]",
           type=None, metavar="SET:DX,DY,DZ:AMPLITUDE[:PHASE_DEG]", action="append"),
    Option("history", "the load history of the mesh's run", "", "a history", type=None),
    Option("settle_tol", "builtin: relative change of W per cycle that counts as settled", "",
           "> 0", metavar="X"),
    Option("max_cycles", "builtin: at most N cycles before W settles", "", ">= 1", type=int,
           metavar="N"),
    _flag("accept_unsettled", f"exit 0 with a result whose W per cycle did not settle (by "
          f"default such a result exits with status {EXIT_UNSETTLED}, its figures printed)"),
    # -- the structure on a mesh: its reduced models and loads
    Option("rom_modes", "fixed-interface modes kept in the contact-node ROM, the lowest N", "",
           f"[1, {MAX_ROM_MODES}]", type=int, metavar="N"),
    Option("cutoff_frequency", "keep every fixed-interface mode below HZ", "Hz", "> 0",
           metavar="HZ"),
    Option("backbone", "joint: the whole joint's backbone, the FE's own first loading by the "
           "mode (fe), the same with work-equivalent displacements (work), or the paper's 1-D "
           "clamp model on the contact patch (tip, centre)", "", "a backbone", type=None),
    Option("load_set", "node set that carries the force F (N, each --force), spread equally "
           "over its nodes", "", "a set name of the mesh file", type=set_name,
           metavar="NAME"),
    Option("load_direction", "direction of the force, global axes", "", "DX,DY,DZ", type=None,
           metavar="DX,DY,DZ"),
    # -- a structure: one mode, or a file
    Option("frequency", "natural frequency with the joint removed", "Hz", "> 0", metavar="HZ"),
    Option("stuck_frequency", "natural frequency with the joint stuck (as measured at low "
           "amplitude); the frequency with the joint removed follows from the joint's initial "
           "stiffness", "Hz", "> 0", metavar="HZ"),
    Option("modal_mass", "modal mass", "kg", "> 0", metavar="KG"),
    Option("damping_ratio", "linear viscous damping ratio, c = 2 X m (2 pi f)", "", "[0, 1)",
           metavar="X"),
    Option("participation", "joint displacement per unit modal displacement", "", "!= 0",
           metavar="X"),
    Option("joint_dof", "a joint between DOF I (0-based) and the ground, or I J between two "
           "DOFs; give it twice for a two-directional joint (one per direction); replaces the "
           "file's joints", "", "I or I J", type=int, metavar="I", nargs="+",
           action="append"),
    Option("method", "epmc: the extended periodic motion concept with harmonic balance; "
           "energy: the energy method from the joint's describing function", "", "a method",
           type=None),
    Option("samples", "time samples per period", "", ">= 1", type=int, metavar="N"),
    Option("amplitude_range", "amplitudes from MIN to MAX", "", "0 < MIN <= MAX", nargs=2,
           metavar=("MIN", "MAX")),
    Option("amplitudes", "number of amplitudes", "", ">= 1", type=int, metavar="N",
           default=20),
    Option("force_range", "force amplitudes, N, below the macroslip force (geometric "
           "spacing)", "N", "0 < MIN <= MAX", nargs=2, metavar=("MIN", "MAX")),
    Option("force", "excitation amplitude (repeat for several curves): a modal force on "
           "--mode, or a force on each --excitation DOF", "N", "> 0", metavar="N",
           action="append"),
    Option("excitation", "--structure: forced DOFs (0-based), each by F cos(2 pi f t)", "",
           "DOF numbers", type=int, metavar="I", nargs="+"),
    Option("frequency_range", "excitation frequencies", "Hz", "0 < MIN < MAX", nargs=2,
           metavar=("MIN", "MAX")),
    Option("step", "largest continuation step, relative to the frequency range and the peak "
           "amplitude", "", "> 0", metavar="S"),
    # -- sweeps and fits
    Option("ratio_range", "planar: force ratios R from A to B, geometrically spaced", "",
           "0 < A <= B", nargs=2, metavar=("A", "B")),
    Option("cases", "number of points of --amplitude-range or --ratio-range", "", ">= 1",
           type=positive_int, metavar="N"),
    Option("grid", "a grid axis, e.g. friction=0.4:0.8:5 or E=70000,210000 (repeatable)", "",
           "NAME=SPEC", type=None, metavar="NAME=SPEC", action="append"),
    Option("sample", "a randomly drawn parameter, e.g. friction=normal:0.8:0.05 (repeatable)",
           "", "NAME=DIST:A:B", type=None, metavar="NAME=DIST:A:B", action="append"),
    Option("seed", "seed of the random draws; the same seed writes the same file", "",
           "[0, 2^63)", type=seed, metavar="S"),
    Option("chunk_size", "cases per chunk / Dask task", "", ">= 1", type=positive_int,
           metavar="N", default=65536),
    Option("retries", "retries of a failed Dask task", "", ">= 0", type=int, metavar="N",
           default=3),
    Option("fit", "parameters to identify", "", "parameter names", type=None, metavar="NAME",
           nargs="+"),
    Option("confidence", "confidence level of the intervals", "", "[0.5, 1)", metavar="X",
           default=0.95),
    # -- reproduce and report
    Option("fe", "run the finite elements", "", "", type=None,
           action=argparse.BooleanOptionalAction),
    Option("structure_study", "the damping of the cantilever example's two bending modes from "
           "its mesh: full FE, contact-node ROM and whole joint side by side", "", "",
           type=None, action=argparse.BooleanOptionalAction),
    _flag("no_fe", "leave the FE runs out (faster)"),
    _flag("bar", "a case of your own mesh: add the 1-D bar report of the case's preset or "
          "[geometry] beside the part's (its loops, damping, the 1-D model against the box "
          "FE); without it the page is about the mesh alone"),
)
