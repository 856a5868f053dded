#!/usr/bin/env python3
"""Validate gbxc's JSON report against docs/report.schema.json.

  validate_report.py SCHEMA GBXC SPEC [gbxc args...]
      Runs `GBXC solve SPEC --format json [gbxc args...]`, requires exit status 0, and
      validates the report. CPU times are expected exactly when `--no-timings` is absent.
  validate_report.py --file SCHEMA REPORT.json [--timings | --no-timings]
      Validates a report already written (CPU times checked only when a flag says which).
  validate_report.py --self-test SCHEMA GBXC SPEC [gbxc args...]
      Validates the spec's report, then asserts that broken copies of it fail: `candidates`
      renamed to `candidate`, the top-level `schema` dropped, and a few more.

Each problem is printed with its JSON path; the exit status is 0 only when there is none.
"""

import copy
import json
import subprocess
import sys

try:
    import jsonschema
    from jsonschema import Draft202012Validator
except ImportError as e:  # pragma: no cover
    sys.exit(f"validate_report: needs python3-jsonschema with Draft 2020-12 support: {e}")


class ReportError(Exception):
    pass


def load_json(text, what):
    """Strict JSON: no NaN/Infinity, no key given twice."""

    def no_constant(name):
        raise ValueError(f"{name} is not JSON (a value that cannot be evaluated is null)")

    def no_duplicates(pairs):
        seen = {}
        for k, v in pairs:
            if k in seen:
                raise ValueError(f"key {k!r} appears twice in one object")
            seen[k] = v
        return seen

    try:
        return json.loads(text, parse_constant=no_constant, object_pairs_hook=no_duplicates)
    except ValueError as e:
        raise ReportError(f"{what} is not valid JSON: {e}")


def load_schema(path):
    with open(path, encoding="utf-8") as f:
        schema = load_json(f.read(), path)
    try:
        Draft202012Validator.check_schema(schema)
    except jsonschema.exceptions.SchemaError as e:
        raise ReportError(f"{path} is not a valid draft 2020-12 schema: {e.message} (at {e.json_path})")
    return schema


def path_of(error):
    return getattr(error, "json_path", None) or "$" + "".join(
        f"[{p}]" if isinstance(p, int) else f".{p}" for p in error.absolute_path)


def short(message, limit=300):
    return message if len(message) <= limit else message[:limit] + " …"


def describe(error):
    """The error, and for a failed oneOf/anyOf each alternative's reason."""
    if error.validator in ("oneOf", "anyOf") and error.context:
        lines = [f"{path_of(error)}: matches none of the `{error.validator}` alternatives"]
        for e in sorted(error.context, key=lambda e: (list(e.schema_path)[:1], path_of(e))):
            lines.append(f"    alternative {list(e.schema_path)[0]}: {path_of(e)}: {short(e.message)}")
        return lines
    return [f"{path_of(error)}: {short(error.message)}"]


def schema_errors(schema, report):
    v = Draft202012Validator(schema)
    out = []
    for e in sorted(v.iter_errors(report), key=lambda e: list(map(str, e.absolute_path))):
        out.extend(describe(e))
    return out


def report_errors(report, timings):
    """What the schema cannot say: CPU times exactly with timings, and each sweep point
    carrying its swept quantity under its own name, equal to `x`."""
    out = []
    if not isinstance(report, dict) or not isinstance(report.get("gearboxes"), list):
        return out
    for gi, g in enumerate(report["gearboxes"]):
        if not isinstance(g, dict):
            continue
        base = f"$.gearboxes[{gi}]"
        for name, sc in (g.get("scenes") or {}).items():
            if not isinstance(sc, dict) or "failure" in sc or timings is None:
                continue
            if timings != ("cpu_seconds" in sc):
                out.append(f"{base}.scenes['{name}']: cpu_seconds {'missing' if timings else 'present'} "
                           f"{'with' if timings else 'without'} timings")
        for name, st in (g.get("studies") or {}).items():
            if not isinstance(st, dict):
                continue
            if "runs" in st and timings is not None:
                for ri, run in enumerate(st["runs"]):
                    if isinstance(run, dict) and timings != ("cpu_seconds" in run):
                        out.append(f"{base}.studies['{name}'].runs[{ri}]: cpu_seconds {'missing' if timings else 'present'} "
                                   f"{'with' if timings else 'without'} timings")
            if "sweep" in st and isinstance(st.get("points"), list):
                target = st["sweep"]
                fixed = {"x", "outputs", "stability", "branch", "unstable"}
                for pi, p in enumerate(st["points"]):
                    if not isinstance(p, dict):
                        continue
                    where = f"{base}.studies['{name}'].points[{pi}]"
                    if target not in p:
                        out.append(f"{where}: no key '{target}' (the swept quantity under its own name)")
                    elif p[target] != p.get("x"):
                        out.append(f"{where}['{target}']: {p[target]} differs from x = {p.get('x')}")
                    # With lines, the line's quantity under its own name too.
                    line = st.get("lines")
                    if line is not None and line not in p:
                        out.append(f"{where}: no key '{line}' (the line's quantity under its own name)")
                    extra = set(p) - fixed - {target} - ({line} if line else set())
                    if extra:
                        out.append(f"{where}: unexpected keys {sorted(extra)}")
                    if (st.get("continuation") == "arclength") != ("branch" in p):
                        out.append(f"{where}: 'branch' goes with an arclength continuation, and only with one")
    return out


def run_gbxc(gbxc, spec, args):
    cmd = [gbxc, "solve", spec, "--format", "json", *args]
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    if r.returncode != 0:
        said = (r.stderr + r.stdout).decode(errors="replace")
        raise ReportError(f"`{' '.join(cmd)}` exited {r.returncode}:\n{short(said, 4000)}")
    return load_json(r.stdout.decode("utf-8"), f"the report of {spec}")


def check(schema, report, timings, label):
    problems = schema_errors(schema, report) + report_errors(report, timings)
    for p in problems:
        print(f"{label}: {p}")
    return not problems


def mutations(report):
    """Broken copies of a valid report, each of which must fail validation."""
    out = []

    def variant(what, change):
        r = copy.deepcopy(report)
        if change(r):
            out.append((what, r))

    def rename_in_gearboxes(old, new):
        def change(r):
            done = False
            for g in r["gearboxes"]:
                if old in g:
                    g[new] = g.pop(old)
                    done = True
            return done
        return change

    def first(r, section, pred):
        for g in r["gearboxes"]:
            for k, v in g.get(section, {}).items():
                if pred(v):
                    return v
        return None

    variant("`candidates` renamed to `candidate`", rename_in_gearboxes("candidates", "candidate"))
    variant("top-level `schema` dropped", lambda r: r.pop("schema", None) is not None)
    variant("top-level `schema` of another version", lambda r: r.update(schema="0.9") or True)

    def count_as_string(r):
        for g in r["gearboxes"]:
            g["count"] = str(g["count"])
        return bool(r["gearboxes"])

    variant("`count` as a string", count_as_string)

    def rename_scene_key(r):
        sc = first(r, "scenes", lambda v: "rhs_evaluations" in v)
        if sc is None:
            return False
        sc["rhs_evaluation"] = sc.pop("rhs_evaluations")
        return True

    def rename_rating_key(r):
        rt = first(r, "ratings", lambda v: "mesh" in v and v["mesh"])
        if rt is None:
            return False
        key = next(iter(rt["mesh"]))
        rt["mesh"][key + "_renamed"] = rt["mesh"].pop(key)
        return True

    def nan_candidate_ratio(r):
        for g in r["gearboxes"]:
            if g["candidates"]:
                g["candidates"][0]["ratio"] = None
                return True
        return False

    variant("a scene's `rhs_evaluations` renamed", rename_scene_key)
    variant("a rating's mesh key renamed", rename_rating_key)
    variant("a candidate's `ratio` null", nan_candidate_ratio)
    return out


def self_test(schema, report, timings, label):
    ok = check(schema, report, timings, label)
    if not ok:
        print(f"{label}: the unchanged report must validate for the self-test to mean anything")
        return False
    names = [w for w, _ in mutations(report)]
    for required in ("`candidates` renamed to `candidate`", "top-level `schema` dropped"):
        if required not in names:
            print(f"{label}: cannot make the variant with {required} (the report has no gearbox?)")
            ok = False
    for what, broken in mutations(report):
        errs = schema_errors(schema, broken)
        if errs:
            print(f"{label}: rejected as it should be, {what}: {errs[0]}")
        else:
            print(f"{label}: FAIL: the schema accepts a report with {what}")
            ok = False
    return ok


def main(argv):
    try:
        if len(argv) >= 3 and argv[0] == "--file":
            schema = load_schema(argv[1])
            timings = {"--timings": True, "--no-timings": False}.get(argv[3]) if len(argv) > 3 else None
            with open(argv[2], encoding="utf-8") as f:
                report = load_json(f.read(), argv[2])
            ok = check(schema, report, timings, argv[2])
        elif len(argv) >= 4 and argv[0] == "--self-test":
            schema = load_schema(argv[1])
            gbxc, spec, args = argv[2], argv[3], argv[4:]
            report = run_gbxc(gbxc, spec, args)
            ok = self_test(schema, report, "--no-timings" not in args, spec)
        elif len(argv) >= 3 and not argv[0].startswith("--"):
            schema = load_schema(argv[0])
            gbxc, spec, args = argv[1], argv[2], argv[3:]
            report = run_gbxc(gbxc, spec, args)
            ok = check(schema, report, "--no-timings" not in args, spec)
        else:
            print(__doc__, file=sys.stderr)
            return 2
    except (ReportError, OSError) as e:
        print(f"validate_report: {e}")
        return 1
    print("ok" if ok else "FAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
