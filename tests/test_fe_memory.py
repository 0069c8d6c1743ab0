"""Memory of the built-in FE on large meshes (issue 23: under 2 GB at 50k DOF): the condensed
model drops its full factor, the modes factorise through :func:`shift_inverse`, and the ROM
build never holds the constraint modes whole; each gives the numbers of the direct way."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse.linalg as spla

from microslip.fe.assembly import rigid_base
from microslip.fe.builtin.meshmodel import SpentBackend, build_mesh_model
from microslip.fe.examples import cantilever_mesh
from microslip.meshdynamics import modes as modes_mod
from microslip.meshdynamics import reduce as reduce_mod
from microslip.meshdynamics.modes import linear_modes, modal_stiffness, shift_inverse
from microslip.meshdynamics.reduce import build_rom, full_mass

RHO = 2700.0


def _model(counts: tuple[int, int, int], **kw: object):  # type: ignore[no-untyped-def]
    return build_mesh_model(cantilever_mesh(*counts), rigid_base(contact_set="contact",
                                                                 clamp_set="clamp",
                                                                 normal_force=2000.0,
                                                                 modulus=70000.0,
                                                                 poisson_ratio=0.33, friction=0.5,
                                                                 stick_slope=1e4), **kw)


@pytest.fixture(scope="module")
def model():  # type: ignore[no-untyped-def]
    return _model((12, 3, 1))


def test_condensed_model_keeps_only_the_name_of_its_full_solver() -> None:
    full = _model((12, 3, 1), condensed=False)
    cond = _model((12, 3, 1), condensed=True)
    assert not isinstance(full.backend, SpentBackend)
    assert isinstance(cond.backend, SpentBackend)
    assert cond.backend.name == full.backend.name == "banded"
    assert cond.backend.half_bandwidth == full.backend.half_bandwidth  # type: ignore[attr-defined]
    with pytest.raises(RuntimeError, match="condensed"):
        cond.backend.factor(np.zeros((1, 3)))


@pytest.mark.parametrize("band_limit", [10**9, -1])  # banded Cholesky, SuperLU
def test_shift_inverse_solves(model, band_limit,
                              monkeypatch) -> None:  # type: ignore[no-untyped-def]
    monkeypatch.setattr(modes_mod, "AUTO_BAND_LIMIT", band_limit)
    k = modal_stiffness(model)
    rhs = np.linspace(-1.0, 2.0, k.shape[0])
    x = shift_inverse(k).matvec(rhs)
    ref = spla.spsolve(k.tocsc(), rhs)
    assert np.max(np.abs(x - ref)) <= 1e-10 * np.max(np.abs(ref))


def test_modes_same_by_either_factor(model, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    banded = linear_modes(model, RHO, 6)
    monkeypatch.setattr(modes_mod, "AUTO_BAND_LIMIT", -1)
    lu = linear_modes(model, RHO, 6)
    np.testing.assert_allclose(lu.frequencies_Hz, banded.frequencies_Hz, rtol=1e-10)
    free_b = linear_modes(model, RHO, 6, contact="free")
    assert free_b.frequencies_Hz[3] > 1.0  # three in-plane rigid motions, then elastic


@pytest.mark.parametrize("block", [256, 7])  # one block, several (7 does not divide n_b)
def test_rom_blocks_equal_dense_constraint_modes(model, block,
                                                 monkeypatch) -> None:  # type: ignore[no-untyped-def]
    monkeypatch.setattr(reduce_mod, "BLOCK", block)
    rom = build_rom(model, RHO, modes=4, response_set="response")
    # the direct way: Psi = -K_ii^-1 K_ib held whole
    k = model.stiffness.toarray()
    m = full_mass(model, RHO).toarray()
    b = rom.boundary
    inner = np.setdiff1d(np.arange(model.dof), b)
    psi = -np.linalg.solve(k[np.ix_(inner, inner)], k[np.ix_(inner, b)])
    t = np.vstack([np.eye(b.size), psi])
    order = np.concatenate([b, inner])
    kb = t.T @ k[np.ix_(order, order)] @ t
    mb = t.T @ m[np.ix_(order, order)] @ t
    nb = b.size
    scale_k, scale_m = np.max(np.abs(kb)), np.max(np.abs(mb))
    assert np.max(np.abs(rom.stiffness[:nb, :nb] - kb)) <= 1e-10 * scale_k
    assert np.max(np.abs(rom.mass[:nb, :nb] - mb)) <= 1e-10 * scale_m
    # the output's boundary columns: the response set's mean of [I; Psi] rows
    assert rom.output is not None
    nodes = model.model_nodes(model.mesh.node_sets["response"])
    full_rows = np.zeros((3, model.dof))
    for c in range(3):
        pos = model.index[3 * nodes + c]
        full_rows[c, pos[pos >= 0]] += 1.0 / nodes.size
    local = full_rows[:, order] @ t
    ref = model.rotation.T @ local
    assert np.max(np.abs(rom.output[:, :nb] - ref)) <= 1e-10 * np.max(np.abs(ref))
