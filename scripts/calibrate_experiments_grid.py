"""calibrate_experiments_grid: calibrate_experiments.py's grid of model settings (issue 42 split it out).

The grid file (JSON, or YAML where PyYAML is installed) or the command-line flags to the grid points
per specimen (geometry, runtime arguments), and one line describing a point; the file's format is
in calibrate_experiments.py's docstring. Errors name the file and the field.
"""
import json
import shlex

from calibrate_experiments_fit import CalibrationError

# A specimen's centre of mass on the grid: the data's stated one, the homogeneous mesh's, or the one the
# Virtual Shake Robot's URDF simulates (rocking_geometry.py --urdf-com; SP2: the stated one's opposite)
COM_CANDIDATES = ("stated", "homogeneous", "urdf")


# ================================================================ the grid

def load_grid_file(path):
    try:
        with open(path) as fh:
            text = fh.read()
    except OSError as e:
        raise CalibrationError(f"{path}: cannot read ({e})")
    if path.endswith((".yaml", ".yml")):
        try:
            import yaml
        except ImportError:
            raise CalibrationError(f"{path}: YAML needs PyYAML; give the grid as JSON")
        try:
            return yaml.safe_load(text)
        except yaml.YAMLError as e:
            raise CalibrationError(f"{path}: {e}")
    try:
        return json.loads(text)
    except json.JSONDecodeError as e:
        raise CalibrationError(f"{path}:{e.lineno}:{e.colno}: {e.msg}")


def _strings(v, where):
    if not isinstance(v, list) or not all(isinstance(s, (str, int, float)) for s in v):
        raise CalibrationError(f"{where}: must be a list of arguments (strings)")
    return [str(s) for s in v]


def parse_grid(doc, where="grid"):
    """Grid dict -> {"points": {specimen: [(geometry, runtime)]}, ...}; geometry a dict
    (tolerance_m, com, com_shift_m), runtime a tuple of arguments. Errors name the field."""
    if not isinstance(doc, dict):
        raise CalibrationError(f"{where}: expected a map with 'specimens' and 'runtime'")
    unknown = set(doc) - {"specimens", "runtime", "geometry_args", "common_args"}
    if unknown:
        raise CalibrationError(f"{where}: unknown field(s) {', '.join(sorted(unknown))}")
    specs = doc.get("specimens")
    if not isinstance(specs, dict) or not specs:
        raise CalibrationError(f"{where}: specimens: a non-empty map specimen -> geometry choices")
    runtime = doc.get("runtime", [[]])
    if not isinstance(runtime, list) or not runtime:
        raise CalibrationError(f"{where}: runtime: a non-empty list of argument lists ([] = defaults)")
    runtime = [tuple(_strings(r, f"{where}: runtime[{i}]")) for i, r in enumerate(runtime)]
    if len(set(runtime)) != len(runtime):
        raise CalibrationError(f"{where}: runtime: an argument list appears twice")
    geometry_args = _strings(doc.get("geometry_args", []), f"{where}: geometry_args")
    common_args = _strings(doc.get("common_args", []), f"{where}: common_args")
    points = {}
    for name, s in specs.items():
        w = f"{where}: specimens: {name}"
        if not isinstance(s, dict):
            raise CalibrationError(f"{w}: expected a map (contact_tolerance_mm, com, com_shift_mm)")
        bad = set(s) - {"contact_tolerance_mm", "com", "com_shift_mm"}
        if bad:
            raise CalibrationError(f"{w}: unknown field(s) {', '.join(sorted(bad))}")
        tols = s.get("contact_tolerance_mm", [1.0])
        if not isinstance(tols, list) or not tols or not all(isinstance(t, (int, float)) and t >= 0 for t in tols):
            raise CalibrationError(f"{w}: contact_tolerance_mm: a non-empty list of numbers >= 0")
        coms = s.get("com", ["stated"])
        if not isinstance(coms, list) or not coms or not all(c in COM_CANDIDATES for c in coms):
            raise CalibrationError(f"{w}: com: a non-empty list of 'stated' / 'homogeneous' / 'urdf'")
        shifts = s.get("com_shift_mm", [[0, 0]])
        if not isinstance(shifts, list) or not shifts or not all(
                isinstance(d, list) and len(d) == 2 and all(isinstance(x, (int, float)) for x in d) for d in shifts):
            raise CalibrationError(f"{w}: com_shift_mm: a non-empty list of [dx, dy] pairs (mm)")
        pts = []
        for t in tols:
            for c in coms:
                for d in shifts:
                    geo = {"contact_tolerance_m": t / 1000.0, "com": c,
                           "com_shift_m": [d[0] / 1000.0, d[1] / 1000.0]}
                    for r in runtime:
                        pts.append((geo, r))
        points[name] = pts
    return {"points": points, "geometry_args": geometry_args, "common_args": common_args,
            "runtime": runtime}


def grid_from_flags(a):
    shifts = []
    for s in a.com_shift_mm:
        try:
            dx, dy = (float(x) for x in s.split(","))
        except ValueError:
            raise CalibrationError(f"--com-shift-mm {s}: expected DX,DY in mm")
        shifts.append([dx, dy])
    spec = {"contact_tolerance_mm": a.tolerances_mm, "com": a.com, "com_shift_mm": shifts}
    return {"specimens": {n: dict(spec) for n in a.specimens},
            "runtime": [shlex.split(r) for r in a.runtime],
            "geometry_args": shlex.split(a.geometry_args), "common_args": shlex.split(a.common_args)}


def describe(geo, runtime, aliases=()):
    """One line per grid point; settings that gave the same model (aliases) joined with '='
    where they differ, e.g. SP1's 'com stated = homogeneous' (SP1 has no stated centre)."""
    def parts(g):
        p = [f"tol {g['contact_tolerance_m'] * 1000:g} mm", f"com {g['com']}"]
        p.append("shift ({:g}, {:g}) mm".format(*(1000 * x for x in g["com_shift_m"]))
                 if any(g["com_shift_m"]) else "")
        return p
    cols = [parts(geo)] + [parts(g) for g in aliases]
    out = []
    for k in range(len(cols[0])):
        vals = list(dict.fromkeys(c[k] for c in cols if c[k]))
        if vals:
            out.append(vals[0] + "".join(" = " + v.split(" ", 1)[-1] if v.split(" ")[0] == vals[0].split(" ")[0]
                                         else " = " + v for v in vals[1:]))
    out.append(" ".join(runtime) if runtime else "defaults")
    return ", ".join(out)
