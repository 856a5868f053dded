"""Report.to_json() is the bytes of `gbxc solve --format json` for every spec of specs/."""

import pytest

import gbxc
from conftest import ROOT, SLOW_SPECS, cli

SPECS = sorted((ROOT / "specs").glob("*.gbx"))


@pytest.mark.parametrize(
    "spec", [pytest.param(s, id=s.name, marks=[pytest.mark.slow] if s.name in SLOW_SPECS else []) for s in SPECS]
)
def test_json_is_the_clis(spec):
    out, err, status = cli("solve", str(spec), "--format", "json", "--no-timings", "-q")
    report = gbxc.solve(str(spec), timings=False)
    assert report.status == status, err
    assert report.to_json() == out
    assert set(report.gearboxes) == {g["name"] for g in report.data["gearboxes"]}
