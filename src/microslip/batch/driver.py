"""The batch driver: validate once, dispatch to a kernel, return a named result."""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, fields
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..conventions import check_choice
from ..energy import DEFAULT_STRAIN_ENERGY, STRAIN_ENERGY, STRAIN_ENERGY_CODES
from ..errors import MacroslipError, ParameterError
from ..models import check_increments, check_small_strain, get_model
from ..models.contact import Contact, check_reading, check_strain_energy
from ..named import result
from ..options import ModelOptions
from ..params import ClampParams

__all__ = [
    "BACKENDS",
    "PARAM_FIELDS",
    "BatchInput",
    "BatchResult",
    "batch_damping",
    "check_range",
    "default_backend",
    "prepare_batch",
    "run_batch",
]

#: The clamped-zone fields, in ClampParams order, with their units.
PARAM_FIELDS: dict[str, str] = {
    "length": "mm",
    "width": "mm",
    "thickness": "mm",
    "modulus": "MPa",
    "poisson_ratio": "",
    "friction": "",
    "normal_force": "N",
}

#: Batch backends: ``numba`` (compiled, parallel) and ``python`` (the same kernels' source
#: run by the interpreter, each kernel's ``py_func``; slow, for benchmarks and tests only).
BACKENDS = ("numba", "python")

FloatArray = NDArray[np.float64]


def default_backend() -> str:
    """The backend used when none is named: ``numba``."""
    return BACKENDS[0]


@dataclass(frozen=True)
class BatchInput:
    """Validated, flattened inputs of one batch (1-D contiguous float64 arrays).

    Attributes
    ----------
    model : str
    shape : tuple of int
        Broadcast shape of the inputs; results are reshaped to it.
    amplitude : ndarray, shape (size,)
        Peak force F0 of each case, N.
    length, width, thickness, modulus, poisson_ratio, friction, normal_force : ndarray
        The clamped zone of each case (units as :class:`~microslip.params.ClampParams`).
    increments : int
    options : ModelOptions
    strain_energy_kind : str
    where : tuple of int
        (index of the first case among all cases, number of cases), for messages.
    contact : Contact or None
        The interface under every case (None: the paper's rigid foundation).
    """

    model: str
    shape: tuple[int, ...]
    amplitude: FloatArray
    length: FloatArray
    width: FloatArray
    thickness: FloatArray
    modulus: FloatArray
    poisson_ratio: FloatArray
    friction: FloatArray
    normal_force: FloatArray
    increments: int
    options: ModelOptions
    strain_energy_kind: str
    where: tuple[int, int | None] = (0, None)
    contact: Contact | None = None

    @property
    def size(self) -> int:
        return int(self.amplitude.shape[0])


@result
class BatchResult:
    """Damping of a batch of cases (paper Eqs 21-23), one value per case.

    Every array has the broadcast shape of the inputs (``shape``).

    Attributes
    ----------
    model : str
        A key of :data:`microslip.models.MODELS`.
    increments : int
        Force increments of each first loading.
    options : ModelOptions
    strain_energy_kind : str
        Definition of U (see :data:`microslip.energy.STRAIN_ENERGY`).
    amplitude : ndarray
        Peak force F0, N.
    peak_displacement : ndarray
        d0, mm.
    dissipated_energy : ndarray
        W_d, N·mm (Eq. 21, trapezoidal closed integral around the Masing loop).
    strain_energy : ndarray
        U, N·mm.
    loss_factor : ndarray
        eta = W_d / (2 pi U) (Eq. 23).
    backend : str
        Which implementation computed it (see :data:`BACKENDS`).
    """

    model: str
    increments: int
    options: ModelOptions
    strain_energy_kind: str
    amplitude: FloatArray
    peak_displacement: FloatArray
    dissipated_energy: FloatArray
    strain_energy: FloatArray
    loss_factor: FloatArray
    backend: str

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(self.loss_factor.shape)

    @property
    def size(self) -> int:
        return int(self.loss_factor.size)

    def summary(self) -> dict[str, FloatArray]:
        """The result columns, named with their units."""
        return {
            "amplitude_N": self.amplitude,
            "peak_displacement_mm": self.peak_displacement,
            "dissipated_energy_Nmm": self.dissipated_energy,
            "strain_energy_Nmm": self.strain_energy,
            "loss_factor": self.loss_factor,
        }


def _param_values(params: ClampParams | Mapping[str, ArrayLike]) -> dict[str, Any]:
    if isinstance(params, ClampParams):
        return params.as_dict()
    if not isinstance(params, Mapping):
        raise ParameterError(
            f"params must be ClampParams or a mapping of {', '.join(PARAM_FIELDS)}; "
            f"got {type(params).__name__}"
        )
    unknown = sorted(set(params) - set(PARAM_FIELDS))
    if unknown:
        raise ParameterError(
            f"unknown parameter {unknown[0]!r}; choose from {', '.join(PARAM_FIELDS)}"
        )
    missing = [k for k in PARAM_FIELDS if k not in params]
    if missing:
        raise ParameterError(f"params lacks {', '.join(missing)}")
    return dict(params)


def _as_float(name: str, value: ArrayLike) -> FloatArray:
    try:
        return np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be numbers, got {value!r}") from None


def _case(i: int, size: int, where: tuple[int, int | None] = (0, None)) -> str:
    offset, total = where
    total = size if total is None else total
    return f" (case {offset + i} of {total})" if total > 1 else ""


def check_range(name: str, x: FloatArray, unit: str, *, lower: float = 0.0,
                lower_inclusive: bool = False, upper: float = np.inf,
                where: tuple[int, int | None] = (0, None)) -> None:
    """One vectorised check; the first bad value is named with the allowed range.

    ``where`` = (index of x[0] among all cases, number of cases) for the message.

    >>> check_range("friction", np.array([0.8, -0.2]), "")
    Traceback (most recent call last):
    ...
    microslip.errors.ParameterError: friction must be finite and in (0, inf), got -0.2 (case 1 of 2)
    """
    with np.errstate(invalid="ignore"):
        low_ok = x >= lower if lower_inclusive else x > lower
        ok = np.isfinite(x) & low_ok & (x < upper)
    if ok.all():
        return
    i = int(np.argmin(ok))
    lo = "[" if lower_inclusive else "("
    hi = f"{upper:g})" if np.isfinite(upper) else "inf)"
    u = f" {unit}" if unit else ""
    raise ParameterError(
        f"{name} must be finite and in {lo}{lower:g}, {hi}{u}, got {float(x.flat[i])!r}"
        f"{_case(i, x.size, where)}"
    )


def prepare_batch(model: str, params: ClampParams | Mapping[str, ArrayLike],
                  amplitude: ArrayLike, increments: int = 1000,
                  options: ModelOptions | None = None,
                  strain_energy: str = DEFAULT_STRAIN_ENERGY, *,
                  where: tuple[int, int | None] = (0, None),
                  contact: Contact | None = None) -> BatchInput:
    """Validate a batch once, vectorised, and flatten it for a kernel.

    ``where`` = (index of the first case among all cases, number of cases) lets a caller
    that splits a larger study into batches name the case globally in an error.
    ``contact``: the interface under every case (stick slope, shear lag, pressure law);
    None or a rigid one: the paper's foundation.

    Raises
    ------
    ParameterError
        The first bad value, named with its allowed range and its case index.
    MacroslipError
        The first case whose amplitude reaches the model's macroslip limit
        (:func:`microslip.macroslip_force`: mu F_N for the tip and the physical centre
        reading, 2 mu F_N for the centre model's ``paper`` reading).
    """
    spec = get_model(model)
    opt = options if options is not None else ModelOptions()
    if not isinstance(opt, ModelOptions):
        raise ParameterError(f"options must be ModelOptions, got {type(opt).__name__}")
    check_choice("strain-energy definition", strain_energy, STRAIN_ENERGY)
    n = check_increments(increments)
    if contact is not None and not isinstance(contact, Contact):
        raise ParameterError(f"contact must be a Contact, got {type(contact).__name__}")
    layer = None if contact is None or contact.is_rigid else contact
    if layer is not None:
        check_strain_energy(layer, strain_energy)
        check_reading(opt, len(spec.domains))
    values = _param_values(params)
    arrays = {k: _as_float(k, values[k]) for k in PARAM_FIELDS}
    amp = _as_float("amplitude", amplitude)
    try:
        shape = np.broadcast_shapes(amp.shape, *(a.shape for a in arrays.values()))
    except ValueError:
        shapes = ", ".join(f"{k} {a.shape}" for k, a in {"amplitude": amp, **arrays}.items())
        raise ParameterError(f"batch inputs do not broadcast together: {shapes}") from None
    size = int(np.prod(shape))

    def flat(a: FloatArray) -> FloatArray:
        # always a writeable C-contiguous float64 array: numba compiles one kernel per
        # array type, and a read-only view (e.g. of a broadcast) would be another type
        return np.require(np.broadcast_to(a, shape).reshape(size), np.float64,
                          ["C_CONTIGUOUS", "WRITEABLE", "ALIGNED"])

    amp_f = flat(amp)
    flat_params = {k: flat(a) for k, a in arrays.items()}
    check_range("amplitude", amp_f, "N", where=where)
    for k, unit in PARAM_FIELDS.items():
        if k == "poisson_ratio":
            check_range(k, flat_params[k], unit, lower_inclusive=True, upper=0.5, where=where)
        else:
            check_range(k, flat_params[k], unit, where=where)
    factor = spec.macroslip_factor(opt)
    limit = factor * flat_params["friction"] * flat_params["normal_force"]
    ok = amp_f < limit
    if not ok.all():
        i = int(np.argmin(ok))
        name = spec.reading(opt)
        reading = f", {name} reading" if name else ""
        rule = "2 mu F_N" if factor == 2.0 else "mu F_N"
        raise MacroslipError(
            f"amplitude {amp_f[i]:g} N is at or beyond the macroslip limit of the {model} "
            f"model ({limit[i]:g} N = {rule}{reading}, friction {flat_params['friction'][i]:g}, "
            f"normal_force {flat_params['normal_force'][i]:g} N){_case(i, size, where)}; "
            f"microslip needs 0 < amplitude < {rule}"
        )
    check_small_strain(amp_f, flat_params["width"], flat_params["thickness"],
                       flat_params["modulus"], where=lambda i: _case(i, size, where))
    return BatchInput(model=spec.name, shape=tuple(shape), amplitude=amp_f, **flat_params,
                      increments=n, options=opt, strain_energy_kind=strain_energy, where=where,
                      contact=layer)


@contextlib.contextmanager
def _numba_threads(threads: int | None) -> Iterator[None]:
    if threads is None:
        yield
        return
    import numba

    if isinstance(threads, bool) or not isinstance(threads, int) or threads < 1:
        raise ParameterError(f"threads must be a whole number >= 1, got {threads!r}")
    before = numba.get_num_threads()
    numba.set_num_threads(min(threads, numba.config.NUMBA_NUM_THREADS))  # type: ignore[attr-defined]
    try:
        yield
    finally:
        numba.set_num_threads(before)


def _kernel(model: str, backend: str, layer: bool) -> Callable[..., None]:
    spec = get_model(model)
    k: Any = spec.layer_kernel if layer else spec.batch_kernel  # a numba dispatcher
    return k.py_func if backend == "python" else k


def run_batch(inp: BatchInput, *, backend: str | None = None,
              threads: int | None = None) -> BatchResult:
    """Run the kernel of ``inp.model`` on a validated batch (see :func:`prepare_batch`)."""
    be = default_backend() if backend is None else backend
    if be not in BACKENDS:
        raise ParameterError(f"unknown batch backend {be!r}; choose one of {', '.join(BACKENDS)}")
    size = inp.size
    out = [np.empty(size) for _ in range(5)]
    opt = inp.options
    args: tuple[Any, ...] = (
        inp.amplitude, inp.length, inp.width, inp.thickness, inp.modulus, inp.poisson_ratio,
        inp.friction, inp.normal_force, inp.increments, *opt.codes,
        STRAIN_ENERGY_CODES[inp.strain_energy_kind])
    if inp.contact is not None:
        args = (*args, *inp.contact.kernel_args)
    kernel = _kernel(inp.model, be, inp.contact is not None)
    if size:
        with _numba_threads(threads if be == "numba" else None):
            kernel(*args, *out)
    d0, w, u, eta, section = out
    ok = (section > 0.0) & np.isfinite(d0) & np.isfinite(eta)
    if not ok.all():
        i = int(np.argmin(ok))
        hint = (" (the paper-literal Poisson update shrinks the section at every increment; "
                "use fewer increments or poisson='consistent')"
                if opt.poisson == "paper-literal" else "")
        raise ParameterError(
            f"the {inp.model} model broke down at {inp.increments} increments: non-finite "
            f"displacement or cross-section <= 0 mm{_case(i, size, inp.where)}{hint}"
        )
    shape = inp.shape
    return BatchResult(
        model=inp.model, increments=inp.increments, options=opt,
        strain_energy_kind=inp.strain_energy_kind,
        amplitude=inp.amplitude.reshape(shape), peak_displacement=d0.reshape(shape),
        dissipated_energy=w.reshape(shape), strain_energy=u.reshape(shape),
        loss_factor=eta.reshape(shape), backend=be,
    )


def batch_damping(model: str, params: ClampParams | Mapping[str, ArrayLike],
                  amplitude: ArrayLike, increments: int = 1000,
                  options: ModelOptions | None = None,
                  strain_energy: str = DEFAULT_STRAIN_ENERGY, *,
                  backend: str | None = None, threads: int | None = None,
                  contact: Contact | None = None) -> BatchResult:
    """W_d, U and eta of many cases at once, without storing any loop.

    The batch equivalent of :func:`microslip.damping`: for every case it runs the model's
    first loading (tip Eqs 2-10, centre Eqs 11-18), completes the loop with Masing's rule
    and evaluates Eqs 21-23, accumulating the energies on the fly (memory O(batch)). The
    numbers are those of :func:`microslip.damping` to rounding (about 1e-13 relative at
    1000 increments).

    Parameters
    ----------
    model : {"tip", "centre"}
    params : ClampParams or mapping
        A ClampParams, or a mapping with every field of it (``length``, ``width``,
        ``thickness``, ``modulus``, ``poisson_ratio``, ``friction``, ``normal_force``), each
        a number or an array; all inputs broadcast together.
    amplitude : array_like
        Peak force F0 of each case, N, below the macroslip limit.
    increments : int
        Force increments of each first loading.
    options : ModelOptions, optional
    strain_energy : str
        Definition of U (``secant``, ``backbone``, ``branch``, ``stored``).
    backend : {"numba", "python"}, optional
        Default: numba.
    threads : int, optional
        Threads of the numba backend (default: all).
    contact : Contact, optional
        The interface under every case (:class:`~microslip.models.contact.Contact`: stick
        slope, shear lag, pressure law); default the paper's rigid foundation. On a contact
        each case runs its model's compiled layer step
        (:mod:`~microslip.models.layered`), the one :func:`microslip.first_loading` runs,
        so the numbers are those of :func:`microslip.damping` with the same contact, bit for
        bit; strain energy ``stored`` and the centre model's ``paper`` reading are refused.

    Returns
    -------
    BatchResult
        Arrays of the broadcast shape of the inputs.

    Examples
    --------
    >>> import math, numpy as np
    >>> from microslip import ModelOptions, preset

    Without the Poisson and length updates the virgin curve is the parabola
    d = F^2/(2 E A q), and the trapezoidal loop area of n increments gives the secant loss
    factor 4/(3 pi) (1 - 1/n^2) exactly:

    >>> r = batch_damping("tip", preset("table1"), np.array([100.0, 200.0, 300.0]),
    ...                   increments=200, options=ModelOptions.uncorrected())
    >>> exact = 4 / (3 * math.pi) * (1 - 1 / 200**2)
    >>> np.round(r.loss_factor / exact, 12).tolist()
    [1.0, 1.0, 1.0]
    """
    inp = prepare_batch(model, params, amplitude, increments, options, strain_energy,
                        contact=contact)
    return run_batch(inp, backend=backend, threads=threads)


assert [f.name for f in fields(ClampParams)] == list(PARAM_FIELDS)
