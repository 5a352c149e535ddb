"""catalogue_table: an inventory spreadsheet (CSV) as the monitor's catalogue YAML, and back to what the
monitor derives from it (issue 43; used by scripts/rocking_catalogue).

Columns (header names, any order, case-insensitive; lengths in m, or mm with the suffix _mm, cm with _cm):
  id            (required) unique name
  description   free text
  sensor        (required, or --sensor) the sensor that feeds the item
  width, depth  base along the item's x and y (box), or the diameter (cylinder; depth = width)
  height        overall height (the centre of mass at half of it when the weight is "uniform")
  mass          kg (the 3-D description of a scanned row; a comment otherwise)
  com           where the weight sits: "uniform" (default), or "x y z": the centre of mass from the
                centre of the base, x along the width, y along the depth, z above the floor
  shape         box (default) | cylinder
  mu_s          static friction with the floor; or floor_material and foot_material (MATERIALS)
  x, y, yaw     pose on the floor plan (m, m, degrees counter-clockwise; yaw_rad for radians)
  scan          a mesh file (relative to the CSV) read by rocking_geometry.py instead of width..height;
                scan_unit, scan_up: its --unit and --up
"""
import csv
import io
import json
import math
import os
import re

# Typical static friction (engineering handbooks; dry, clean): a first guess, measure critical items.
MATERIALS = {
    ("steel", "concrete"): 0.45, ("steel", "vinyl"): 0.35, ("steel", "terrazzo"): 0.40,
    ("steel", "wood"): 0.40, ("steel", "steel"): 0.50, ("steel", "tile"): 0.35,
    ("rubber", "concrete"): 0.80, ("rubber", "vinyl"): 0.60, ("rubber", "terrazzo"): 0.60,
    ("rubber", "wood"): 0.70, ("rubber", "tile"): 0.60,
    ("wood", "concrete"): 0.60, ("wood", "vinyl"): 0.40, ("wood", "wood"): 0.40,
    ("wood", "terrazzo"): 0.50, ("wood", "tile"): 0.45,
    ("castor", "vinyl"): 0.30, ("castor", "concrete"): 0.35, ("castor", "terrazzo"): 0.30,
    ("castor", "tile"): 0.30, ("castor", "wood"): 0.30,
    ("stone", "stone"): 0.60, ("stone", "wood"): 0.50, ("stone", "concrete"): 0.65,
    ("stone", "steel"): 0.55, ("stone", "terrazzo"): 0.60, ("stone", "tile"): 0.55, ("stone", "vinyl"): 0.50,
    ("felt", "wood"): 0.30, ("felt", "vinyl"): 0.25, ("felt", "tile"): 0.25,
}
LENGTH_SUFFIX = {"": 1.0, "_m": 1.0, "_mm": 1e-3, "_cm": 1e-2}
KNOWN = {"id", "description", "sensor", "width", "depth", "height", "mass", "com", "shape", "mu_s",
         "floor_material", "foot_material", "x", "y", "yaw", "yaw_deg", "yaw_rad", "scan", "scan_unit",
         "scan_up"}
LENGTHS = {"width", "depth", "height", "x", "y"}
# Which spreadsheet column a catalogue key comes from (to name it in the node parser's errors).
KEY_COLUMN = {"width": "width", "depth": "depth", "cg_height": "height", "eccentricity": "com",
              "eccentricity_y": "com", "shape": "shape", "mu_s": "mu_s", "pose": "x", "sensor": "sensor",
              "description": "description", "id": "id", "radius_of_gyration": "height",
              "radius_of_gyration_y": "height", "mass": "mass", "centre_of_mass": "com",
              "base_polygon": "scan", "central_inertia": "scan"}


class TableError(Exception):
    """A spreadsheet cell the catalogue cannot hold; the message names the row and the column."""


def read_table(path):
    """Rows as dicts of canonical column -> (text, scale), with the row number of the file (header
    is row 1). Unknown columns are an error (a misspelt header would be silently ignored)."""
    try:
        with open(path, newline="", encoding="utf-8-sig") as f:
            text = f.read()
    except OSError as e:
        raise TableError(f"{path}: cannot read ({e.strerror})")
    reader = csv.reader(io.StringIO(text))
    try:
        header = next(reader)
    except StopIteration:
        raise TableError(f"{path}: empty (no header row)")
    columns = []
    for k, name in enumerate(header):
        key = name.strip().lower().replace(" ", "_")
        scale, base = 1.0, key
        for suffix, s in LENGTH_SUFFIX.items():
            if suffix and key.endswith(suffix) and key[: -len(suffix)] in LENGTHS:
                base, scale = key[: -len(suffix)], s
        if base == "mass_kg":
            base = "mass"
        if base not in KNOWN:
            raise TableError(f"{path}: row 1, column {k + 1} '{name}': unknown column (known: "
                             f"{', '.join(sorted(KNOWN))}; lengths may end in _mm or _cm)")
        columns.append((base, scale, name.strip()))
    if "id" not in [c[0] for c in columns]:
        raise TableError(f"{path}: row 1: no 'id' column")
    rows = []
    for lineno, cells in enumerate(reader, 2):
        if not any(c.strip() for c in cells):
            continue
        if len(cells) > len(columns):
            raise TableError(f"{path}: row {lineno}: {len(cells)} cells, the header has {len(columns)}")
        row = {"_row": lineno}
        for (base, scale, name), cell in zip(columns, cells):
            if cell.strip():
                row[base] = (cell.strip(), scale, name)
        rows.append(row)
    if not rows:
        raise TableError(f"{path}: no rows under the header")
    return rows


def _number(path, row, key, positive=False):
    text, scale, name = row[key]
    try:
        x = float(text) * scale
    except ValueError:
        raise TableError(f"{path}: row {row['_row']}, column '{name}': '{text}' is not a number")
    if not math.isfinite(x) or (positive and not x > 0):
        raise TableError(f"{path}: row {row['_row']}, column '{name}': {text} must be a "
                         f"{'positive' if positive else 'finite'} number")
    return x


def _friction(path, row):
    if "mu_s" in row:
        return _number(path, row, "mu_s")
    if "floor_material" in row or "foot_material" in row:
        foot = row.get("foot_material", ("", 1, "foot_material"))[0].lower()
        floor = row.get("floor_material", ("", 1, "floor_material"))[0].lower()
        mu = MATERIALS.get((foot, floor), MATERIALS.get((floor, foot)))
        if mu is None:
            known = sorted({m for pair in MATERIALS for m in pair})
            raise TableError(f"{path}: row {row['_row']}, columns 'foot_material', 'floor_material': no "
                             f"friction for {foot or '?'} on {floor or '?'} (materials: {', '.join(known)}; "
                             "or give mu_s)")
        return mu
    return None


def yaml_str(s):
    """A YAML scalar that reads back as this string (JSON strings are YAML)."""
    return s if re.fullmatch(r"[A-Za-z_][A-Za-z0-9_\-.#]*", s) and s.lower() not in (
        "true", "false", "null", "yes", "no", "on", "off") else json.dumps(s)


def item_lines(path, row, default_sensor, plan_frame):
    """(YAML lines of one item, comment) from a row without a scan."""
    g = lambda k: row[k][0] if k in row else None  # noqa: E731
    rid = g("id")
    sensor = g("sensor") or default_sensor
    if not sensor:
        raise TableError(f"{path}: row {row['_row']}: no sensor (a 'sensor' column or --sensor)")
    shape = (g("shape") or "box").lower()
    for k in ("width", "height"):
        if k not in row:
            raise TableError(f"{path}: row {row['_row']}, column '{k}': empty (or give a scan)")
    width, height = _number(path, row, "width"), _number(path, row, "height")
    depth = _number(path, row, "depth") if "depth" in row else (width if shape == "cylinder" else None)
    com = (g("com") or "uniform").lower()
    if com == "uniform":
        h, nu, nuy = height / 2, 0.5, 0.5
    else:
        parts = com.replace(",", " ").replace(";", " ").split()
        try:
            cx, cy, cz = (float(p) for p in parts)
        except ValueError:
            raise TableError(f"{path}: row {row['_row']}, column '{row['com'][2]}': '{row['com'][0]}': "
                             "'uniform' or three numbers x y z (m, from the centre of the base)")
        h, nu = cz, 0.5 + cx / width if width else float("nan")
        nuy = 0.5 + cy / depth if depth else 0.5
    lines = [f"  - id: {yaml_str(rid)}   # row {row['_row']} of {os.path.basename(path)}"]
    if g("description"):
        lines.append(f"    description: {json.dumps(g('description'))}")
    lines += [f"    sensor: {yaml_str(sensor)}",
              f"    shape: {yaml_str(shape)}",
              f"    width: {width:.9g}   # m"]
    if depth is not None:
        lines.append(f"    depth: {depth:.9g}   # m")
    lines += [f"    cg_height: {h:.9g}   # m, " + ("half the height (uniform)" if com == "uniform"
                                                 else "measured centre of mass")]
    if com != "uniform" or "eccentricity" in row:
        lines.append(f"    eccentricity: {nu:.9g}")
        if depth is not None:
            lines.append(f"    eccentricity_y: {nuy:.9g}")
    mu = _friction(path, row)
    if mu is not None:
        src = "" if "mu_s" in row else f"   # typical, {g('foot_material')} on {g('floor_material')}"
        lines.append(f"    mu_s: {mu:.9g}{src}")
    if "mass" in row:
        lines.append(f"    # mass {_number(path, row, 'mass', True):g} kg (the planar model does not need it)")
    lines += pose_lines(path, row, plan_frame)
    return lines


def pose_lines(path, row, plan_frame):
    if "x" not in row and "y" not in row:
        return []
    x = _number(path, row, "x") if "x" in row else 0.0
    y = _number(path, row, "y") if "y" in row else 0.0
    if "yaw_rad" in row:
        yaw = _number(path, row, "yaw_rad")
    else:
        key = "yaw_deg" if "yaw_deg" in row else "yaw"
        yaw = math.radians(_number(path, row, key)) if key in row else 0.0
    return [f"    pose: {{parent_frame: {yaml_str(plan_frame)}, x: {x:.9g}, y: {y:.9g}, yaw: {yaw:.9g}}}"]


def scan_lines(path, row, default_sensor, plan_frame):
    """A row with a scan: the entry from rocking_geometry.py (both planes and the 3-D keys)."""
    import rocking_geometry as rg
    import scan_entry
    scan = os.path.join(os.path.dirname(os.path.abspath(path)), row["scan"][0])
    mass = _number(path, row, "mass", True) if "mass" in row else 1.0
    com = None
    if "com" in row and row["com"][0].lower() != "uniform":
        try:
            com = [float(p) for p in row["com"][0].replace(",", " ").replace(";", " ").split()]
            assert len(com) == 3
        except (ValueError, AssertionError):
            raise TableError(f"{path}: row {row['_row']}, column 'com': with a scan, 'uniform' or the "
                             "measured centre of mass x y z in the mesh's frame, m")
    try:
        g, _, notes = scan_entry.scan_geometry(scan, mass, com=com,
                                               unit=row.get("scan_unit", ("auto",))[0],
                                               up=row.get("scan_up", (None,))[0])
    except rg.GeometryError as e:
        raise TableError(f"{path}: row {row['_row']}, column 'scan': {e}")
    sensor = row.get("sensor", (default_sensor,))[0]
    if not sensor:
        raise TableError(f"{path}: row {row['_row']}: no sensor (a 'sensor' column or --sensor)")
    text = rg.catalogue_entry(row["id"][0], g, sensor, mu_s=None, extra=scan_entry.entry_comments(g))
    lines = text.rstrip("\n").split("\n")
    lines[0] = f"  - id: {yaml_str(row['id'][0])}   # row {row['_row']}: scan {row['scan'][0]}"
    lines[1] = f"    sensor: {yaml_str(sensor)}"
    if "description" in row:
        lines.insert(1, f"    description: {json.dumps(row['description'][0])}")
    mu = _friction(path, row)
    if mu is not None:
        lines.append(f"    mu_s: {mu:.9g}")
    return lines + pose_lines(path, row, plan_frame)


def catalogue_text(path, rows, default_sensor=None, plan_frame="accelerometer", topics=None, made_by=""):
    """The whole YAML (sensors: and items:) with its comments; rows in order."""
    blocks = [(scan_lines if "scan" in row else item_lines)(path, row, default_sensor, plan_frame) for row in rows]
    return document(f"from-table {os.path.basename(path)}", blocks, topics, made_by,
                    "each item names its spreadsheet row")


def document(source, blocks, topics=None, made_by="", about=""):
    """The catalogue file: a sensors: list for the items' sensors (topic from `topics`, default
    /<sensor>/imu) and the items' blocks of lines."""
    sensors = []
    for lines in blocks:
        s = [ln for ln in lines if ln.startswith("    sensor:")][0].split(":", 1)[1].strip()
        if s not in sensors:
            sensors.append(s)
    topics = topics or {}
    out = [f"# rocking_monitor catalogue written by rocking_catalogue {source}",
           f"# {made_by}" if made_by else "#",
           f"# Units SI. Items' keys: config/catalogue_example.yaml{'; ' + about if about else ''}.",
           "# Edit the sensors' topics to your accelerometers (default /<sensor>/imu, sensor_msgs/Imu).",
           "sensors:"]
    for s in sensors:
        name = json.loads(s) if s.startswith('"') else s
        out.append(f"  - name: {s}\n    topic: {topics.get(name, '/' + re.sub(r'[^A-Za-z0-9_/]', '_', name) + '/imu')}"
                   "\n    type: imu")
    out.append("items:")
    return "\n".join(out + ["\n".join(b) for b in blocks]) + "\n"


ERROR_RE = re.compile(r"items\[(\d+)\](?: '([^']*)')?: ([A-Za-z_]+)")


def locate_error(message, path, rows):
    """The node parser's message with the spreadsheet row and column in front."""
    m = ERROR_RE.search(message)
    if not m:
        return f"{path}: {message}"
    k, key = int(m.group(1)), m.group(3)
    if k >= len(rows):
        return f"{path}: {message}"
    row = rows[k]
    column = KEY_COLUMN.get(key, key)
    if column == "mu_s" and "mu_s" not in row:
        column = "floor_material/foot_material"
    if column == "height" and "scan" in row:
        column = "scan"
    name = row[column][2] if column in row else column
    return f"{path}: row {row['_row']}, column '{name}': {message[m.start():]}"
