"""Readers of CalculiX's .dat, .sta and .frd files: round trips on small synthetic files,
strictness on truncated ones, and the contact-status rule."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from microslip.fe import ResultsError, contact_status, read_dat, read_frd, read_sta


def frd_text(coords, blocks, end=True):
    """An ASCII .frd in CalculiX's fixed-width layout. blocks: (name, time, step, inc,
    components, node ids, values)."""
    out = ["    1C", "    1UUSER", f"    2C{len(coords):>30d}{1:>37d}"]
    for i, (x, y, z) in enumerate(coords, 1):
        out.append(f" -1{i:10d}{x:12.5E}{y:12.5E}{z:12.5E}")
    out.append(" -3")
    for k, (name, t, step, inc, comps, ids, vals) in enumerate(blocks, 1):
        out.append(f"    1PSTEP{k:>25d}{inc:>12d}{step:>12d}")
        out.append(f"  100CL{100 + k:5d}{t:12.9f}{len(ids):12d}{'':20s} 0{k:5d}{'':10s} 1")
        out.append(f" -4  {name:<8s}{len(comps) + (name == 'DISP'):5d}    1")
        for c in comps:
            out.append(f" -5  {c:<8s}    1    4    1    1")
        if name == "DISP":
            out.append(" -5  ALL         1    2    0    0    1ALL")
        for n, row in zip(ids, vals, strict=True):
            first, rest = row[:6], row[6:]
            out.append(f" -1{n:10d}" + "".join(f"{v:12.5E}" for v in first))
            if len(rest):
                out.append(f" -2{'':10s}" + "".join(f"{v:12.5E}" for v in rest))
        out.append(" -3")
    if end:
        out.append(" 9999")
    return "\n".join(out) + "\n"


CONTACT = ("COPEN", "CSLIP1", "CSLIP2", "CPRESS", "CSHEAR1", "CSHEAR2")


def test_frd_round_trip_with_adjoining_negative_numbers(tmp_path: Path):
    coords = [(0.0, 0.0, 0.0), (6.35, 0.0, 0.0), (254.0, 25.4, 3.18)]
    disp = np.array([[-1.35278e-06, -1.28639e-06, -8.43958e-07], [0, 0, 0],
                     [4.5588e-03, 1.6972e-04, -1.0e-12]])
    cont = np.array([[-7.88691e-07, -1.24711e-06, -1.10017e-06, 7.88691e-02, -1.24711e-02,
                      -1.10017e-02]] * 3)
    p = tmp_path / "job.frd"
    p.write_text(frd_text(coords, [("DISP", 1.025, 2, 1, ("D1", "D2", "D3"), [1, 2, 3], disp),
                                   ("CONTACT", 1.025, 2, 1, CONTACT, [1, 2, 3], cont)]))
    r = read_frd(p)
    assert r.nodes.tolist() == [1, 2, 3]
    np.testing.assert_allclose(r.coords, coords, rtol=1e-5)
    d, c = r.select("DISP")[0], r.select("CONTACT")[0]
    assert (d.components, d.time, d.step, d.increment) == (("D1", "D2", "D3"), 1.025, 2, 1)
    np.testing.assert_array_equal(d.values, disp)
    assert c.components == CONTACT
    np.testing.assert_array_equal(c.values, cont)
    assert [b.name for b in read_frd(p, names=("CONTACT",)).blocks] == ["CONTACT"]


# E12.5 has room for two exponent digits, which is all CalculiX writes
FRD_FLOATS = st.floats(-1e3, 1e3).filter(lambda v: v == 0.0 or abs(v) > 1e-90)


@given(vals=hnp.arrays(np.float64, (4, 8), elements=FRD_FLOATS))
@settings(max_examples=30, deadline=None)
def test_frd_round_trip_keeps_five_digits_and_continuation_lines(vals, tmp_path_factory):
    p = tmp_path_factory.mktemp("frd") / "j.frd"
    comps = tuple(f"C{i}" for i in range(8))
    p.write_text(frd_text([(0, 0, 0)] * 4, [("STRESS", 2.0, 2, 7, comps, [1, 2, 3, 4], vals)]))
    b = read_frd(p).blocks[0]
    assert b.values.shape == (4, 8) and b.increment == 7
    np.testing.assert_allclose(b.values, vals, rtol=6e-6, atol=1e-300)


def test_frd_without_end_record_or_with_open_block_is_truncated(tmp_path: Path):
    block = ("DISP", 1.0, 1, 1, ("D1", "D2", "D3"), [1], np.zeros((1, 3)))
    p = tmp_path / "a.frd"
    p.write_text(frd_text([(0, 0, 0)], [block], end=False))
    with pytest.raises(ResultsError, match="truncated"):
        read_frd(p)
    text = frd_text([(0, 0, 0)], [block])
    p.write_text(text[: text.rindex(" -3")])
    with pytest.raises(ResultsError, match="truncated"):
        read_frd(p)
    with pytest.raises(ResultsError, match="missing"):
        read_frd(tmp_path / "none.frd")


DAT = """
 displacements (vx,vy,vz) for set NLOAD and time  0.1000000E+01

         3  1.352778E-06 -1.286393E-06 -8.439703E-07
        11 -2.000000E-03  0.000000E+00  1.000000E-09

 forces (fx,fy,fz) for set NLOAD and time  0.1000000E+01

         3  1.000000E+00  0.000000E+00  0.000000E+00

 displacements (vx,vy,vz) for set NLOAD and time  0.1025000E+01

         3  2.000000E-06 -1.286393E-06 -8.439703E-07
        11 -3.000000E-03  0.000000E+00  1.000000E-09
"""


def test_dat_blocks_in_order(tmp_path: Path):
    p = tmp_path / "job.dat"
    p.write_text(DAT)
    blocks = read_dat(p, expected_rows=2)
    assert [b.time for b in blocks] == [1.0, 1.025]
    assert blocks[0].nset == "NLOAD" and blocks[0].quantity == "displacements (vx,vy,vz)"
    assert blocks[1].nodes.tolist() == [3, 11]
    assert blocks[1].values[1].tolist() == [-3e-3, 0.0, 1e-9]
    assert [b.values[0, 0] for b in read_dat(p, "forces")] == [1.0]


def test_dat_with_a_short_block_is_truncated(tmp_path: Path):
    p = tmp_path / "job.dat"
    p.write_text(DAT.rsplit("\n", 2)[0] + "\n")  # last block lost its second row
    with pytest.raises(ResultsError, match="expected 2"):
        read_dat(p, expected_rows=2)


def test_sta_skips_attempts_that_did_not_converge(tmp_path: Path):
    p = tmp_path / "job.sta"
    p.write_text(
        "SUMMARY OF JOB INFORMATION\n"
        "  STEP      INC     ATT  ITRS     TOT TIME     STEP TIME      INC TIME\n"
        "     1          1     1     2  0.100000E+01  0.100000E+01  0.100000E+01\n"
        "     2          1     1     6  0.102500E+01  0.250000E-01  0.250000E-01\n"
        "     2          2     1     5  0.105000E+01  0.500000E-01  0.250000E-01\n"
        "     2          3     1U 1150  0.105000E+01  0.500000E-01  0.250000E-01\n")
    s = read_sta(p)
    assert s.step.tolist() == [1, 2, 2]
    two = s.in_step(2)
    assert two.iterations.tolist() == [6, 5]
    np.testing.assert_allclose(two.step_time, [0.025, 0.05])


# -- contact status ---------------------------------------------------------------------------
def test_contact_status_separates_slipping_locked_stuck_and_open():
    mu, lam = 0.8, 1e4
    p = np.full((3, 4), 0.07)
    p[2, 3] = 0.0
    tau = np.zeros((3, 4, 2))
    s = np.zeros((3, 4, 2))
    limit = mu * 0.07
    # point 0 slips forward in both increments; point 1 slips, then is locked at the limit
    # (traction unchanged, no slip); point 2 is stuck elastically below the limit
    tau[1:, 0, 0] = limit
    s[1, 0, 0], s[2, 0, 0] = 1e-4, 2e-4
    tau[1:, 1, 0] = limit
    s[1:, 1, 0] = 5e-5
    tau[1:, 2, 0] = 0.3 * limit
    s[1:, 2, 0] = 0.3 * limit / lam
    st_ = contact_status(p, tau, s, mu, lam)
    assert st_.tolist() == [[1, 1, 1, 1], [2, 2, 1, 1], [2, 1, 1, 0]]


def test_contact_status_follows_the_slip_direction_in_the_plane():
    # a point sliding along y at the limit is slipping too
    p = np.full((2, 1), 0.1)
    tau = np.zeros((2, 1, 2))
    s = np.zeros((2, 1, 2))
    tau[1, 0, 1] = -0.08
    s[1, 0, 1] = -1e-3
    assert contact_status(p, tau, s, 0.8, 1e5).tolist() == [[1], [2]]
