"""CalculiX input deck cards, one keyword card per function.

Every card is generated from validated inputs and is tested as an exact string; the decks
are :func:`~microslip.fe.calculix.meshdeck.build_mesh_deck`'s (the user's mesh, an assembly
and the paper's box alike).

Units: N, mm, MPa.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable, Sequence

import numpy as np
from numpy.typing import ArrayLike

from ...errors import ParameterError

__all__ = [
    "CONTACT_PAIR_TYPES",
    "LOAD_AMPLITUDE",
    "LOAD_NSET",
    "amplitude_card",
    "boundary_card",
    "cload_card",
    "contact_file_card",
    "contact_pair_card",
    "controls_card",
    "dload_card",
    "elements_card",
    "elset_card",
    "end_step_card",
    "heading_card",
    "material_card",
    "node_file_card",
    "node_print_card",
    "nodes_card",
    "nset_card",
    "solid_section_card",
    "static_card",
    "step_card",
    "surface_card",
    "surface_interaction_card",
]

#: Name of the node set of the loaded section (its displacements go to the .dat file).
LOAD_NSET = "NLOAD"
#: Name of the amplitude of the tangential load.
LOAD_AMPLITUDE = "FT"

_NAME = re.compile(r"[A-Za-z][A-Za-z0-9_]{0,79}\Z")
_PER_LINE = 16  # entries per data line of a set


def _name(kind: str, value: str) -> str:
    if not isinstance(value, str) or not _NAME.match(value):
        raise ParameterError(
            f"{kind} name must be a letter followed by up to 79 letters, digits or '_', "
            f"got {value!r}")
    return value.upper()


def _num(x: float, what: str = "value", *, positive: bool = False) -> str:
    """A finite float in the shortest form that reads back to 12 significant digits."""
    try:
        v = float(x)
    except (TypeError, ValueError):
        raise ParameterError(f"{what} must be a number, got {x!r}") from None
    if not math.isfinite(v) or (positive and v <= 0.0):
        rule = "finite and > 0" if positive else "finite"
        raise ParameterError(f"{what} must be {rule}, got {x!r}")
    if v == 0.0:
        return "0"
    return format(v, ".12g")


def _ids(ids: ArrayLike, what: str) -> list[int]:
    a = np.asarray(ids)
    if a.ndim != 1 or a.size == 0 or not np.issubdtype(a.dtype, np.integer) or np.any(a < 1):
        raise ParameterError(f"{what} must be a non-empty list of positive integers")
    return [int(v) for v in a]


def _rows(values: Sequence[str], per_line: int = _PER_LINE) -> str:
    return "".join(", ".join(values[i:i + per_line]) + "\n"
                   for i in range(0, len(values), per_line))


def heading_card(title: str) -> str:
    """``*HEADING`` with a one-line title.

    >>> heading_card("tip load")
    '*HEADING\\ntip load\\n'
    """
    if not isinstance(title, str) or "\n" in title or title.lstrip().startswith("*"):
        raise ParameterError("heading must be one line that does not start with '*'")
    return f"*HEADING\n{title}\n"


def nodes_card(coords: ArrayLike, first: int = 1) -> str:
    """``*NODE``: one line ``id, x, y, z`` per node (mm), ids from ``first``.

    >>> nodes_card([[0.0, 0.0, 0.0], [12.7, 0.0, 3.18]])
    '*NODE\\n1, 0, 0, 0\\n2, 12.7, 0, 3.18\\n'
    """
    xyz = np.asarray(coords, dtype=float)
    if xyz.ndim != 2 or xyz.shape[1] != 3 or xyz.shape[0] == 0:
        raise ParameterError("node coordinates must have shape (n, 3)")
    if not np.all(np.isfinite(xyz)):
        raise ParameterError("node coordinates must be finite")
    lines = [f"{first + i}, {_num(x)}, {_num(y)}, {_num(z)}" for i, (x, y, z) in enumerate(xyz)]
    return "*NODE\n" + "\n".join(lines) + "\n"


_NODES_PER_ELEMENT = {"C3D20R": 20, "C3D20": 20, "C3D8": 8, "C3D8R": 8, "C3D8I": 8}


def elements_card(etype: str, elset: str, connectivity: ArrayLike, first: int = 1) -> str:
    """``*ELEMENT``: element id then its nodes; 20-node lines continue after 15 nodes.

    >>> elements_card("C3D8", "BASE", [[1, 2, 3, 4, 5, 6, 7, 8]], first=9)
    '*ELEMENT, TYPE=C3D8, ELSET=BASE\\n9, 1, 2, 3, 4, 5, 6, 7, 8\\n'
    """
    if etype not in _NODES_PER_ELEMENT:
        raise ParameterError(
            f"element type must be one of {', '.join(_NODES_PER_ELEMENT)}, got {etype!r}")
    conn = np.asarray(connectivity)
    n = _NODES_PER_ELEMENT[etype]
    if (conn.ndim != 2 or conn.shape[1] != n or conn.shape[0] == 0
            or not np.issubdtype(conn.dtype, np.integer) or np.any(conn < 1)):
        raise ParameterError(f"{etype} connectivity must be positive node ids, shape (m, {n})")
    out = [f"*ELEMENT, TYPE={etype}, ELSET={_name('element set', elset)}"]
    for i, row in enumerate(conn):
        ids = [str(int(v)) for v in row]
        if n > 15:
            out.append(f"{first + i}, " + ", ".join(ids[:15]) + ",")
            out.append(", ".join(ids[15:]))
        else:
            out.append(f"{first + i}, " + ", ".join(ids))
    return "\n".join(out) + "\n"


def nset_card(name: str, ids: ArrayLike) -> str:
    """``*NSET``, 16 node ids per line.

    >>> nset_card("nload", [3, 1, 2])
    '*NSET, NSET=NLOAD\\n3, 1, 2\\n'
    """
    return f"*NSET, NSET={_name('node set', name)}\n" + _rows([str(i) for i in _ids(ids, name)])


def elset_card(name: str, ids: ArrayLike) -> str:
    """``*ELSET``, 16 element ids per line.

    >>> elset_card("ETOP", [21, 22])
    '*ELSET, ELSET=ETOP\\n21, 22\\n'
    """
    return (f"*ELSET, ELSET={_name('element set', name)}\n"
            + _rows([str(i) for i in _ids(ids, name)]))


_FACES = ("S1", "S2", "S3", "S4", "S5", "S6")


def surface_card(name: str, elements: ArrayLike, face: str) -> str:
    """Element-face ``*SURFACE``: the face ``face`` (S1 .. S6) of each element.

    >>> surface_card("SBOTTOM", [1, 2], "S1")
    '*SURFACE, NAME=SBOTTOM, TYPE=ELEMENT\\n1, S1\\n2, S1\\n'
    """
    if face not in _FACES:
        raise ParameterError(f"face must be one of {', '.join(_FACES)}, got {face!r}")
    ids = _ids(elements, name)
    return (f"*SURFACE, NAME={_name('surface', name)}, TYPE=ELEMENT\n"
            + "".join(f"{e}, {face}\n" for e in ids))


def material_card(name: str, modulus: float, poisson_ratio: float) -> str:
    """``*MATERIAL`` with ``*ELASTIC`` (isotropic): E in MPa, nu in [0, 0.5).

    >>> material_card("BAR", 68947.0, 0.3)
    '*MATERIAL, NAME=BAR\\n*ELASTIC\\n68947, 0.3\\n'
    """
    nu = _num(poisson_ratio, "poisson_ratio")
    if not 0.0 <= float(poisson_ratio) < 0.5:
        raise ParameterError(f"poisson_ratio must be in [0, 0.5), got {poisson_ratio!r}")
    return (f"*MATERIAL, NAME={_name('material', name)}\n*ELASTIC\n"
            f"{_num(modulus, 'modulus (MPa)', positive=True)}, {nu}\n")


def solid_section_card(elset: str, material: str) -> str:
    """``*SOLID SECTION`` assigning a material to an element set.

    >>> solid_section_card("BAR", "AL")
    '*SOLID SECTION, ELSET=BAR, MATERIAL=AL\\n'
    """
    return (f"*SOLID SECTION, ELSET={_name('element set', elset)}, "
            f"MATERIAL={_name('material', material)}\n")


def surface_interaction_card(name: str, normal_slope: float, friction: float,
                             stick_slope: float, tension: float | None = None) -> str:
    """``*SURFACE INTERACTION`` with a linear penalty law and Coulomb friction.

    ``*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR``: contact pressure = ``normal_slope``
    (N/mm^3) times the overclosure. ``*FRICTION``: coefficient mu and stick slope lambda
    (N/mm^3), the shear traction per unit of elastic (reversible) slip below mu p.
    ``tension`` (MPa): sigma_inf, the second value that node-to-surface contact needs (its
    law is p = K d (1/2 + atan(d / eps) / pi), eps = pi sigma_inf / K: the kink of p = K d
    rounded over eps, p -> K d - sigma_inf deep in contact, -sigma_inf far open).

    >>> print(surface_interaction_card("SI", 1e5, 0.8, 1e4), end="")
    *SURFACE INTERACTION, NAME=SI
    *SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR
    100000
    *FRICTION
    0.8, 10000
    >>> surface_interaction_card("SI", 1e5, 0.8, 1e4, tension=0.001).splitlines()[2]
    '100000, 0.001'
    """
    slope = _num(normal_slope, 'normal slope (N/mm^3)', positive=True)
    if tension is not None:
        slope += f", {_num(tension, 'tension at large clearance (MPa)', positive=True)}"
    return (f"*SURFACE INTERACTION, NAME={_name('interaction', name)}\n"
            "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n"
            f"{slope}\n"
            "*FRICTION\n"
            f"{_num(friction, 'friction coefficient', positive=True)}, "
            f"{_num(stick_slope, 'stick slope (N/mm^3)', positive=True)}\n")


#: ``*CONTACT PAIR`` types CalculiX takes (the deck's name -> the card's TYPE).
CONTACT_PAIR_TYPES = {"face-to-face": "SURFACE TO SURFACE", "node-to-surface": "NODE TO SURFACE"}


def contact_pair_card(interaction: str, slave: str, master: str,
                      kind: str = "face-to-face") -> str:
    """Penalty ``*CONTACT PAIR`` (slave surface first), face-to-face (the default) or
    node-to-surface (:data:`CONTACT_PAIR_TYPES`).

    >>> contact_pair_card("SI", "SBOTTOM", "SBASE")
    '*CONTACT PAIR, INTERACTION=SI, TYPE=SURFACE TO SURFACE\\nSBOTTOM, SBASE\\n'
    >>> contact_pair_card("SI", "SBOTTOM", "SBASE", "node-to-surface").split(", ")[2]
    'TYPE=NODE TO SURFACE\\nSBOTTOM'
    """
    if kind not in CONTACT_PAIR_TYPES:
        raise ParameterError(f"contact pair type must be one of {', '.join(CONTACT_PAIR_TYPES)}"
                             f", got {kind!r}")
    return (f"*CONTACT PAIR, INTERACTION={_name('interaction', interaction)}, "
            f"TYPE={CONTACT_PAIR_TYPES[kind]}\n{_name('surface', slave)}, "
            f"{_name('surface', master)}\n")


def boundary_card(rows: Iterable[tuple[str, int, int]]) -> str:
    """``*BOUNDARY``: (node set, first dof, last dof) held at zero.

    >>> boundary_card([("NBASE", 1, 3), ("NSYM", 2, 2)])
    '*BOUNDARY\\nNBASE, 1, 3, 0\\nNSYM, 2, 2, 0\\n'
    """
    out = ["*BOUNDARY"]
    for nset, a, b in rows:
        if not (isinstance(a, int) and isinstance(b, int) and 1 <= a <= b <= 3):
            raise ParameterError(f"boundary dofs must satisfy 1 <= first <= last <= 3, "
                                 f"got {a!r}, {b!r}")
        out.append(f"{_name('node set', nset)}, {a}, {b}, 0")
    if len(out) == 1:
        raise ParameterError("a *BOUNDARY card needs at least one row")
    return "\n".join(out) + "\n"


def amplitude_card(name: str, times: ArrayLike, values: ArrayLike) -> str:
    """Tabular ``*AMPLITUDE`` (step time, s; factor), four pairs per line.

    >>> amplitude_card("FT", [0.0, 0.5], [0.0, 1.0])
    '*AMPLITUDE, NAME=FT\\n0, 0, 0.5, 1\\n'
    """
    t = np.asarray(times, dtype=float)
    v = np.asarray(values, dtype=float)
    if t.ndim != 1 or t.shape != v.shape or t.size < 2:
        raise ParameterError("amplitude needs equal-length time and value lists (>= 2 points)")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(v)) and np.all(np.diff(t) > 0)):
        raise ParameterError("amplitude times must be finite and increasing, values finite")
    pairs = [f"{_num(a)}, {_num(b)}" for a, b in zip(t, v, strict=True)]
    return f"*AMPLITUDE, NAME={_name('amplitude', name)}\n" + _rows(pairs, 4)


def step_card(max_increments: int, nlgeom: bool = False) -> str:
    """``*STEP`` with the maximum number of increments.

    >>> step_card(100), step_card(60, nlgeom=True)
    ('*STEP, INC=100\\n', '*STEP, NLGEOM, INC=60\\n')
    """
    if not isinstance(max_increments, int) or max_increments < 1:
        raise ParameterError(f"max_increments must be an integer >= 1, got {max_increments!r}")
    return f"*STEP{', NLGEOM' if nlgeom else ''}, INC={max_increments}\n"


def static_card(increment: float, period: float, direct: bool) -> str:
    """``*STATIC``: initial (or, with ``DIRECT``, every) increment and step period, s.

    >>> static_card(0.025, 1.25, direct=True)
    '*STATIC, DIRECT\\n0.025, 1.25\\n'
    """
    inc = _num(increment, "increment (s)", positive=True)
    per = _num(period, "step period (s)", positive=True)
    if float(increment) > float(period):
        raise ParameterError(f"increment {increment} s exceeds the step period {period} s")
    return f"*STATIC{', DIRECT' if direct else ''}\n{inc}, {per}\n"


def controls_card(max_iterations: int) -> str:
    """Iterations allowed per increment (ccx's I_C; the other time controls keep defaults).

    >>> controls_card(26)
    '*CONTROLS, PARAMETERS=TIME INCREMENTATION\\n, , , 26\\n'
    """
    if not isinstance(max_iterations, int) or max_iterations < 4:
        raise ParameterError(f"max_iterations must be an integer >= 4, got {max_iterations!r}")
    return f"*CONTROLS, PARAMETERS=TIME INCREMENTATION\n, , , {max_iterations}\n"


def dload_card(elset: str, face: str, pressure: float) -> str:
    """``*DLOAD``: uniform pressure (MPa, positive into the face) on a face of each element.

    >>> dload_card("ETOP", "S2", 0.069)
    '*DLOAD\\nETOP, P2, 0.069\\n'
    """
    if face not in _FACES:
        raise ParameterError(f"face must be one of {', '.join(_FACES)}, got {face!r}")
    return (f"*DLOAD\n{_name('element set', elset)}, P{face[1]}, "
            f"{_num(pressure, 'pressure (MPa)', positive=True)}\n")


def cload_card(nodes: ArrayLike, dof: int, forces: ArrayLike, amplitude: str | None = None
               ) -> str:
    """``*CLOAD``: nodal forces (N) in one direction, optionally scaled by an amplitude.

    >>> cload_card([5, 6], 1, [-1.0, 4.0], amplitude="FT")
    '*CLOAD, AMPLITUDE=FT\\n5, 1, -1\\n6, 1, 4\\n'
    """
    ids = _ids(nodes, "loaded nodes")
    f = np.asarray(forces, dtype=float)
    if f.shape != (len(ids),) or not np.all(np.isfinite(f)):
        raise ParameterError("one finite force per loaded node is needed")
    if dof not in (1, 2, 3):
        raise ParameterError(f"load direction must be 1, 2 or 3, got {dof!r}")
    head = "*CLOAD" + (f", AMPLITUDE={_name('amplitude', amplitude)}" if amplitude else "")
    return head + "\n" + "".join(f"{n}, {dof}, {_num(v)}\n" for n, v in zip(ids, f, strict=True))


_NODE_KEYS = ("U", "RF")
_CONTACT_KEYS = ("CDIS", "CSTR")


def _keys(keys: Sequence[str], allowed: tuple[str, ...]) -> str:
    if not keys or any(k not in allowed for k in keys):
        raise ParameterError(f"output keys must be among {', '.join(allowed)}, got {keys!r}")
    return ", ".join(keys)


def node_print_card(nset: str, keys: Sequence[str] = ("U",)) -> str:
    """``*NODE PRINT`` of a node set to the ``.dat`` file at every increment.

    >>> node_print_card("NLOAD")
    '*NODE PRINT, NSET=NLOAD\\nU\\n'
    """
    return f"*NODE PRINT, NSET={_name('node set', nset)}\n{_keys(keys, _NODE_KEYS)}\n"


def node_file_card(keys: Sequence[str] = ("U",)) -> str:
    """``*NODE FILE``: nodal results of every node to the ``.frd`` file.

    >>> node_file_card()
    '*NODE FILE\\nU\\n'
    """
    return f"*NODE FILE\n{_keys(keys, _NODE_KEYS)}\n"


def contact_file_card(keys: Sequence[str] = _CONTACT_KEYS) -> str:
    """``*CONTACT FILE``: slips/opening (CDIS) and tractions (CSTR) at the slave nodes.

    >>> contact_file_card()
    '*CONTACT FILE\\nCDIS, CSTR\\n'
    """
    return f"*CONTACT FILE\n{_keys(keys, _CONTACT_KEYS)}\n"


def end_step_card() -> str:
    """``*END STEP``.

    >>> end_step_card()
    '*END STEP\\n'
    """
    return "*END STEP\n"
