#!/usr/bin/env python3
"""Writes the hand-made glTF seeds of the glTF fuzz target into corpus/gltf (run from anywhere;
the files are committed, this script says how they were made). Each is small and valid, and
together they reach every part of the loader: indexed and non-indexed triangles, normals, UVs,
a base-colour texture (PNG) in a data: URI and in a GLB buffer view, materials, a perspective
and an orthographic camera, node matrices and TRS, and point, spot and directional lights."""
import base64
import json
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "corpus", "gltf")
FLOAT, USHORT, UINT = 5126, 5123, 5125


def png_2x2():
    rows = b"\x00\xff\x00\x00\xff\x00\xff\x00\xff" + b"\x00\x00\x00\xff\xff\xff\xff\xff\xff"  # filter 0, RGB

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    header = struct.pack(">IIBBBBB", 2, 2, 8, 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b"")


def quad_buffer():
    positions = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]
    normals = [0, 0, 1] * 4
    uvs = [0, 0, 1, 0, 1, 1, 0, 1]
    indices = [0, 1, 2, 0, 2, 3]
    data = struct.pack("<12f", *positions) + struct.pack("<12f", *normals) + struct.pack("<8f", *uvs)
    data += struct.pack("<6H", *indices) + b"\x00\x00"  # pad to 4 bytes
    views = [
        {"buffer": 0, "byteOffset": 0, "byteLength": 48},
        {"buffer": 0, "byteOffset": 48, "byteLength": 48},
        {"buffer": 0, "byteOffset": 96, "byteLength": 32},
        {"buffer": 0, "byteOffset": 128, "byteLength": 12},
    ]
    accessors = [
        {"bufferView": 0, "componentType": FLOAT, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
        {"bufferView": 1, "componentType": FLOAT, "count": 4, "type": "VEC3"},
        {"bufferView": 2, "componentType": FLOAT, "count": 4, "type": "VEC2"},
        {"bufferView": 3, "componentType": USHORT, "count": 6, "type": "SCALAR"},
    ]
    return data, views, accessors


def lights():
    return {"KHR_lights_punctual": {"lights": [
        {"type": "point", "color": [1, 0.9, 0.8], "intensity": 20, "range": 10},
        {"type": "spot", "intensity": 40, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}},
        {"type": "directional", "intensity": 2},
    ]}}


def textured_quad(image):
    data, views, accessors = quad_buffer()
    doc = {
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": lights(),
        "scene": 0,
        "scenes": [{"nodes": [0, 2, 3]}],
        "nodes": [
            {"mesh": 0, "children": [1], "translation": [0, 0, -2], "rotation": [0, 0.383, 0, 0.924]},
            {"mesh": 0, "matrix": [2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 1, 0, 0, 1]},
            {"camera": 0, "translation": [0.5, 0.5, 3]},
            {"children": [4, 5, 6], "scale": [1, 1, 1]},
            {"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0, 2, 1]},
            {"extensions": {"KHR_lights_punctual": {"light": 1}}, "translation": [1, 1, 2]},
            {"extensions": {"KHR_lights_punctual": {"light": 2}}, "rotation": [-0.383, 0, 0, 0.924]},
        ],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "zfar": 100, "aspectRatio": 1.5}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3,
                                    "material": 0, "mode": 4}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0.1,
                                                "roughnessFactor": 0.7, "baseColorTexture": {"index": 0}}}],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{"magFilter": 9729, "minFilter": 9729}],
        "images": [image],
        "bufferViews": views,
        "accessors": accessors,
    }
    return doc, data


def write(name, data):
    with open(os.path.join(OUT, name), "wb") as f:
        f.write(data)


def main():
    os.makedirs(OUT, exist_ok=True)
    png = png_2x2()

    # .gltf: buffer and image as data: URIs.
    doc, data = textured_quad({"uri": "data:image/png;base64," + base64.b64encode(png).decode()})
    doc["buffers"] = [{"byteLength": len(data),
                       "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}]
    write("textured-quad.gltf", json.dumps(doc, separators=(",", ":")).encode())

    # .glb: the same scene, the image in a buffer view of the BIN chunk.
    doc, data = textured_quad({"bufferView": 4, "mimeType": "image/png"})
    doc["bufferViews"].append({"buffer": 0, "byteOffset": len(data), "byteLength": len(png)})
    data += png
    data += b"\x00" * (-len(data) % 4)
    doc["buffers"] = [{"byteLength": len(data)}]
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    glb = struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(text) + 8 + len(data))
    glb += struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(data), 0x004E4942) + data
    write("textured-quad.glb", glb)

    # One non-indexed triangle, no material, no camera, no lights; an orthographic camera.
    triangle = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    doc = {
        "asset": {"version": "2.0"},
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"mesh": 0}, {"camera": 0}],
        "cameras": [{"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 10}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "accessors": [{"bufferView": 0, "componentType": FLOAT, "count": 3, "type": "VEC3"}],
        "bufferViews": [{"buffer": 0, "byteLength": len(triangle)}],
        "buffers": [{"byteLength": len(triangle),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(triangle).decode()}],
    }
    write("triangle.gltf", json.dumps(doc, separators=(",", ":")).encode())

    # uint32 indices, a strided view and a second primitive mode the loader skips (LINES).
    data = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<3I", 0, 1, 2)
    doc = {
        "asset": {"version": "2.0"},
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1},
                                   {"attributes": {"POSITION": 0}, "mode": 1}]}],
        "accessors": [{"bufferView": 0, "componentType": FLOAT, "count": 3, "type": "VEC3"},
                      {"bufferView": 1, "componentType": UINT, "count": 3, "type": "SCALAR"}],
        "bufferViews": [{"buffer": 0, "byteLength": 36, "byteStride": 12},
                        {"buffer": 0, "byteOffset": 36, "byteLength": 12}],
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
    }
    write("uint32-indices.gltf", json.dumps(doc, separators=(",", ":")).encode())


if __name__ == "__main__":
    main()
