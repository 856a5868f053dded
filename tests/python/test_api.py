"""check(), solve()'s errors, overrides, the DataFrame and the notebook view."""

import html
import json

import pytest

import gbxc
from conftest import ROOT, cli

DIAGNOSTICS = sorted((ROOT / "tests" / "golden" / "diagnostics").glob("*.gbx"))

SMALL = """gearbox Small {
  stage s1: spur {
    pinion.z in 18..20;  wheel.z in 40..44;
    normal_module = 2 mm;  pressure_angle = 20 deg;  face_width = 20 mm;
  }
  operating { input_speed = 1500 rpm; power = 10 kW; }
}
"""


@pytest.mark.parametrize("spec", DIAGNOSTICS, ids=[p.name for p in DIAGNOSTICS])
def test_check_gives_the_clis_diagnostics(spec):
    out, _, _ = cli("check", str(spec), "--format", "json")
    expected = json.loads(out)["diagnostics"]
    mine = gbxc.check(str(spec))
    assert len(mine) == len(expected)
    for d, e in zip(mine, expected):
        span = e["span"] or {}
        assert (d.code, d.severity, d.message) == (e["code"], e["severity"], e["message"])
        assert (d.file, d.line, d.column) == (span.get("file"), span.get("line"), span.get("column"))
        notes = "; ".join(n["message"] for n in e["notes"])
        # The notes, or the suggestion the message ends with.
        assert d.fix == notes if notes else (d.fix is None or e["message"].endswith("; " + d.fix))


def test_check_takes_text_and_never_raises():
    assert gbxc.check(SMALL) == []
    found = gbxc.check(SMALL.replace("face_width = 20 mm", "face_width = 20 kg"))
    assert [d.code for d in found] == ["E0302"]
    assert found[0].file == "<text>.gbx" and found[0].line == 4
    missing = gbxc.check("no/such/spec.gbx")
    assert missing and missing[0].code == "E0001"


def test_a_spec_error_raises_with_its_diagnostics():
    with pytest.raises(gbxc.SpecError) as e:
        gbxc.solve(SMALL.replace("normal_module = 2 mm", "normal_module = 2 s"))
    assert [d.code for d in e.value.diagnostics] == ["E0302"]
    assert "E0302" in str(e.value)


def test_overrides_are_the_value_written_in(tmp_path):
    written = tmp_path / "small.gbx"
    written.write_text(SMALL.replace("face_width = 20 mm", "face_width = 26 mm").replace("power = 10 kW", "power = 12 kW"))
    base = tmp_path / "base" / "small.gbx"
    base.parent.mkdir()
    base.write_text(SMALL)
    by_override = gbxc.solve(str(base), overrides={"s1.face_width": "26 mm", "operating.power": "12 kW"}, timings=False)
    assert by_override.to_json() == gbxc.solve(str(written), timings=False).to_json()
    assert list(by_override.gearboxes) == ["Small"]
    # A number without a unit is a number: a plain float goes in as written.
    shifted = gbxc.solve(SMALL, overrides={"s1.pinion.shift": 0.2}, timings=False)
    assert shifted.gearboxes["Small"].designs


@pytest.mark.parametrize(
    "override, words",
    [
        ({"s1.nothing": "20 mm"}, "E0211"),
        ({"s1.face_width": "20 kg"}, "E0302"),
        ({"operating.power": "3 m"}, "E0302"),
        ({"s1..face_width": "20 mm"}, "not a path"),
        ({"s1.face_width": "20 mm; require false"}, "one value"),
    ],
)
def test_a_bad_override_raises_with_the_diagnostics_text(override, words):
    with pytest.raises(gbxc.SpecError) as e:
        gbxc.solve(SMALL, overrides=override)
    assert words in str(e.value)


def test_a_diagnostic_says_its_fix():
    found = gbxc.check(SMALL.replace("face_width = 20 mm", "face_widht = 20 mm"))
    assert found[0].code == "E0211" and found[0].fix == "did you mean `face_width`?"
    bare = gbxc.check(SMALL.replace("face_width = 20 mm", "face_width = 20"))
    assert bare[0].fix and bare[0].fix.startswith("write it with a unit")


@pytest.mark.parametrize(
    "kwargs, error",
    [({"jobs": 0}, ValueError), ({"jobs": 1000}, ValueError), ({"jobs": 1.5}, ValueError), ({"time_limit": 0}, ValueError),
     ({"time_limit": -1}, ValueError), ({"time_limit": float("nan")}, ValueError), ({"overrides": [("a", "b")]}, TypeError)],
)
def test_bad_arguments_are_refused_as_the_command_line_refuses_them(kwargs, error):
    with pytest.raises(error):
        gbxc.solve(SMALL, **kwargs)


def test_a_failed_override_names_the_gearbox_not_its_variant():
    with pytest.raises(gbxc.SpecError) as e:
        gbxc.solve(SMALL, overrides={"s9.face_width": "20 mm"})
    assert "gbxc_override" not in str(e.value)
    assert "gearbox `Small`" in str(e.value)
    assert all("gbxc_override" not in d.message for d in e.value.diagnostics)


def test_an_override_with_one_gearbox_keeps_its_baseline():
    """`relative(…)` reads the gearbox's baseline: asked for one gearbox, its baseline is there,
    overridden alike (here with the spec's own value: the CLI's bytes)."""
    spec = ROOT / "specs" / "turbine_modification.gbx"
    out, _, status = cli("solve", str(spec), "--gearbox", "TurbineReducer", "--format", "json", "--no-timings", "-q")
    report = gbxc.solve(str(spec), gearbox="TurbineReducer", overrides={"operating.power": "7500 kW"}, timings=False)
    assert report.status == status == 0
    assert report.to_json() == out
    values = report.gearboxes["TurbineReducer"].designs[0].values
    relative = [k for k in values if k.startswith("relative(")]
    assert relative and all(values[k] is not None for k in relative)


def test_a_path_like_is_a_path_and_a_folder_is_refused_as_one():
    import pathlib

    assert gbxc.check(pathlib.Path("no/such/spec.gbx"))[0].code == "E0001"
    with pytest.raises(gbxc.SpecError) as e:
        gbxc.solve(str(ROOT / "specs"), overrides={"s1.face_width": "20 mm"})
    assert [d.code for d in e.value.diagnostics] == ["E0001"]


def test_designs_frame_of_a_gearbox_the_report_lacks():
    pytest.importorskip("pandas")
    with pytest.raises(KeyError, match="Big"):
        gbxc.solve(SMALL, timings=False).designs_frame("Big")


def test_unknown_gearbox_raises():
    with pytest.raises(gbxc.SpecError, match="no gearbox `Big`"):
        gbxc.solve(SMALL, gearbox="Big")


def test_designs_frame_has_units_in_its_column_names():
    pandas = pytest.importorskip("pandas")
    report = gbxc.solve(str(ROOT / "specs" / "helical_reducer.gbx"), timings=False)
    frame = report.designs_frame()
    assert isinstance(frame, pandas.DataFrame)
    g = report.gearboxes["HelicalReducer"]
    assert len(frame) == len(g.designs)
    assert "input.A.life [s]" in frame.columns
    assert frame["input.A.life [s]"].iloc[0] == g.designs[0].values["input.A.life"]


def test_designs_frame_says_what_to_install(monkeypatch):
    import builtins

    real = builtins.__import__

    def no_pandas(name, *args, **kwargs):
        if name == "pandas":
            raise ImportError("No module named 'pandas'")
        return real(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_pandas)
    with pytest.raises(ImportError, match="python3-pandas"):
        gbxc.solve(SMALL, timings=False).designs_frame()


def test_notebook_view_is_the_html_reports_summary(tmp_path):
    spec = ROOT / "specs" / "helical_reducer.gbx"
    cli("solve", str(spec), "--format", "html", "--no-timings", "-q", "-o", str(tmp_path))
    page = (tmp_path / "report.html").read_text()
    start = page.index('<section class="summary">')
    end = page.index("</section>", start) + len("</section>")
    framed = gbxc.solve(str(spec), timings=False)._repr_html_()
    assert framed.startswith("<iframe srcdoc=")
    inner = html.unescape(framed.split('srcdoc="', 1)[1].split('" style=', 1)[0])
    assert page[start:end] in inner
    assert "<style>" in inner  # the report's style, inside the frame only


def test_report_reads_as_the_spec():
    report = gbxc.solve(str(ROOT / "specs" / "helical_reducer.gbx"), timings=False)
    g = report.gearboxes["HelicalReducer"]
    best = g.designs[0]
    assert best.rank == 1 and best.teeth["hs.pinion.z"] > 0
    assert g.funnel and g.funnel[0]["rule"] == "domain"
    assert "hs" in g.ratings
    assert isinstance(g.warnings, list) and isinstance(g.notes, list)
    assert "HelicalReducer" in repr(report)
