"""``microslip report`` on a case of the user's own mesh (issue 34 item 3): no [geometry]
needed; every section about the case's mesh, loads and modes (the loops of ``fe --case`` at
its [[mesh.load]] tables, what the solver built, the checks, the modal study); the 1-D bar's
sections only with --bar and a bar to describe; the case's assembly tables read as the
commands read them. Parts: the new user's plate (tests/data/meshes/plate.msh) and the bar
on its block (two bodies, tests/data/meshes/cantilever_on_block.inp)."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from microslip.cli.main import main

DATA = Path(__file__).resolve().parent / "data" / "meshes"

PLATE = """name = "steel plate on its washer"
[material]
modulus = 210000
poisson_ratio = 0.3
[contact]
friction = 0.5
[clamping]
normal_force = 8000
[mesh]
file = "plate.msh"
contact_set = "contact"
clamp_set = "washer"
response_set = "response"
[[mesh.load]]
set = "tip"
direction = [0.0, 1.0, 0.0]
amplitude = 20.0
"""

#: Two bodies: the bar's face on the block's, a preload, the block held (test_cli_assembly).
ASSEMBLY = """name = "bar on its block"
[contact]
friction = 0.5
stick_slope = 1e4
[mesh]
file = "cantilever_on_block.inp"
[[mesh.contact]]
face = "bar_int"
counter = "base_int"
[[mesh.preload]]
face = "clamp"
force = 2000.0
[[mesh.support]]
set = "base_fix"
[[mesh.material]]
elset = "BAR"
modulus = 70000
poisson_ratio = 0.33
[[mesh.material]]
elset = "BASE"
modulus = 7e7
poisson_ratio = 0.33
[[mesh.load]]
set = "tip"
direction = [1, 0, 0]
amplitude = 100
"""


def _write(tmp_path: Path, text: str, mesh: str) -> Path:
    shutil.copy(DATA / mesh, tmp_path / mesh)
    (tmp_path / "case.toml").write_text(text)
    return tmp_path / "case.toml"


def _json(capsys: pytest.CaptureFixture[str], *argv: str) -> dict:
    code = main(list(argv))
    captured = capsys.readouterr()
    assert code == 0, captured.err
    return json.loads(captured.out)


def test_a_mesh_case_without_geometry_reports_its_part(tmp_path: Path,
                                                       capsys: pytest.CaptureFixture[str]
                                                       ) -> None:
    """Before: "a report needs the whole clamp: give preset or all seven clamp values".
    Now the page names the mesh's file and loads, gives the model's set areas and the
    loops of fe --case (the same numbers, bit for bit), and no bar section."""
    case = _write(tmp_path, PLATE, "plate.msh")
    page = tmp_path / "r.html"
    out = _json(capsys, "report", "--case", str(case), "--out", str(page), "--json",
                "--no-progress")
    fe = _json(capsys, "fe", "--case", str(case), "--json")
    assert out["kind"] == "mesh" and out["mesh_file"].endswith("plate.msh")
    assert out["loads"] == [{"set": "tip", "direction": [0.0, 1.0, 0.0], "amplitude_N": 20.0,
                             "phase_deg": 0.0}]
    washer = out["model"]["sets"]["washer"]
    assert washer["area_mm2"] == pytest.approx(101.823, rel=1e-4)
    assert washer["pressure_MPa"] == pytest.approx(8000 / washer["area_mm2"])
    for key in ("dissipated_energy_Nmm", "peak_displacement_mm", "work_per_cycle_Nmm"):
        assert out["fe"][key] == fe[key], key
    assert out["model"] == fe["model"]
    assert out["bar"] is None and out["structure"] is None  # no density: no modes
    assert any("38 of 63 contact nodes are open" in c for c in out["checks"])
    text = page.read_text()
    assert "plate.msh" in text and "20 N on tip along (0, 1, 0)" in text
    assert "<h2>What the solver built</h2>" in text and "101.823" in text
    assert "1-D model against finite elements" not in text and "[geometry]" not in text
    assert "Hysteresis loops" not in text
    assert text.count('<img src="data:image/svg+xml;base64,') == 1  # the loops


def test_the_assembly_tables_are_read(tmp_path: Path, capsys: pytest.CaptureFixture[str]
                                      ) -> None:
    """[[mesh.contact]], [[mesh.preload]], [[mesh.support]], [[mesh.material]]: the
    report's model is fe --case's (two bodies, the interface pair, the held block)."""
    case = _write(tmp_path, ASSEMBLY, "cantilever_on_block.inp")
    out = _json(capsys, "report", "--case", str(case), "--json", "--no-progress")
    fe = _json(capsys, "fe", "--case", str(case), "--json")
    m = out["model"]
    assert m == fe["model"] and m["bodies"] == 2
    assert m["sets"]["bar_int"]["role"] == "contact"
    assert m["sets"]["base_int"]["role"] == "counter face"
    assert m["sets"]["base_fix"] == {"role": "support", "directions": "xyz"}
    assert m["assembly"]["contacts"] == [{"face": "bar_int", "counter": "base_int"}]
    assert out["fe"]["dissipated_energy_Nmm"] == fe["dissipated_energy_Nmm"]
    assert out["inputs"]["mesh.contact"] == [{"face": "bar_int", "counter": "base_int"}]
    assert [m["elset"] for m in out["inputs"]["mesh.material"]] == ["BAR", "BASE"]


def test_mistakes_of_a_mesh_case_stop_the_report_in_one_line(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    case = _write(tmp_path, PLATE.replace('clamp_set = "washer"', 'clamp_set = "washr"'),
                  "plate.msh")
    assert main(["report", "--case", str(case), "--json", "--no-progress"]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "washr" in err[0]
    case = _write(tmp_path, PLATE, "plate.msh")
    assert main(["report", "--case", str(case), "--json", "--bar", "--no-progress"]) == 1
    assert "--bar) needs the bar's geometry" in capsys.readouterr().err
    assert main(["report", "--case", str(case), "--json", "--mesh", "tiny"]) == 1
    assert "--mesh tiny is the bar's FE mesh" in capsys.readouterr().err


@pytest.mark.slow
def test_the_bar_appears_only_when_asked(tmp_path: Path, capsys: pytest.CaptureFixture[str]
                                         ) -> None:
    """A mesh case with a preset: the bar's 1-D sections only with --bar, named as the
    bar's, after the part's."""
    text = PLATE.replace('name = "steel plate on its washer"',
                         'name = "plate"\npreset = "table1"')
    case = _write(tmp_path, text, "plate.msh")
    plain = _json(capsys, "report", "--case", str(case), "--json", "--no-progress",
                  "--out", str(tmp_path / "a.html"))
    assert plain["bar"] is None
    asked = _json(capsys, "report", "--case", str(case), "--json", "--no-progress", "--bar",
                  "--no-fe", "--out", str(tmp_path / "b.html"))
    assert asked["bar"]["one_d"]["dissipated_energy_Nmm"] > 0
    page = (tmp_path / "b.html").read_text()
    assert page.index("What the solver built") < page.index("The 1-D bar of the case")
    assert "1-D model against finite elements" in page
    assert "1-D model against finite elements" not in (tmp_path / "a.html").read_text()


@pytest.mark.slow
def test_a_mesh_case_with_a_density_reports_its_modes(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """The modal study of the case's mode on the same part: the model, the amplitude limit
    (with [material] yield_strength), the verdicts, the figure with the open nodes."""
    text = PLATE.replace("[mesh]\n", "[mesh]\ndensity = 7850\nmode = 2\n").replace(
        "poisson_ratio = 0.3\n", "poisson_ratio = 0.3\nyield_strength = 355\n")
    case = _write(tmp_path, text, "plate.msh")
    out = _json(capsys, "report", "--case", str(case), "--json", "--no-progress", "--out",
                str(tmp_path / "r.html"))
    s = out["structure"]
    assert s["mode"] == 2 and s["model"] == out["model"]
    assert s["amplitude_limit"]["yield_strength_MPa"] == 355.0
    assert set(s["verdicts"]) == {"rom", "interface", "joint"}
    page = (tmp_path / "r.html").read_text()
    assert "Amplitude limit" in page and page.count("data:image/svg+xml") == 2
    # both figures (the loops, the modes) render offline in headless Chromium
    import re

    from test_report import PROBE, _dump_dom

    probe = tmp_path / "probe.html"
    probe.write_text(page.replace("</body>", PROBE + "</body>"), encoding="utf-8")
    body = re.search(r"<body[^>]*>", _dump_dom(probe, tmp_path / "profile"))
    assert body is not None and 'data-rendered="2"' in body.group(0), body.group(0)
    assert not re.search(r"https?://|<script", page)
