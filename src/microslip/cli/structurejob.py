"""The main job's structure study: the damping the cantilever example's clamp gives its two
lowest bending modes, every model side by side (``microslip reproduce``; issue 23).

``modal --mesh ... --solver all`` on the cantilever of :func:`microslip.fe.examples.
cantilever_mesh` (24x6x2 C3D8I, the clamp of ``examples/cantilever.inp``'s README: aluminium
E 70000 MPa, nu 0.33, 2700 kg/m^3, mu 0.5, F_N 2000 N, stick slope 1e4 N/mm^3, ``fixed``
normal contact) for its out-of-plane and in-plane bending modes: each mode's JSON and figure,
and report lines with the verdicts. It lives in the command-line layer because it runs the
command's own code path (:func:`.modalcompare.run_all`).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

__all__ = ["STRUCTURE_ARGV", "STRUCTURE_MODES", "structure_study"]

#: The cantilever's clamp and material (N, MPa, N/mm^3, kg/m^3).
STRUCTURE_ARGV = ("--contact-set", "contact", "--clamp-set", "clamp", "--response-set",
                  "response", "--normal-force", "2000", "--friction", "0.5", "--stick-slope",
                  "1e4", "--modulus", "70000", "--poisson-ratio", "0.33", "--density", "2700")
#: Out-of-plane and in-plane bending.
STRUCTURE_MODES = (1, 2)
#: Amplitudes per mode, first slip to near gross sliding.
STRUCTURE_AMPLITUDES = 5


def structure_study(stage: Path, echo: Any = None, counts: tuple[int, int, int] = (24, 6, 2),
                    amplitudes: int = STRUCTURE_AMPLITUDES) -> tuple[list[Path], list[str]]:
    """Write ``structure/`` in ``stage``: the mesh (``counts`` elements), ``mode<N>.json`` and
    ``mode<N>.png`` per mode; return the files and the report's lines (Markdown)."""
    from ..fe.examples import cantilever_mesh
    from ..fe.meshfile import write_inp
    from ..io import write_json
    from ..plot.ownmesh import plot_compare
    from .main import build_parser
    from .modalcompare import run_all
    from .modalmesh import mesh_study

    folder = stage / "structure"
    folder.mkdir(parents=True, exist_ok=True)
    name = "cantilever_{}x{}x{}.inp".format(*counts)
    mesh = Path(write_inp(cantilever_mesh(*counts), folder / name))
    files = [mesh]
    lines = ["## The damping of the cantilever's modes (issue 23)", "",
             f"`microslip modal --mesh structure/{name} ... --solver all` "
             "(aluminium, F_N 2000 N, mu 0.5, stick slope 1e4 N/mm^3): the full FE's "
             "quasi-static modal analysis (the truth), the contact-node ROM, the interface-"
             "reduced ROM and the whole-joint model on one amplitude grid.", ""]
    for number in STRUCTURE_MODES:
        if echo is not None:
            echo(f"structure: mode {number} of the cantilever, every model")
        argv = ["modal", "--mesh", str(mesh), *STRUCTURE_ARGV, "--mode", str(number),
                "--amplitudes", str(amplitudes), "--solver", "all", "--json"]
        out = run_all(mesh_study(build_parser(argv).parse_args(argv)))[1]
        out["mesh"] = name  # the staged path is gone once the results are in place
        data, figure = folder / f"mode{number}.json", folder / f"mode{number}.png"
        write_json(data, out)
        plot_compare(out, figure)
        files += [data, figure]
        f = out["linear_frequencies_Hz"][number - 1]
        lines += [f"**Mode {number}** ({out['label']}, stuck {f:.6g} Hz; figure "
                  f"`structure/mode{number}.png`):", ""]
        lines += [f"- {v['verdict']}" for v in out["verdicts"].values()]
        lines.append("")
    return files, lines
