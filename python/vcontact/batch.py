"""Many scenarios in one call: run_batch, and parameter overrides by path into a scenario.

The runs go to C++ (vcontact._vcontact.run_batch) as JSON text and run on a TBB thread pool
with the GIL released; each comes back as a dict of NumPy arrays and numbers (docs/PYTHON.md,
"Batches"). A path names one value of the scenario's JSON (docs/STUDY.md, "Paths"):

    models.steel.effects.coulomb.mu      a key of an object, level by level
    loads.drive.stiffness[0]             an index of a list ("stiffness.0" is the same)
    bodies.peg.pose.x                    a list element by its "name"; a pose's x, y, z, roll,
                                         pitch, yaw (degrees), whatever form the pose has
    bodies.block.shape.scale             a mesh file's scale (PATH@SCALE); a primitive's
                                         radius, length (cylinder) or x, y, z (box)
"""

import copy
import json
import os
import re

from . import _vcontact

__all__ = ["parse_path", "set_path", "get_path", "run_batch"]

_SEGMENT = re.compile(r"([^.\[\]]+)|\[(\d+)\]")
_POSE_KEYS = ("x", "y", "z", "roll", "pitch", "yaw")
_PRIMITIVE_KEYS = {"sphere": ("radius",), "cylinder": ("radius", "length"), "box": ("x", "y", "z")}
# Unit names a mesh file's scale may have (io/shape_spec.hpp), in metres per file unit.
_UNITS = {"m": 1.0, "cm": 0.01, "mm": 0.001, "um": 1e-6, "in": 0.0254, "ft": 0.3048}


class PathError(ValueError):  # a ValueError, like InputError
    """A path that names nothing in the scenario; the message names the path and what is there."""


def parse_path(text):
    """'loads.drive.stiffness[0]' -> ['loads', 'drive', 'stiffness', 0]."""
    if not isinstance(text, str) or not text:
        raise PathError(f"path {text!r}: expected text such as 'bodies.peg.pose.x'")
    segments, pos = [], 0
    for m in _SEGMENT.finditer(text):
        if m.start() != pos and text[pos:m.start()] != ".":
            raise PathError(f"path '{text}': cannot read '{text[pos:m.start()]}'")
        key, index = m.groups()
        segments.append(int(index) if index is not None else (int(key) if key.isdigit() else key))
        pos = m.end()
    if pos != len(text) or not segments:
        raise PathError(f"path '{text}': cannot read '{text[pos:]}'")
    return segments


def _element(items, key, where):
    """A list's element by index or by its "name" (a pair without one by "<a>-<b>")."""
    if isinstance(key, int):
        if not 0 <= key < len(items):
            raise PathError(f"{where}: index {key} out of range (the list has {len(items)})")
        return key
    names = []
    for i, item in enumerate(items):
        if isinstance(item, dict):
            name = item.get("name", f"{item.get('a')}-{item.get('b')}" if "a" in item else None)
            if name == key:
                return i
            names.append(str(name))
    raise PathError(f"{where}: no element named '{key}' (there are: {', '.join(names) or 'none'})")


def _pose_numbers(pose, where):
    """A pose in any form as [x, y, z, roll, pitch, yaw] (degrees), or 7 numbers (quaternion)."""
    values = [float(v) for v in pose.split(",")] if isinstance(pose, str) else list(pose)
    if len(values) == 3:
        values += [0.0, 0.0, 0.0]
    if len(values) not in (6, 7):
        raise PathError(f"{where}: a pose of {len(values)} numbers (expected 3, 6 or 7)")
    return values


def _set_pose(parent, key, component, value, where):
    values = _pose_numbers(parent[key], where)
    i = component if isinstance(component, int) else _POSE_KEYS.index(component)
    if i >= len(values):
        raise PathError(f"{where}: index {i} of a pose of {len(values)} numbers")
    if len(values) == 7 and i >= 3:
        raise PathError(f"{where}.{component}: the pose is a quaternion (x,y,z,qw,qx,qy,qz); "
                        "give it as x,y,z,roll,pitch,yaw to vary an angle")
    values[i] = value
    parent[key] = values


def _shape_parts(text, where):
    """(kind, numbers, mesh path) of a shape's text."""
    for kind, names in _PRIMITIVE_KEYS.items():
        if text.startswith(kind + ":"):
            return kind, [float(v) for v in text[len(kind) + 1:].split(",")], None
    if text == "halfspace":
        raise PathError(f"{where}: a half-space has no dimension")
    path, _, scale = text.rpartition("@")
    number = _UNITS.get(scale)
    if number is None:
        try:
            number = float(scale)
        except ValueError:  # no scale: the text after "@" is part of the path (README, Shapes)
            return "mesh", [1.0], text
    return "mesh", [number], path


def _set_shape(parent, key, component, value, where):
    kind, numbers, path = _shape_parts(parent[key], where)
    names = ("scale",) if kind == "mesh" else _PRIMITIVE_KEYS[kind]
    if component not in names:
        raise PathError(f"{where}.{component}: a {kind} shape has {', '.join(names)}")
    numbers[names.index(component)] = value
    text = ",".join(repr(float(v)) for v in numbers)
    parent[key] = f"{path}@{text}" if kind == "mesh" else f"{kind}:{text}"


def _descend(doc, segments, text):
    """The container holding the path's last segment, and that segment (checked to exist,
    except a new key of an object, which the scenario reader then judges)."""
    node, where = doc, ""
    for depth, seg in enumerate(segments[:-1]):
        where = f"{where}.{seg}" if where else str(seg)
        if isinstance(node, dict):
            if seg not in node:
                known = ", ".join(map(str, node)) or "none"
                raise PathError(f"path '{text}': no '{seg}' at {where} (there are: {known})")
            nxt = node[seg]
        elif isinstance(node, list):
            nxt = node[_element(node, seg, f"path '{text}' at {where}")]
        else:
            raise PathError(f"path '{text}': {where.rpartition('.')[0] or 'the top'} is a value, "
                            f"not an object or a list")
        if isinstance(nxt, (str, list)) and seg in ("pose", "shape") and depth == len(segments) - 2:
            return node, seg, segments[-1], where
        node = nxt
    return node, segments[-1], None, where


def set_path(doc, text, value, raw=False):
    """Sets the value `text` names in the JSON document `doc` (a dict, changed in place) to a
    number; with `raw`, text (an integrator's name) may replace text as well."""
    segments = parse_path(text) if isinstance(text, str) else text
    name = text if isinstance(text, str) else ".".join(map(str, text))
    parent, key, component, where = _descend(doc, segments, name)
    value = value if isinstance(value, str) and raw else float(value)
    if component is not None:
        place = f"path '{name}'"
        if key == "pose" and (component in _POSE_KEYS or isinstance(component, int)):
            return _set_pose(parent, key, component, value, place)
        if key == "shape" and isinstance(parent[key], str):
            return _set_shape(parent, key, component, value, place)
        if isinstance(parent[key], list) and isinstance(component, int):
            parent = parent[key]
            key = component
        else:
            raise PathError(f"{place}: a {key} takes "
                            f"{', '.join(_POSE_KEYS) if key == 'pose' else 'scale or a dimension'}")
    if isinstance(parent, list):
        parent[_element(parent, key, f"path '{name}'")] = value
        return None
    if not isinstance(parent, dict):
        raise PathError(f"path '{name}': {where} is a value, not an object or a list")
    if raw and isinstance(value, str) and isinstance(parent.get(key, ""), str):
        parent[key] = value
        return None
    if key in parent and not isinstance(parent[key], (int, float)) or isinstance(parent.get(key),
                                                                                  bool):
        raise PathError(f"path '{name}': the value there is {json.dumps(parent[key])[:60]}, "
                        "not a number")
    parent[key] = value
    return None


def get_path(doc, text):
    """The number a path names (after the same rules as set_path), or None for a new key."""
    probe = copy.deepcopy(doc)
    segments = parse_path(text)
    parent, key, component, _ = _descend(probe, segments, text)
    if component is None:
        return parent[_element(parent, key, text)] if isinstance(parent, list) else parent.get(key)
    if key == "pose" and (component in _POSE_KEYS or isinstance(component, int)):
        i = component if isinstance(component, int) else _POSE_KEYS.index(component)
        return _pose_numbers(parent[key], text)[i]
    if key == "shape":
        kind, numbers, _ = _shape_parts(parent[key], text)
        names = ("scale",) if kind == "mesh" else _PRIMITIVE_KEYS[kind]
        return numbers[names.index(component)] if component in names else None
    return parent[key][component]


def _scenario_text(scenario):
    """(JSON text, source, base folder) of a path or a dict."""
    if isinstance(scenario, dict):
        return json.dumps(scenario), "scenario", os.getcwd()
    path = os.fspath(scenario)
    with open(path, encoding="utf-8") as f:
        text = f.read()
    return text, path, os.path.dirname(os.path.abspath(path))


def run_batch(scenarios, overrides=None, threads=0, events=()):
    """Runs scenarios in C++ on a TBB pool of `threads` (0: every core), the GIL released.

    `scenarios` is a list of scenario paths or dicts; or one of them with `overrides`, a list of
    {path: value} dicts, one run each (the scenario with those values set, docs/STUDY.md
    "Paths"). `events` are crossing times to record: {"name", "body", "axis" (0 x, 1 y, 2 z),
    "level" (m), "below" (bool)}. Returns one dict per run: status ("completed", "stopped",
    "error"), message, stop_cause, stop_time, wall_time (s), sim (step counts), bodies
    {name: final_p, final_q, final_v, final_w, min_p, max_p}, pairs {name: peak_f_n,
    peak_force, final_f_n, contact_time, first_contact, max_patches, impacts (columns)}, loads
    {name: peak_force, final_force, final_torque}, events {name: s}.
    """
    if overrides is None:
        items = [_scenario_text(s) for s in scenarios]
    else:
        text, source, base = _scenario_text(scenarios)
        base_doc = json.loads(text)
        items = []
        for k, values in enumerate(overrides):
            doc = copy.deepcopy(base_doc)
            for path, value in values.items():
                set_path(doc, path, value)
            items.append((json.dumps(doc), f"{source} (run {k})", base))
    return _vcontact.run_batch(items, [dict(e) for e in events], int(threads))
