#!/usr/bin/env python3
"""Writes data/cornell_moving_light.gltf: the Cornell box (make_cornell_box.py) lit by a lamp carried
through it, with a thin panel swinging over the floor: the project's own animated scene (glTF 2.0
node animation), for sequences, history under motion and flicker against the reference.

Over 2 seconds (LINEAR samplers, keys every half second):
  lamp   a point light (the box's warm colour) at 0.42 m height, carried from the front left over the
         short block to the back and out to the front right, so that its direct light, the red and
         green walls' bounce and the blocks' shadows all move;
  panel  an 18 x 0.8 x 18 cm white slab 0.38 m above the floor (above the eye), sliding along x and turning a quarter
         turn about the vertical, so that its shadow, and the indirect light under it, move.
The ceiling spot of cornell_box.gltf is left out: the lamp is the only light. The camera is the box's.

Output is deterministic (Python 3 standard library only): run it again and diff.
Usage: data/make_cornell_moving_light.py [output.gltf]   (default: beside this script)
"""
import base64
import json
import math
import pathlib
import struct
import sys

import make_cornell_box as box

LAMP_HEIGHT = 0.42
LAMP_KEYS = [(0.0, (0.14, LAMP_HEIGHT, 0.12)), (0.5, (0.20, LAMP_HEIGHT, 0.30)), (1.0, (0.28, LAMP_HEIGHT, 0.45)),
             (1.5, (0.38, LAMP_HEIGHT, 0.30)), (2.0, (0.44, LAMP_HEIGHT, 0.12))]
PANEL_HALF = (0.09, 0.004, 0.09)
PANEL_KEYS = [(t, (0.16 + 0.24 * t / 2.0, 0.38, 0.20), 45.0 * t) for t in (0.0, 0.5, 1.0, 1.5, 2.0)]  # degrees about y


def lamp_intensity():
    """Candela giving the floor straight below the lamp the box's floor radiance (make_cornell_box.py)."""
    weights = (0.2126, 0.7152, 0.0722)
    albedo = sum(w * a * c for w, a, c in zip(weights, box.WHITE, box.LIGHT_COLOR))
    return round(math.pi * box.TARGET_FLOOR_RADIANCE * LAMP_HEIGHT * LAMP_HEIGHT / albedo, 4)


def slab(half):
    """(positions, normals) of an axis-aligned box about the origin, 2 triangles a face, counter-clockwise."""
    positions, normals = [], []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            n = [0.0, 0.0, 0.0]
            n[axis] = sign
            u, v = (axis + 1) % 3, (axis + 2) % 3
            corners = []
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis] = sign * half[axis]
                p[u] = a * half[u]
                p[v] = b * half[v]
                corners.append(tuple(p))
            if sign < 0:
                corners.reverse()
            for tri in ((corners[0], corners[1], corners[2]), (corners[0], corners[2], corners[3])):
                positions.extend(tri)
                normals.extend([tuple(n)] * 3)
    return positions, normals


def build():
    doc = box.build()
    prefix = "data:application/octet-stream;base64,"
    buffer = bytearray(base64.b64decode(doc["buffers"][0]["uri"][len(prefix):]))

    def add_view(data, target=None):
        while len(buffer) % 4:
            buffer.append(0)
        view = {"buffer": 0, "byteOffset": len(buffer), "byteLength": len(data)}
        if target:
            view["target"] = target
        doc["bufferViews"].append(view)
        buffer.extend(data)
        return len(doc["bufferViews"]) - 1

    def add_accessor(values, kind, **extra):
        fmt = {"SCALAR": "<f", "VEC3": "<3f", "VEC4": "<4f"}[kind]
        data = b"".join(struct.pack(fmt, *(v if isinstance(v, tuple) else (v,))) for v in values)
        doc["accessors"].append({"bufferView": add_view(data, extra.pop("target", None)), "componentType": 5126,
                                 "count": len(values), "type": kind, **extra})
        return len(doc["accessors"]) - 1

    # The ceiling spot and its node go: the lamp is the only light.
    doc["nodes"] = [n for n in doc["nodes"] if n["name"] != "ceiling_light"]
    doc["extensions"]["KHR_lights_punctual"]["lights"] = [{
        "name": "lamp", "type": "point", "color": list(box.LIGHT_COLOR), "intensity": lamp_intensity()}]

    positions, normals = slab(PANEL_HALF)
    positions = [tuple(box.f32(x) for x in p) for p in positions]
    pos = add_accessor(positions, "VEC3", target=34962, min=[min(p[i] for p in positions) for i in range(3)],
                       max=[max(p[i] for p in positions) for i in range(3)])
    nrm = add_accessor(normals, "VEC3", target=34962)
    doc["meshes"].append({"name": "panel", "primitives": [{"attributes": {"POSITION": pos, "NORMAL": nrm},
                                                            "material": 0, "mode": 4}]})
    doc["nodes"].append({"name": "panel", "mesh": len(doc["meshes"]) - 1, "translation": list(PANEL_KEYS[0][1])})
    panel = len(doc["nodes"]) - 1
    doc["nodes"].append({"name": "lamp", "translation": list(LAMP_KEYS[0][1]),
                         "extensions": {"KHR_lights_punctual": {"light": 0}}})
    lamp = len(doc["nodes"]) - 1
    doc["scenes"][0]["nodes"] = list(range(len(doc["nodes"])))

    def times(keys):
        values = [float(k[0]) for k in keys]
        return add_accessor(values, "SCALAR", min=[min(values)], max=[max(values)])

    def turn(degrees):  # about +y, (x, y, z, w)
        half = math.radians(degrees) / 2
        return (0.0, math.sin(half), 0.0, math.cos(half))

    samplers = [
        {"input": times(LAMP_KEYS), "output": add_accessor([k[1] for k in LAMP_KEYS], "VEC3"), "interpolation": "LINEAR"},
        {"input": times(PANEL_KEYS), "output": add_accessor([k[1] for k in PANEL_KEYS], "VEC3"),
         "interpolation": "LINEAR"},
        {"input": times(PANEL_KEYS), "output": add_accessor([turn(k[2]) for k in PANEL_KEYS], "VEC4"),
         "interpolation": "LINEAR"},
    ]
    doc["animations"] = [{"name": "lamp_and_panel", "samplers": samplers, "channels": [
        {"sampler": 0, "target": {"node": lamp, "path": "translation"}},
        {"sampler": 1, "target": {"node": panel, "path": "translation"}},
        {"sampler": 2, "target": {"node": panel, "path": "rotation"}},
    ]}]
    doc["asset"]["generator"] = "data/make_cornell_moving_light.py"
    doc["buffers"][0] = {"byteLength": len(buffer), "uri": prefix + base64.b64encode(bytes(buffer)).decode("ascii")}
    return doc


def main():
    here = pathlib.Path(__file__).resolve().parent
    out = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else here / "cornell_moving_light.gltf"
    out.write_text(json.dumps(build(), indent=1) + "\n")
    print(f"wrote {out} (lamp intensity {lamp_intensity()} cd)")


if __name__ == "__main__":
    main()
