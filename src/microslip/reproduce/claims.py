"""The paper's qualitative claims, each judged from the columns of the CSV files that
``microslip reproduce`` writes (never by hand): softening, the centre model stiffer than the
tip model, the extremes of the loss factor over R, and the agreement with finite elements.

Units: N, mm, N·mm; loss factors dimensionless.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..planar import ratio_label

__all__ = ["VERDICTS", "Claim", "check_claims", "eta_extremes", "fmt_number"]

VERDICTS = ("confirmed", "not confirmed", "cannot be checked")


#: Relative tolerance for "the same R" when reading R back from a CSV.
_R_TOL = 1e-9


#: Loss factors closer than this (relative) over all R count as equal (round-off).
_TIE = 1e-9


@dataclass(frozen=True)
class Claim:
    """One of the paper's claims, checked against our numbers.

    Attributes
    ----------
    key : str
        Short name (``softening``, ``centre-stiffer``, ``eta-extremes-paper``, ...).
    claim : str
        What the paper says, with its section.
    verdict : str
        ``confirmed``, ``not confirmed`` or ``cannot be checked``.
    evidence : str
        The numbers the verdict rests on, with units.
    reason : str
        Why our implementation gives this verdict.
    source : str
        The CSV file whose columns were used.
    """

    key: str
    claim: str
    verdict: str
    evidence: str
    reason: str
    source: str


def _finite(values: Any) -> np.ndarray:
    return np.asarray(values, dtype=float)


def _rows_at(ratios: np.ndarray, r: float) -> np.ndarray:
    return np.isclose(ratios, r, rtol=_R_TOL, atol=0.0)


def fmt_number(x: float, digits: int = 6) -> str:
    """``x`` to ``digits`` significant digits, or ``n/a`` when not finite."""
    return "n/a" if not math.isfinite(x) else f"{x:.{digits}g}"


def _claim_softening(comp: Mapping[str, Any]) -> Claim:
    models = [str(m) for m in comp["model"]]
    amp = _finite(comp["amplitude_N"])
    k = _finite(comp["secant_stiffness_N_per_mm"])
    parts, falls, missing, enough = [], [], [], True
    for name in ("tip", "centre"):
        sel = np.array([m == name for m in models], dtype=bool)
        a, kk = amp[sel], k[sel]
        good = np.isfinite(kk)
        if np.any(~good):
            missing.append(f"{name} at {', '.join(f'{x:g}' for x in a[~good])} N")
        a, kk = a[good], kk[good]
        order = np.argsort(a)
        a, kk = a[order], kk[order]
        enough = enough and kk.size >= 2
        falls.append(bool(np.all(np.diff(kk) < 0.0)))
        parts.append(f"{name}: F_T/δ0 = " + ", ".join(
            f"{fmt_number(x)} N/mm at {y:g} N" for x, y in zip(kk, a, strict=True)))
    ok = all(falls)
    verdict = ("cannot be checked" if not enough else "confirmed" if ok else "not confirmed")
    evidence = "; ".join(parts)
    if missing:
        evidence += f" (not computable in this reading: {'; '.join(missing)})"
    reason = ("the slip length grows in proportion to F_T (Eqs 3-4, 11), so the stiffness "
              "2EA/u of the slipping part (Eqs 9, 16) falls as 1/F_T; the secant stiffness "
              "F_T/δ0 of each model's loop " + ("falls" if ok else "does not fall")
              + " monotonically over the paper's amplitudes")
    return Claim("softening", "As F_T increases for each of the models the stiffness decreases "
                 "(softening; Section 5, Figs 10-11).", verdict, evidence, reason,
                 "stiffness_vs_amplitude.csv")


def _claim_centre_stiffer(comp: Mapping[str, Any], table: Mapping[str, Any]) -> Claim:
    r = _finite(table["R"])
    kt = _finite(table["tip_secant_stiffness_N_per_mm"])
    kc = _finite(table["centre_secant_stiffness_N_per_mm"])
    good = np.isfinite(kt) & np.isfinite(kc)
    if not np.any(good):
        return Claim("centre-stiffer", _CENTRE_CLAIM, "cannot be checked",
                     "no case computed", "", "loss_factor_vs_R.csv")
    ratio = kc[good] / kt[good]
    stiffer = bool(np.all(ratio > 1.0))
    i_min = int(np.argmin(ratio))
    at_one = _rows_at(r[good], 1.0)
    parts = []
    if np.any(at_one):
        parts.append(f"at R = 1 (Fig. 10a) the centre loop is {ratio[at_one][0]:.4g} times "
                     f"as stiff as the tip loop")
    parts.append(f"smallest centre/tip secant-stiffness ratio over the computed R: "
                 f"{ratio[i_min]:.6g} at R = {ratio_label(r[good][i_min])}")
    # At equal amplitude level (stiffness_vs_amplitude.csv).
    models = [str(m) for m in comp["model"]]
    lev = _finite(comp["level"])
    ks = _finite(comp["secant_stiffness_N_per_mm"])
    eq = []
    for lv in sorted(set(lev.tolist())):
        t = [ks[i] for i in range(len(models)) if models[i] == "tip" and lev[i] == lv]
        c = [ks[i] for i in range(len(models)) if models[i] == "centre" and lev[i] == lv]
        if t and c and math.isfinite(t[0]) and math.isfinite(c[0]):
            eq.append(c[0] / t[0])
    if eq:
        parts.append(f"at equal level the ratio is {min(eq):.4g} to {max(eq):.4g}")
    verdict = "confirmed" if stiffer else "not confirmed"
    reason = ("on a rigid foundation the centre displacement is F^2/(8EAq) against the tip's "
              "F^2/(2EAq) (two halves in parallel, each with half the force and half the slip "
              "length), and Table 2's centre section is twice the tip's; the secant stiffness "
              "of the centre loop is " + ("above" if stiffer else "not above")
              + " the tip's at every computed R")
    return Claim("centre-stiffer", _CENTRE_CLAIM, verdict, "; ".join(parts), reason,
                 "loss_factor_vs_R.csv, stiffness_vs_amplitude.csv")


_CENTRE_CLAIM = ("The stiffness of the centre model is greater than that of the tip model "
                 "(Section 5, 'obvious from Figure 8a', i.e. the loops of Fig. 10a).")


def eta_extremes(r: np.ndarray, eta: np.ndarray) -> tuple[str, str, str]:
    """Verdict, evidence and ranking for "eta lowest at R = 1, highest at R = 0.25 and 4".

    Returns ``(verdict, evidence, ranking)``; the verdict is ``cannot be checked`` when R = 1,
    0.25 or 4 has no finite loss factor.
    """
    good = np.isfinite(eta)
    needed = [x for x in (1.0, 0.25, 4.0) if not np.any(_rows_at(r[good], x))]
    order = np.argsort(eta[good], kind="stable")
    rg, eg = r[good][order], eta[good][order]
    ranking = " < ".join(ratio_label(x) for x in rg)
    if eg.size:
        spread = (eg[-1] - eg[0]) / eg[0] * 100.0
        evidence = (f"R ordered by rising eta: {ranking}; eta from {eg[0]:.6g} "
                    f"(R = {ratio_label(rg[0])}) to {eg[-1]:.6g} (R = {ratio_label(rg[-1])}), "
                    f"a spread of {spread:.3g} %")
    else:
        evidence = "no case computed"
    missing = [x for x in range(r.size) if not good[x]]
    if missing:
        evidence += "; not computed: R = " + ", ".join(ratio_label(r[i]) for i in missing)
    if needed:
        return "cannot be checked", evidence, ranking
    if eg[-1] - eg[0] <= _TIE * abs(eg[0]):
        return ("not confirmed", f"eta is the same at every R to {_TIE:g} (relative): "
                f"{eg[0]:.9g}", "all equal")
    lowest_is_one = math.isclose(rg[0], 1.0, rel_tol=_R_TOL)
    top_two = {round(float(x), 9) for x in rg[-2:]}
    highest_ok = top_two == {0.25, 4.0}
    verdict = "confirmed" if (lowest_is_one and highest_ok) else "not confirmed"
    return verdict, evidence, ranking


def _claim_eta(table: Mapping[str, Any], comp: Mapping[str, Any], coupling: str) -> Claim:
    r = _finite(table["R"])
    eta = _finite(table[f"{coupling}_loss_factor"])
    verdict, evidence, _ = eta_extremes(r, eta)
    models = [str(m) for m in comp["model"]]
    amp = _finite(comp["amplitude_N"])
    le = _finite(comp["loss_factor"])
    drift = []
    for name in ("tip", "centre"):
        sel = np.array([m == name for m in models]) & np.isfinite(le)
        if np.count_nonzero(sel) >= 2:
            a, e = amp[sel], le[sel]
            lo, hi = int(np.argmin(a)), int(np.argmax(a))
            drift.append(f"{name} {(e[hi] / e[lo] - 1.0) * 100.0:+.3g} % from {a[lo]:g} N to "
                         f"{a[hi]:g} N")
    what = ("the paper's resultant loop (Eqs 19-23)" if coupling == "paper"
            else "the work of the load (W = 2 W_tip + W_centre, U summed over the components)")
    reason = (f"eta of {what}. For quadratic backbones (corrections off) every loop has the "
              "same shape, the resultant is a scaled copy and eta is the same at every R; what "
              "varies here comes only from the Poisson and length corrections, through the "
              "amplitude dependence of each model's own eta (" + "; ".join(drift) + "), so the "
              "order over R follows the amplitudes each R uses")
    return Claim(f"eta-extremes-{coupling}",
                 "The loss factor is lowest at R = 1 and largest at R = 0.25 and R = 4 "
                 "(Section 5, Fig. 12).", verdict, evidence, reason, "loss_factor_vs_R.csv")


def _claim_fe(validation: Mapping[str, Any]) -> Claim:
    claim = ("Both 1-D models agree well with the finite-element results (Section 5, Fig. 9; "
             "Section 6).")
    need = ("case", "mesh", "err_peak_model_fe", "err_wd_model_fe", "tolerance_peak",
            "tolerance_wd")
    if any(k not in validation for k in need) or not validation["case"]:
        return Claim("fe-agreement", claim, "cannot be checked",
                     "validation.csv lacks the model-vs-FE columns", "", "validation.csv")
    parts, ok = [], True
    for i, case in enumerate(validation["case"]):
        ep = float(validation["err_peak_model_fe"][i])
        ew = float(validation["err_wd_model_fe"][i])
        tp_, tw = float(validation["tolerance_peak"][i]), float(validation["tolerance_wd"][i])
        conv = str(validation.get("converged", ["True"] * (i + 1))[i]) in ("True", "1", "1.0")
        within = conv and abs(ep) <= tp_ and abs(ew) <= tw
        ok = ok and within
        parts.append(f"{case} ({validation['mesh'][i]} mesh): model − FE {100 * ep:+.2f} % in "
                     f"peak displacement (tolerance {100 * tp_:g} %), {100 * ew:+.2f} % in W_d "
                     f"(tolerance {100 * tw:g} %)" + ("" if conv else ", FE not converged"))
    return Claim("fe-agreement", claim, "confirmed" if ok else "not confirmed",
                 "; ".join(parts),
                 "the FE model (Table 1 bar, rigid base, Coulomb friction, CalculiX) is what the "
                 "1-D models idealise; agreement is judged against the validation's own "
                 "tolerances, with the models in the reading of the validation",
                 "validation.csv")


def check_claims(components: Mapping[str, Any], table: Mapping[str, Any],
                 validation: Mapping[str, Any] | None = None) -> tuple[Claim, ...]:
    """The paper's qualitative claims, judged from the columns of the two CSV files.

    Parameters
    ----------
    components : mapping
        Columns of ``stiffness_vs_amplitude.csv`` (:func:`component_table`).
    table : mapping
        Columns of ``loss_factor_vs_R.csv`` (:meth:`RatioSweep.columns`).

    validation : mapping, optional
        Columns of ``validation.csv`` when the finite-element validation ran.

    Returns
    -------
    tuple of Claim
        Softening, centre stiffer than tip, the loss-factor extremes for the paper's
        coupling and for the work-based result, and (with ``validation``) the agreement of
        the models with finite elements.
    """
    claims: tuple[Claim, ...] = (
        _claim_softening(components),
        _claim_centre_stiffer(components, table),
        _claim_eta(table, components, "paper"),
        _claim_eta(table, components, "work"),
    )
    if validation is not None:
        claims = (*claims, _claim_fe(validation))
    return claims

