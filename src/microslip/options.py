"""Interpretation options of the paper's equations.

The paper leaves several readings open (see ``docs/interpretation.md``). Each choice
that changes results is a named option here; the defaults are the readings that
converge as the increments are refined and agree with the exact limits.
"""

from __future__ import annotations

from dataclasses import dataclass

from .errors import ParameterError

__all__ = ["CENTRE_READINGS", "POISSON_CODES", "POISSON_MODES", "READING_CODES", "ModelOptions"]

#: Poisson (cross-section) update, Eqs 6-7 (tip) and 12-15 (centre).
#:
#: ``consistent``: tip Eqs 6-7 with the force *increment* dF_i in place of F_i (the
#: recursion then converges to dw/dF = -nu/(E t)); centre Eqs 12-15 with the sign of
#: Eq. 15 corrected so the tension domain thins, as the paper's text says.
#: ``paper-literal``: Eqs 6-7 with the total force F_i at every increment (depends on the
#: number of increments and does not converge) and Eq. 15 with its printed ``+`` sign.
#: ``off``: cross-section constant.
POISSON_MODES = ("consistent", "paper-literal", "off")

#: Reading of the centre model, Eqs 11 and 17.
#:
#: ``physical``: each half (tension, compression) carries F/2 and its slip length is
#: a = F L / (2 mu F_N) = F/(2q), as for a bar with one frictional face; macroslip at mu F_N.
#: ``paper``: Eq. 11 as printed, u = F L / (4 mu F_N), and each domain carries the full F in
#: Eq. 17 (the only force that recovers the exact displacement F^2/(8EAq)); macroslip where
#: u reaches the half length, at 2 mu F_N.
CENTRE_READINGS = ("physical", "paper")

#: Integer codes of the Poisson modes and readings, as the compiled kernels take them.
POISSON_CODES: dict[str, int] = {m: i for i, m in enumerate(POISSON_MODES)}
READING_CODES: dict[str, int] = {r: i for i, r in enumerate(CENTRE_READINGS)}


@dataclass(frozen=True)
class ModelOptions:
    """How the paper's incremental models are read.

    Parameters
    ----------
    poisson : str
        One of :data:`POISSON_MODES`.
    length_update : bool
        Update the clamped length by the previous displacement, L + delta_(i-1) (Eqs 4, 11).
    centre : str
        One of :data:`CENTRE_READINGS`.

    Examples
    --------
    >>> ModelOptions.uncorrected()
    ModelOptions(poisson='off', length_update=False, centre='physical')
    >>> ModelOptions(poisson="sideways")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    microslip.errors.ParameterError: poisson must be one of consistent, ...; got 'sideways'
    """

    poisson: str = "consistent"
    length_update: bool = True
    centre: str = "physical"

    def __post_init__(self) -> None:
        if self.poisson not in POISSON_MODES:
            raise ParameterError(
                f"poisson must be one of {', '.join(POISSON_MODES)}; got {self.poisson!r}"
            )
        if self.centre not in CENTRE_READINGS:
            raise ParameterError(
                f"centre must be one of {', '.join(CENTRE_READINGS)}; got {self.centre!r}"
            )
        object.__setattr__(self, "length_update", bool(self.length_update))

    @classmethod
    def uncorrected(cls) -> ModelOptions:
        """Poisson and length updates off: the rigid-foundation closed forms hold exactly."""
        return cls(poisson="off", length_update=False)

    @classmethod
    def paper(cls) -> ModelOptions:
        """The paper's equations as printed (Eqs 6-7 with total force, Eq. 15's sign, Eq. 11)."""
        return cls(poisson="paper-literal", length_update=True, centre="paper")

    @property
    def codes(self) -> tuple[int, int, int]:
        """(Poisson code, length update 0/1, reading code): the compiled kernels' switches."""
        return POISSON_CODES[self.poisson], int(self.length_update), READING_CODES[self.centre]

    @property
    def corrections(self) -> bool:
        """True when the Poisson or the length update is on."""
        return self.poisson != "off" or self.length_update
