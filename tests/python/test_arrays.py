"""A scene's signals and spectra, and a study's sweeps, as NumPy arrays equal to the CSV tables
that `gbxc solve -o DIR --format csv` writes."""

import csv

import numpy
import pytest

import gbxc
from conftest import ROOT, cli


# The display units the sweep's CSV uses here, in SI.
SI = {"rpm": 2 * numpy.pi / 60, "": 1.0, "m/s^2": 1.0, "N": 1.0}


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
    # Each peak spectra.csv lists (written from the scene's peaks, not its plot) is a line of
    # the spectrum's arrays.
    peaks = read(tmp_path / "spectra.csv")
    assert peaks
    for p in peaks:
        sig = report.gearboxes[p["gearbox"]].scenes[p["scene"]].signals[p["spectrum"]]
        at = numpy.flatnonzero(numpy.isclose(sig.x, float(p["frequency [Hz]"]), rtol=1e-12, atol=0))
        assert len(at) == 1, p
        assert sig.y[at[0]] == pytest.approx(float(p["amplitude"]), rel=1e-12)


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
            # The CSV is in the display unit, the arrays in SI.
            x = numpy.array([float(r["x"]) for r in mine]) * SI[mine[0]["x_unit"]]
            numpy.testing.assert_allclose(x, sweep.x, rtol=1e-12, atol=0)
            y = numpy.array([float(r["value"]) for r in mine]) * SI[mine[0]["unit"]]
            numpy.testing.assert_allclose(y, values, rtol=1e-12, atol=0)


def test_a_sweeps_lines_equal_the_csv_table(tmp_path):
    spec = tmp_path / "lines.gbx"
    spec.write_text(
        """gearbox G {
  stage hs: spur { pinion.z = 20; wheel.z = 40; normal_module = 4 mm; face_width = 40 mm; }
  operating { input_speed = 1500 rpm; input_torque = 400 N*m; }
  scene te on hs { effects { loaded_mesh { slices = 1; positions = 100; } } output level(static_transmission_error, 1); }
  study map { sweep input_torque in 100 N*m..700 N*m step 300 N*m; hs.tip_relief in {0 um, 20 um};
              output te.level(static_transmission_error, 1); }
}
"""
    )
    out = tmp_path / "out"
    cli("solve", str(spec), "--format", "csv", "--no-timings", "-q", "-o", str(out))
    rows = read(out / "sweeps.csv")
    sweep = gbxc.solve(str(spec), timings=False).gearboxes["G"].sweeps["map"]
    assert sweep.lines == "hs.tip_relief"
    assert [r["line"] for r in rows] == ["hs.tip_relief"] * 6
    assert {r["unit"] for r in rows} == {"dB"}
    line = numpy.array([float(r["line_value"]) for r in rows]) * 1e-6  # um
    numpy.testing.assert_allclose(sweep.line, line, rtol=1e-12, atol=1e-18)
    numpy.testing.assert_allclose(sweep.outputs["te.level(static_transmission_error, 1)"],
                                  [float(r["value"]) for r in rows], rtol=1e-12, atol=0)
