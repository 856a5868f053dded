"""gbxc from Python: check and solve .gbx gearbox specs in the script's own process.

    import gbxc
    report = gbxc.solve("reducer.gbx", overrides={"hs.face_width": "60 mm"})
    best = report.gearboxes["Reducer"].designs[0]

The same compiler and runtime as the `gbxc` command: `Report.to_json()` is the bytes of
`gbxc solve --format json`. docs/python.md describes every call.
"""

from __future__ import annotations

import html
import itertools
import json
import os
import threading
from dataclasses import dataclass, field
from typing import Any, Dict, List, Mapping, Optional, Union

from . import _gbxc

__all__ = [
    "Design",
    "Diagnostic",
    "Gearbox",
    "Report",
    "Scene",
    "Signal",
    "SolveError",
    "SpecError",
    "Sweep",
    "check",
    "solve",
    "__version__",
]

__version__: str = _gbxc.version

PathOrText = Union[str, "os.PathLike[str]"]


@dataclass(frozen=True)
class Diagnostic:
    """One finding of the checker: an error or a warning at a place in a spec."""

    code: str  # stable: E0302, W0501, ...
    severity: str  # "error", "warning" or "note"
    file: Optional[str]
    line: Optional[int]
    column: Optional[int]
    message: str
    fix: Optional[str]  # what the notes suggest, when they do

    def __str__(self) -> str:
        where = f"{self.file}:{self.line}:{self.column}: " if self.file else ""
        return f"{where}{self.severity}[{self.code}]: {self.message}"


class SpecError(Exception):
    """The spec does not check (or an override names nothing): `diagnostics` says why."""

    def __init__(self, message: str, diagnostics: List[Diagnostic]):
        super().__init__(message)
        self.diagnostics = diagnostics


class SolveError(Exception):
    """The spec checked but solving it failed (exit 3 of `gbxc solve`): the message says why."""


# How a diagnostic's message words its suggestion, after its last "; " (docs/diagnostics.md).
_SUGGESTIONS = ("did you mean", "write ", "use ", "give ", "add ", "remove ", "declare ", "import ", "put ")


def _fix(message: str, notes: List[str]) -> Optional[str]:
    """What to do about a diagnostic: its notes' suggestions, else the suggestion its message
    ends with (`did you mean `face_width`?`, `write it in mm`), else None."""
    if notes:
        return "; ".join(notes)
    for clause in reversed(message.split("; ")[1:]):
        if clause.startswith(_SUGGESTIONS):
            return clause
    return None


def _diagnostics(text: str) -> List[Diagnostic]:
    out = []
    for d in json.loads(text) if text else []:
        span = d.get("span") or {}
        notes = [n["message"] for n in d.get("notes", [])]
        out.append(
            Diagnostic(
                code=d["code"],
                severity=d["severity"],
                file=span.get("file"),
                line=span.get("line"),
                column=span.get("column"),
                message=d["message"],
                fix=_fix(d["message"], notes),
            )
        )
    return out


def _source(path_or_text: PathOrText) -> tuple:
    """(source, is_text, display): a path names a file; text holding a newline or a brace
    is a spec itself, shown in diagnostics as <text>.gbx."""
    if isinstance(path_or_text, os.PathLike):
        return os.fsdecode(path_or_text), False, os.fsdecode(path_or_text)
    s = os.fsdecode(path_or_text)
    if os.path.exists(s) or ("\n" not in s and "{" not in s):
        return s, False, s
    return s, True, "<text>.gbx"


def check(path_or_text: PathOrText) -> List[Diagnostic]:
    """The spec's diagnostics, as `gbxc check` finds them; empty when it checks clean.
    Never raises on a spec error: the errors are in the list."""
    source, is_text, display = _source(path_or_text)
    return _diagnostics(_gbxc.check(source, is_text, display)["diagnostics"])


@dataclass
class Signal:
    """A scene's plotted output: a signal over time (x in s) or a spectrum (x in Hz)."""

    key: str
    unit: str  # the unit of `y`
    spectrum: bool
    x: Any  # numpy.ndarray
    y: Any  # numpy.ndarray
    mesh_frequency: float = 0.0  # a spectrum's mesh frequency, Hz

    @property
    def x_unit(self) -> str:
        return "Hz" if self.spectrum else "s"


@dataclass
class Scene:
    """A dynamic scene of the best design: its outputs (SI), the error estimate that covers
    the model, its cost, and its plotted signals and spectra as arrays."""

    name: str
    data: Dict[str, Any]  # the scene as the JSON report holds it
    signals: Dict[str, Signal] = field(default_factory=dict)

    @property
    def outputs(self) -> Dict[str, float]:
        return dict(self.data.get("outputs", {}))

    @property
    def error_estimate(self) -> Optional[float]:
        return self.data.get("error_estimate")

    @property
    def cpu_seconds(self) -> Optional[float]:
        return self.data.get("cpu_seconds")


@dataclass
class Sweep:
    """A study's sweep: the swept value and each output along it, as arrays."""

    name: str
    x: Any  # numpy.ndarray of the swept value (SI)
    outputs: Dict[str, Any]  # output -> numpy.ndarray
    data: Dict[str, Any]
    lines: str = ""  # the quantity drawn a line per value (`hs.tip_relief in {…}`), "" without
    line: Any = None  # numpy.ndarray of each point's line value (SI), or None without lines


@dataclass
class Design:
    """A listed design: its tooth counts, its ratio, and every column's value in SI."""

    rank: int
    teeth: Dict[str, int]
    ratio: float
    ratio_exact: str
    values: Dict[str, Any]
    undecided: bool
    data: Dict[str, Any]


class Gearbox:
    """One gearbox of the report: its designs, rule funnel, ratings, scenes and sweeps."""

    def __init__(self, data: Dict[str, Any], signals: List[dict], remarks: Mapping[str, List[str]]):
        self.data = data
        self.name: str = data["name"]
        self.count: int = data.get("count", 0)
        self.columns: List[Dict[str, Any]] = data.get("columns", [])
        self.funnel: List[Dict[str, Any]] = data.get("funnel", [])
        self.ratings: Dict[str, Any] = data.get("ratings", {})
        self.warnings: List[str] = list(remarks.get("warnings", []))
        self.notes: List[str] = list(remarks.get("notes", []))
        self.designs: List[Design] = [
            Design(c["rank"], dict(c.get("teeth", {})), c.get("ratio"), c.get("ratio_exact", ""), dict(c.get("values", {})),
                   bool(c.get("undecided", False)), c)
            for c in data.get("candidates", [])
        ]
        self.scenes: Dict[str, Scene] = {}
        for name, scene in (data.get("scenes") or {}).items():
            self.scenes[name] = Scene(name, scene)
        for p in signals:
            scene = self.scenes.setdefault(p["scene"], Scene(p["scene"], {}))
            scene.signals[p["key"]] = Signal(p["key"], p["unit"], p["spectrum"], p["x"], p["y"], p["mesh_frequency"])
        self.sweeps: Dict[str, Sweep] = {}
        for name, study in (data.get("studies") or {}).items():
            if isinstance(study, dict) and "sweep" in study and "points" in study:
                self.sweeps[name] = _sweep(name, study)

    def __repr__(self) -> str:
        return f"<gbxc.Gearbox {self.name}: {len(self.designs)} designs listed of {self.count}>"


def _sweep(name: str, body: Dict[str, Any]) -> Sweep:
    import numpy

    points = body["points"]
    keys: List[str] = []
    for p in points:
        for k in p.get("outputs", {}):
            if k not in keys:
                keys.append(k)
    x = numpy.array([p["x"] for p in points], dtype=float)
    outputs = {k: numpy.array([p.get("outputs", {}).get(k, numpy.nan) for p in points], dtype=float) for k in keys}
    lines = body.get("lines", "")
    line = numpy.array([p[lines] for p in points], dtype=float) if lines else None
    return Sweep(name, x, outputs, body, lines, line)


class Report:
    """What `gbxc solve` reports: the gearboxes by name, with their designs, ratings, scenes
    and sweeps; `to_json()` is the JSON report itself."""

    def __init__(self, solved: Any):
        self._summary: str = solved.summary_html
        self._json: str = solved.json
        self.data: Dict[str, Any] = json.loads(self._json) if self._json else {"gearboxes": []}
        self.status: int = solved.status  # 0 solved; 3 a part failed or the time limit cut the search
        self.errors: str = solved.errors  # what the solve printed as errors (a partial search's note)
        self.warnings: List[Diagnostic] = _diagnostics(solved.diagnostics)  # the checker's warnings
        signals = solved.plots()
        remarks = solved.remarks()
        self.gearboxes: Dict[str, Gearbox] = {}
        for g in self.data.get("gearboxes", []):
            mine = [p for p in signals if p["gearbox"] == g["name"]]
            self.gearboxes[g["name"]] = Gearbox(g, mine, remarks.get(g["name"], {}))

    def to_json(self) -> str:
        """The JSON report: the same bytes as `gbxc solve --format json` for the same input."""
        return self._json

    def designs_frame(self, gearbox: Optional[str] = None):
        """The listed designs as a pandas DataFrame, a column per value with its SI unit in the
        name (`input.A.life [s]`). Needs pandas (Debian: python3-pandas)."""
        try:
            import pandas
        except ImportError as e:
            raise ImportError("Report.designs_frame() needs pandas: apt install python3-pandas (or pip install pandas)") from e
        if gearbox is not None and gearbox not in self.gearboxes:
            raise KeyError(f"the report has no gearbox {gearbox!r} (it has {', '.join(self.gearboxes) or 'none'})")
        rows = []
        for g in self.gearboxes.values():
            if gearbox is not None and g.name != gearbox:
                continue
            units = {c["name"]: c.get("si_unit", "") for c in g.columns}
            for d in g.designs:
                row: Dict[str, Any] = {"gearbox": g.name, "rank": d.rank}
                row.update(d.teeth)
                row["ratio"] = d.ratio
                for k, v in d.values.items():
                    unit = units.get(k, "")
                    row[f"{k} [{unit}]" if unit and unit != "1" else k] = v
                rows.append(row)
        return pandas.DataFrame(rows)

    @property
    def ok(self) -> bool:
        """Solved whole: status 0, every gearbox searched, rated and simulated."""
        return self.status == 0

    def _repr_html_(self) -> str:
        """The HTML report's summary card, in a frame of its own so that its style stays
        out of the notebook's."""
        height = 120 + 300 * max(1, len(self.gearboxes))
        page = "<!DOCTYPE html><html><head><meta charset=\"utf-8\"></head><body>" + self._summary + "</body></html>"
        return (f'<iframe srcdoc="{html.escape(page, quote=True)}" style="width:100%;height:{height}px;border:none" '
                f'title="gbxc report summary"></iframe>')

    def __repr__(self) -> str:
        names = ", ".join(self.gearboxes) or "no gearbox"
        return f"<gbxc.Report: {names}>"


_tokens = itertools.count(1)


def _interruptible(token: int, call, *args):
    """Runs the native call (which releases the GIL) on a thread of its own and waits for it
    here, where Ctrl-C arrives as KeyboardInterrupt: the solve is then told to stop, as its
    time limit would stop it, and the interrupt raised once it has."""
    result: Dict[str, Any] = {}

    def target():
        try:
            result["value"] = call(*args)
        except BaseException as e:  # handed to the waiting thread
            result["error"] = e

    worker = threading.Thread(target=target, name="gbxc solve", daemon=True)
    try:
        # Started inside the try: a Ctrl-C that lands while it starts still stops the solve.
        worker.start()
        while worker.is_alive():
            worker.join(0.1)
    except KeyboardInterrupt:
        while worker.is_alive():
            _gbxc.interrupt(token)
            worker.join(0.05)
        raise
    if "error" in result:
        raise result["error"]
    return result["value"]


def solve(
    path_or_text: PathOrText,
    gearbox: Optional[str] = None,
    jobs: int = 1,
    time_limit: Optional[float] = None,
    overrides: Optional[Mapping[str, Union[str, float, int]]] = None,
    timings: bool = True,
) -> Report:
    """Solves the spec (a path, or the spec's text) as `gbxc solve` does and returns its
    Report. `overrides` sets fixed attributes and operating values by path, with units
    (`{"hs.face_width": "60 mm", "operating.power": "250 kW"}`). Raises SpecError when the
    spec or an override does not check, SolveError when solving fails, and KeyboardInterrupt
    on Ctrl-C (within a second). `timings=False` leaves CPU times out (same bytes each run)."""
    source, is_text, display = _source(path_or_text)
    if isinstance(jobs, bool) or not isinstance(jobs, int) or not 1 <= jobs <= 256:
        raise ValueError(f"jobs needs a whole number from 1 to 256, not {jobs!r}")
    if time_limit is not None and not (isinstance(time_limit, (int, float)) and 0 < time_limit < float("inf")):
        raise ValueError(f"time_limit needs a positive number of seconds (or None), not {time_limit!r}")
    if overrides is not None and not isinstance(overrides, Mapping):
        raise TypeError(f"overrides needs a mapping of path to value, such as {{'hs.face_width': '60 mm'}}, "
                        f"not a {type(overrides).__name__}")
    pairs = [(str(k), str(v)) for k, v in (overrides or {}).items()]
    token = next(_tokens)
    solved = _interruptible(token, _gbxc.solve, token, source, is_text, display, gearbox or "", int(jobs),
                            float(time_limit or 0), bool(timings), pairs)
    if solved.status == 1:
        raise SpecError(solved.diagnostics_text.strip() or "the spec has errors", _diagnostics(solved.diagnostics))
    if solved.status == 2:
        raise SpecError(solved.errors, [])
    if solved.status == 3 and not solved.json:
        raise SolveError(solved.errors.strip())
    return Report(solved)

