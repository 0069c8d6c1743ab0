"""The main job's structure study: the damping the cantilever example's clamp gives its two
lowest bending modes, every model side by side (``microslip reproduce``; issue 23).

``modal --mesh ... --solver all`` on the cantilever of :func:`microslip.fe.examples.
cantilever_mesh` (24x6x2 C3D8I, the clamp of ``examples/cantilever.inp``'s README: aluminium
E 70000 MPa, nu 0.33, 2700 kg/m^3, mu 0.5, F_N 2000 N, stick slope 1e4 N/mm^3, ``fixed``
normal contact) for its out-of-plane and in-plane bending modes: each mode's JSON and figure,
and report lines with the verdicts. The command's own study
(:func:`microslip.meshdynamics.modalstudy.modal_study`) on a typed case, no command line.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ..fe.clamp import MeshClamp

__all__ = ["STRUCTURE_CLAMP", "STRUCTURE_MODES", "structure_study"]

#: The cantilever's clamp and material (N, MPa, N/mm^3); density 2700 kg/m^3, response set
#: ``response``.
STRUCTURE_CLAMP = MeshClamp("contact", "clamp", normal_force=2000.0, modulus=70000.0,
                            poisson_ratio=0.33, friction=0.5, stick_slope=1e4)
STRUCTURE_DENSITY = 2700.0
STRUCTURE_RESPONSE = "response"
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
    from ..meshdynamics.case import StructureCase
    from ..meshdynamics.modalstudy import ModalSettings, modal_study
    from ..plot.ownmesh import plot_compare

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
        case = StructureCase(str(mesh), STRUCTURE_CLAMP,
                             density=STRUCTURE_DENSITY, mode=number,
                             response_set=STRUCTURE_RESPONSE)
        out = modal_study(case, ModalSettings(amplitudes=amplitudes)).to_dict()
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
