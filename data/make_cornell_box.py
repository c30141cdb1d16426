#!/usr/bin/env python3
"""Writes data/cornell_box.gltf: the Cornell box from its published measurements.

Geometry: Cornell Program of Computer Graphics, "Cornell Box Data"
(https://www.graphics.cornell.edu/online/box/data.html), vertex coordinates in millimetres exactly
as published (the walls are not quite square: the floor is 552.8 mm wide at the front and 549.6 mm
at the back, the red wall leans out to x = 556 mm at the top). Converted to metres, y up; the
open side faces -z, where the camera stands.

Each quad is split into two triangles, each with its own face normal (the red wall is slightly
non-planar), pointing into the room for the walls and out of the blocks for the blocks. Triangle
winding is counter-clockwise seen from the normal side (glTF front faces).

Light: the published area light (130 x 105 mm in the ceiling) becomes a KHR_lights_punctual spot
light 1 mm below the centre of the opening, pointing down, innerConeAngle 0 and outerConeAngle
pi/2: with glTF's smooth cone falloff that is a downward hemisphere emitter that does not light
the ceiling. There is no emissive geometry: once emissive triangles become lights, the light's flux
would be counted twice. The opening itself is just part of the ceiling.

Output is deterministic (Python 3 standard library only): run it again and diff.
Usage: data/make_cornell_box.py [output.gltf]   (default: cornell_box.gltf beside this script)
"""
import base64
import json
import math
import pathlib
import struct
import sys

MM = 0.001  # published data is in millimetres; glTF wants metres

# Diffuse albedos in linear RGB, the values commonly used for this box.
WHITE = (0.725, 0.71, 0.68)
RED = (0.63, 0.065, 0.05)
GREEN = (0.14, 0.45, 0.091)

# Surfaces as published: lists of quads, each 4 corners (x, y, z) in mm.
FLOOR = [[(552.8, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 559.2), (549.6, 0.0, 559.2)]]
CEILING = [[(556.0, 548.8, 0.0), (556.0, 548.8, 559.2), (0.0, 548.8, 559.2), (0.0, 548.8, 0.0)]]
BACK_WALL = [[(549.6, 0.0, 559.2), (0.0, 0.0, 559.2), (0.0, 548.8, 559.2), (556.0, 548.8, 559.2)]]
RIGHT_WALL = [[(0.0, 0.0, 559.2), (0.0, 0.0, 0.0), (0.0, 548.8, 0.0), (0.0, 548.8, 559.2)]]  # green
LEFT_WALL = [[(552.8, 0.0, 0.0), (549.6, 0.0, 559.2), (556.0, 548.8, 559.2), (556.0, 548.8, 0.0)]]  # red
SHORT_BLOCK = [
    [(130.0, 165.0, 65.0), (82.0, 165.0, 225.0), (240.0, 165.0, 272.0), (290.0, 165.0, 114.0)],
    [(290.0, 0.0, 114.0), (290.0, 165.0, 114.0), (240.0, 165.0, 272.0), (240.0, 0.0, 272.0)],
    [(130.0, 0.0, 65.0), (130.0, 165.0, 65.0), (290.0, 165.0, 114.0), (290.0, 0.0, 114.0)],
    [(82.0, 0.0, 225.0), (82.0, 165.0, 225.0), (130.0, 165.0, 65.0), (130.0, 0.0, 65.0)],
    [(240.0, 0.0, 272.0), (240.0, 165.0, 272.0), (82.0, 165.0, 225.0), (82.0, 0.0, 225.0)],
]
TALL_BLOCK = [
    [(423.0, 330.0, 247.0), (265.0, 330.0, 296.0), (314.0, 330.0, 456.0), (472.0, 330.0, 406.0)],
    [(423.0, 0.0, 247.0), (423.0, 330.0, 247.0), (472.0, 330.0, 406.0), (472.0, 0.0, 406.0)],
    [(472.0, 0.0, 406.0), (472.0, 330.0, 406.0), (314.0, 330.0, 456.0), (314.0, 0.0, 456.0)],
    [(314.0, 0.0, 456.0), (314.0, 330.0, 456.0), (265.0, 330.0, 296.0), (265.0, 0.0, 296.0)],
    [(265.0, 0.0, 296.0), (265.0, 330.0, 296.0), (423.0, 330.0, 247.0), (423.0, 0.0, 247.0)],
]
ROOM_CENTRE = (278.0, 274.4, 279.6)  # normals of walls, floor and ceiling face this point

# (node name, material index, quads, inward=True: normals towards ROOM_CENTRE,
#  inward=False: away from the centroid of the object's own vertices)
SURFACES = [
    ("floor", 0, FLOOR, True),
    ("ceiling", 0, CEILING, True),
    ("back_wall", 0, BACK_WALL, True),
    ("left_wall_red", 1, LEFT_WALL, True),
    ("right_wall_green", 2, RIGHT_WALL, True),
    ("short_block", 0, SHORT_BLOCK, False),
    ("tall_block", 0, TALL_BLOCK, False),
]

# Light: centre of the published opening (x 213..343, z 227..332), 1 mm below the ceiling.
LIGHT_POSITION_MM = ((213.0 + 343.0) / 2, 548.8 - 1.0, (227.0 + 332.0) / 2)
LIGHT_COLOR = (1.0, 0.706, 0.235)  # warm white of the published emission spectrum, max = 1
TARGET_FLOOR_RADIANCE = 0.5

# Camera as published: at (278, 273, -800) mm looking down +z, 35 mm lens on 25 x 25 mm film.
CAMERA_POSITION_MM = (278.0, 273.0, -800.0)
CAMERA_YFOV = 2.0 * math.atan(12.5 / 35.0)


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def normalize(a):
    length = math.sqrt(dot(a, a))
    return tuple(x / length for x in a)


def centroid(points):
    return tuple(sum(p[i] for p in points) / len(points) for i in range(3))


def f32(x):
    """x rounded to float32, so accessor min/max equal the stored data exactly."""
    return struct.unpack("<f", struct.pack("<f", x))[0]


def triangles(quads, inward):
    """(positions, normals) in mm, 3 vertices per triangle, wound counter-clockwise about the normal."""
    reference = centroid([p for q in quads for p in q])
    positions, normals = [], []
    for a, b, c, d in quads:
        for tri in ((a, b, c), (a, c, d)):
            n = normalize(cross(sub(tri[1], tri[0]), sub(tri[2], tri[0])))
            face_centre = centroid(tri)
            want = sub(ROOM_CENTRE, face_centre) if inward else sub(face_centre, reference)
            if dot(n, want) < 0:
                tri = (tri[0], tri[2], tri[1])
                n = tuple(-x for x in n)
            positions.extend(tri)
            normals.extend([n] * 3)
    return positions, normals


def light_intensity():
    """Spot intensity (cd) giving the floor below the light a radiance of TARGET_FLOOR_RADIANCE.

    A Lambertian floor at distance d straight below a point light of intensity I (the spot's
    full-intensity axis) has irradiance E = I / d^2 and radiance L = albedo / pi * E, so
    I = pi * L * d^2 / albedo. The light is coloured, so "radiance 0.5" is taken for the
    luminance (Rec. 709 weights) of albedo * colour.
    """
    d = LIGHT_POSITION_MM[1] * MM
    weights = (0.2126, 0.7152, 0.0722)
    albedo = sum(w * a * c for w, a, c in zip(weights, WHITE, LIGHT_COLOR))
    return round(math.pi * TARGET_FLOOR_RADIANCE * d * d / albedo, 4)


def build():
    buffer = bytearray()
    accessors, buffer_views, meshes, nodes = [], [], [], []

    def add_view(data):
        while len(buffer) % 4:
            buffer.append(0)
        buffer_views.append({"buffer": 0, "byteOffset": len(buffer), "byteLength": len(data), "target": 34962})
        buffer.extend(data)
        return len(buffer_views) - 1

    for name, material, quads, inward in SURFACES:
        positions_mm, normals = triangles(quads, inward)
        positions = [tuple(f32(x * MM) for x in p) for p in positions_mm]
        normals = [tuple(f32(x) for x in n) for n in normals]
        pos_view = add_view(b"".join(struct.pack("<3f", *p) for p in positions))
        nrm_view = add_view(b"".join(struct.pack("<3f", *n) for n in normals))
        accessors.append({
            "bufferView": pos_view, "componentType": 5126, "count": len(positions), "type": "VEC3",
            "min": [min(p[i] for p in positions) for i in range(3)],
            "max": [max(p[i] for p in positions) for i in range(3)],
        })
        accessors.append({"bufferView": nrm_view, "componentType": 5126, "count": len(normals), "type": "VEC3"})
        meshes.append({"name": name, "primitives": [{
            "attributes": {"POSITION": len(accessors) - 2, "NORMAL": len(accessors) - 1},
            "material": material, "mode": 4}]})
        nodes.append({"name": name, "mesh": len(meshes) - 1})

    # Spot pointing down: rotate the light's -z axis onto -y, i.e. -90 degrees about x.
    s = math.sqrt(0.5)
    nodes.append({
        "name": "ceiling_light",
        "translation": [x * MM for x in LIGHT_POSITION_MM],
        "rotation": [-s, 0.0, 0.0, s],
        "extensions": {"KHR_lights_punctual": {"light": 0}},
    })
    # glTF cameras look down their local -z: turn 180 degrees about y to look down +z.
    nodes.append({
        "name": "front",
        "camera": 0,
        "translation": [x * MM for x in CAMERA_POSITION_MM],
        "rotation": [0.0, 1.0, 0.0, 0.0],
    })

    def material(name, rgb):
        return {"name": name, "pbrMetallicRoughness": {
            "baseColorFactor": [*rgb, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}}

    return {
        "asset": {"version": "2.0", "generator": "data/make_cornell_box.py",
                  "copyright": "geometry: Cornell Program of Computer Graphics, Cornell Box Data"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "scene": 0,
        "scenes": [{"name": "cornell_box", "nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": [material("white", WHITE), material("red", RED), material("green", GREEN)],
        "cameras": [{"name": "front", "type": "perspective", "perspective": {
            "yfov": CAMERA_YFOV, "aspectRatio": 1.0, "znear": 0.01, "zfar": 100.0}}],
        "extensions": {"KHR_lights_punctual": {"lights": [{
            "name": "ceiling_light", "type": "spot", "color": list(LIGHT_COLOR),
            "intensity": light_intensity(),
            "spot": {"innerConeAngle": 0.0, "outerConeAngle": math.pi / 2}}]}},
        "accessors": accessors,
        "bufferViews": buffer_views,
        "buffers": [{"byteLength": len(buffer),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(buffer)).decode("ascii")}],
    }


def main():
    out = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent / "cornell_box.gltf"
    out.write_text(json.dumps(build(), indent=1) + "\n")
    print(f"wrote {out} (light intensity {light_intensity()} cd)")


if __name__ == "__main__":
    main()
