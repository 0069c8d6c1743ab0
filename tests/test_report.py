"""``microslip report``: a self-contained HTML page that renders in headless Chromium offline."""

from __future__ import annotations

import re
import shutil
import subprocess
from html.parser import HTMLParser
from pathlib import Path

import pytest

from microslip import damping, preset
from microslip.case.model import load_case
from microslip.cli.main import main
from microslip.report import ReportSettings, compute_report

CASE = """\
name = "rig clamp"
description = "Table 1 bar, a planar load of R = 1.5 on it"
preset = "table1"
[contact]
friction = 0.6
[load]
model = "tip"
amplitude_fraction = 0.6
[load.planar]
tip_amplitude = 75.0
centre_amplitude = 100.0
"""

FAST = ["--mesh", "tiny", "--substeps", "20", "--no-progress"]

#: Chromium flags for a closed network (docs/report.md).
CHROMIUM_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
                  "--no-first-run", "--disable-background-networking",
                  "--disable-component-update", "--disable-sync"]

#: Added to a copy of the page under test only: counts the images the browser laid out with a
#: decoded, non-empty picture and writes the counts into the DOM that --dump-dom prints.
PROBE = """<script>window.addEventListener('load', function () {
var imgs = Array.prototype.slice.call(document.images);
var ok = imgs.filter(function (i) { var r = i.getBoundingClientRect();
  return i.complete && i.naturalWidth > 0 && i.naturalHeight > 0 && r.width > 0 &&
         r.height > 0; });
document.body.setAttribute('data-images', imgs.length);
document.body.setAttribute('data-rendered', ok.length); });</script>"""


class Links(HTMLParser):
    """Every tag and every src/href (and style text) of a page."""

    def __init__(self) -> None:
        super().__init__()
        self.tags: list[str] = []
        self.refs: list[str] = []
        self.images = 0

    def handle_starttag(self, tag, attrs):
        self.tags.append(tag)
        self.images += tag == "img"
        self.refs += [v or "" for k, v in attrs if k in ("src", "href", "srcset", "data")]


@pytest.fixture(scope="module")
def page(tmp_path_factory) -> tuple[Path, str, str]:
    d = tmp_path_factory.mktemp("report")
    case = d / "clamp.toml"
    case.write_text(CASE)
    out = d / "report.html"
    assert main(["report", "--case", str(case), "--out", str(out), *FAST]) == 0
    return out, out.read_text(encoding="utf-8"), str(case)


def _chromium() -> str:
    exe = shutil.which("chromium") or shutil.which("chromium-browser")
    if exe is None:
        pytest.skip("Chromium is not installed: `bash scripts/setup.sh` installs the Debian "
                    "package chromium (apt-get, as root)")
    return exe


def _dump_dom(page: Path, profile: Path) -> str:
    profile.mkdir()
    done = subprocess.run(
        [_chromium(), *CHROMIUM_FLAGS, f"--user-data-dir={profile}",
         "--virtual-time-budget=10000", "--dump-dom", page.as_uri()],
        capture_output=True, text=True, timeout=120, check=True)
    return done.stdout


@pytest.mark.slow
def test_figures_render_in_headless_chromium(page, tmp_path):
    _, text, _ = page
    probe = tmp_path / "probe.html"
    probe.write_text(text.replace("</body>", PROBE + "</body>"), encoding="utf-8")
    body = re.search(r"<body[^>]*>", _dump_dom(probe, tmp_path / "profile"))
    assert body is not None
    images = re.search(r'data-images="(\d+)"', body.group(0))
    rendered = re.search(r'data-rendered="(\d+)"', body.group(0))
    assert images and rendered, body.group(0)
    # loops, damping against amplitude, planar coupling: all three drawn
    assert int(images.group(1)) == 3
    assert int(rendered.group(1)) == 3


def test_a_broken_figure_is_caught_by_the_probe(page, tmp_path):
    _, text, _ = page
    broken = re.sub(r'src="data:image/svg\+xml;base64,[^"]{0,40}', 'src="data:image/svg+xml;'
                    'base64,AAAA', text, count=1)
    probe = tmp_path / "probe.html"
    probe.write_text(broken.replace("</body>", PROBE + "</body>"), encoding="utf-8")
    body = _dump_dom(probe, tmp_path / "profile")
    assert 'data-rendered="2"' in body


def test_the_page_needs_no_network(page):
    _, text, _ = page
    parser = Links()
    parser.feed(text)
    assert parser.images == 3
    assert not [r for r in parser.refs if not r.startswith("data:")]
    assert "script" not in parser.tags and "link" not in parser.tags
    assert "iframe" not in parser.tags and "object" not in parser.tags
    assert not re.search(r"https?://|@import|url\(", text)


def test_every_input_is_shown_with_its_unit(page):
    _, text, _ = page
    for key, value, unit in [("geometry.length", "254", "mm"), ("material.modulus", "68947",
                             "MPa"), ("contact.friction", "0.6", "dimensionless"),
                             ("clamping.normal_force", "445", "N"),
                             ("contact.stick_slope", "10000", "N/mm^3"),
                             ("load.planar.tip_amplitude", "75", "N")]:
        assert re.search(rf"<td>{re.escape(key)}</td><td>{value}</td><td>{re.escape(unit)}"
                         "</td>", text), key
    assert "<td>load amplitude F0</td><td>160.2</td><td>N</td>" in text


def test_the_numbers_are_the_library_s(page):
    _, text, case_path = page
    data = compute_report(load_case(case_path), ReportSettings(mesh="tiny", substeps=20,
                                                               fe_points=False),
                          progress=False)
    p = preset("table1").replace(friction=0.6)
    assert data.amplitude == 0.6 * 0.6 * 445.0
    direct = damping("tip", p, data.amplitude, 1000)
    assert data.loops[-1].loss_factor == direct.loss_factor
    assert f'<td class="num">{direct.loss_factor:.6g}</td>' in text
    assert data.fe is None and data.fe_curve.shape == (0, 4)
    assert data.planar is not None and data.planar.ratio == pytest.approx(1.5, rel=1e-12)


def test_without_a_planar_load_the_section_says_so(tmp_path, capsys):
    case = tmp_path / "c.toml"
    case.write_text('preset = "table2-centre"\n[load]\nmodel = "centre"\n')
    out = tmp_path / "r.html"
    assert main(["report", "--case", str(case), "--out", str(out), "--no-fe",
                 "--no-progress"]) == 0
    text = out.read_text()
    assert "no coupling to report" in text and text.count("<img") == 2
    assert "centre-loaded bar" in text
    assert "0 FE run(s)" in capsys.readouterr().out


@pytest.mark.parametrize("case_text, extra, message, code", [
    ('name = "no clamp"\n', [], "a report needs the whole clamp", 1),
    ('preset = "table1"\n[load]\namplitude = 500.0\n', ["--no-fe"],
     "0 < amplitude < 356 N", 1),
    # --mesh is checked by the parser, as on every command that takes it (a usage error)
    ('preset = "table1"\n', ["--mesh", "huge"], "unknown mesh 'huge'", 2),
])
def test_user_errors_are_one_line_and_write_nothing(tmp_path, capsys, case_text, extra,
                                                    message, code):
    case = tmp_path / "c.toml"
    case.write_text(case_text)
    out = tmp_path / "r.html"
    assert main(["report", "--case", str(case), "--out", str(out), "--no-progress",
                 *extra]) == code
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1
    assert not out.exists()


def test_out_must_be_html(tmp_path, capsys):
    assert main(["report", "--case", "x.toml", "--out", str(tmp_path / "r.pdf")]) == 1
    assert "--out must end in .html" in capsys.readouterr().err


def test_unwritable_out_is_refused_before_the_work(tmp_path, capsys, monkeypatch):
    import microslip.report as report

    def never(*args, **kwargs):
        raise AssertionError("the report was computed although --out cannot be written")

    monkeypatch.setattr(report, "write_report", never)
    blocker = tmp_path / "afile"
    blocker.write_text("x")
    case = tmp_path / "c.toml"
    assert main(["case", "new", str(case)]) == 0
    capsys.readouterr()
    assert main(["report", "--case", str(case), "--out", str(blocker / "r.html")]) == 1
    err = capsys.readouterr().err
    assert err.startswith("error: cannot write report") and err.count("\n") == 1
