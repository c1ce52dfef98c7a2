#!/usr/bin/env python3
"""Writes a glTF quad whose base-colour texture is a PNG declaring far more texels than a frame
needs (bench/RESULTS.md, "Memory: oversized textures"): a flat colour, so the file stays small
(a 16384^2 RGB PNG compresses to about 250 KiB) while it declares gigabytes of texels.

usage: oversized_texture.py FOLDER SIDE [rgb|rgba]
writes FOLDER/quad.gltf and FOLDER/texture.png; then measure, e.g.
  /usr/bin/time -f '%M KiB' build/punctual render FOLDER/quad.gltf --size 160x120 --out x.png
Only the standard library: zlib's stream compresses row by row, so SIDE^2 texels are never held.
"""
import json
import os
import struct
import sys
import zlib


def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


def write_png(path, side, channels):
    colour = bytes([200, 120, 60, 255][:channels])
    row = b"\x00" + colour * side  # filter byte 0, then the texels
    packer = zlib.compressobj(9)
    compressed = b"".join(packer.compress(row) for _ in range(side)) + packer.flush()
    colour_type = 2 if channels == 3 else 6
    header = struct.pack(">IIBBBBB", side, side, 8, colour_type, 0, 0, 0)
    with open(path, "wb") as out:
        out.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", compressed) + chunk(b"IEND", b""))


def write_gltf(path):
    # A 2 x 2 m quad at y = 0 seen from 3 m above, lit by a sun, textured by texture.png.
    positions = struct.pack("<12f", -1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1)
    normals = struct.pack("<12f", *([0, 1, 0] * 4))
    uvs = struct.pack("<8f", 0, 0, 1, 0, 1, 1, 0, 1)
    indices = struct.pack("<6H", 0, 2, 1, 0, 3, 2)
    blob = positions + normals + uvs + indices
    views = [(0, 48), (48, 48), (96, 32), (128, 12)]
    doc = {
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "intensity": 2.0}]}},
        "scene": 0, "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [{"mesh": 0},
                  {"camera": 0, "translation": [0, 3, 0], "rotation": [-0.70710678, 0, 0, 0.70710678]},
                  {"rotation": [-0.70710678, 0, 0, 0.70710678], "extensions": {"KHR_lights_punctual": {"light": 0}}}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "zfar": 10}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3,
                                    "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0}}],
        "textures": [{"source": 0}], "images": [{"uri": "texture.png"}],
        "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64,"
                     + __import__("base64").b64encode(blob).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": o, "byteLength": n} for o, n in views],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, 0, -1], "max": [1, 0, 1]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}],
    }
    with open(path, "w") as out:
        json.dump(doc, out)


def main(argv):
    if len(argv) not in (3, 4) or (len(argv) == 4 and argv[3] not in ("rgb", "rgba")):
        sys.stderr.write(__doc__)
        return 2
    folder, side = argv[1], int(argv[2])
    write_png(os.path.join(folder, "texture.png"), side, 4 if len(argv) == 4 and argv[3] == "rgba" else 3)
    write_gltf(os.path.join(folder, "quad.gltf"))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
