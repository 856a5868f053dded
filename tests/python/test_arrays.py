"""A scene's signals and spectra, and a study's sweeps, as NumPy arrays equal to the CSV tables
that `gbxc solve -o DIR --format csv` writes."""

import csv

import numpy

import gbxc
from conftest import ROOT, cli


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_signals_and_spectra_equal_the_csv_series(tmp_path):
    spec = ROOT / "specs" / "turbine_modification.gbx"
    cli("solve", str(spec), "--format", "csv", "--no-timings", "-q", "-o", str(tmp_path))
    rows = read(tmp_path / "signals.csv")
    report = gbxc.solve(str(spec), timings=False)
    seen = 0
    for g in report.gearboxes.values():
        for s in g.scenes.values():
            for key, sig in s.signals.items():
                mine = [r for r in rows if (r["gearbox"], r["scene"], r["output"]) == (g.name, s.name, key)]
                assert len(mine) == len(sig.x) == len(sig.y) > 0
                assert isinstance(sig.x, numpy.ndarray) and sig.x.dtype == float
                assert numpy.array_equal(numpy.array([float(r["x"]) for r in mine]), sig.x)
                assert numpy.array_equal(numpy.array([float(r["value"]) for r in mine]), sig.y)
                assert {r["unit"] for r in mine} == {sig.unit}
                assert {r["x_unit"] for r in mine} == {sig.x_unit}
                seen += 1
    assert seen >= 1
    assert any(sig.spectrum for g in report.gearboxes.values() for s in g.scenes.values() for sig in s.signals.values())


def test_sweeps_equal_the_csv_table(tmp_path):
    spec = ROOT / "specs" / "spur_resonance.gbx"
    cli("solve", str(spec), "--format", "csv", "--no-timings", "-q", "-o", str(tmp_path))
    rows = read(tmp_path / "sweeps.csv")
    report = gbxc.solve(str(spec), timings=False)
    g = report.gearboxes["SpurResonance"]
    assert g.sweeps
    for name, sweep in g.sweeps.items():
        assert isinstance(sweep.x, numpy.ndarray)
        for output, values in sweep.outputs.items():
            mine = [r for r in rows if (r["study"], r["output"]) == (name, output)]
            assert len(mine) == len(values)
            # The CSV is in the display unit (rpm, say): one factor from the SI arrays.
            x = numpy.array([float(r["x"]) for r in mine])
            numpy.testing.assert_allclose(x / x[0], sweep.x / sweep.x[0], rtol=1e-12)
            y = numpy.array([float(r["value"]) for r in mine])
            numpy.testing.assert_allclose(y / y[0], values / values[0], rtol=1e-12)
