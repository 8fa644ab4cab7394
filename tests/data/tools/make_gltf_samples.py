#!/usr/bin/env python3
"""Writes the small glTF samples in tests/data (run by hand from tests/data/tools if they must
be remade). All geometry is one triangle, (0,0,0) (1,0,0) (0,1,0), indices 0 1 2."""
import base64, json, struct, os

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.dirname(HERE)

POSITIONS = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
INDICES = struct.pack("<3H", 0, 1, 2) + b"\0\0"  # padded to 4 bytes


def gltf(positions=POSITIONS, indices=INDICES, position_count=3, index_count=3, nodes=None):
    blob = positions + indices
    return {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes or [{}])))}],
        "nodes": nodes or [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(positions)},
                        {"buffer": 0, "byteOffset": len(positions), "byteLength": len(indices)}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": position_count, "type": "VEC3"},
                      {"bufferView": 1, "componentType": 5123, "count": index_count, "type": "SCALAR"}],
    }


def glb(doc, declared_length=None):
    """GLB with the buffer moved into the BIN chunk."""
    doc = json.loads(json.dumps(doc))
    blob = base64.b64decode(doc["buffers"][0].pop("uri").split(",", 1)[1])
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    blob += b"\0" * (-len(blob) % 4)
    body = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(blob), 0x004E4942) + blob
    length = 12 + len(body) if declared_length is None else declared_length
    return struct.pack("<4sII", b"glTF", 2, length) + body


def write(name, data):
    mode = "wb" if isinstance(data, bytes) else "w"
    with open(os.path.join(DATA, name), mode) as f:
        f.write(data)


# Good: the triangle twice, once moved by +10 in x and once mirrored in x (winding must flip).
write("triangle_instanced.gltf", json.dumps(gltf(nodes=[
    {"mesh": 0, "translation": [10, 0, 0]},
    {"mesh": 0, "scale": [-1, 1, 1]}]), indent=1) + "\n")
write("triangle.glb", glb(gltf()))

# Bad.
good_glb = glb(gltf())
write("bad/bad_magic.glb", b"glTX" + good_glb[4:])
write("bad/truncated_length.glb", glb(gltf(), declared_length=len(good_glb) + 1000))
write("bad/json_syntax.gltf", json.dumps(gltf(), indent=1)[:-40] + "\n")
write("bad/accessor_out_of_bounds.gltf", json.dumps(gltf(position_count=10), indent=1) + "\n")
write("bad/index_out_of_range.gltf",
      json.dumps(gltf(indices=struct.pack("<3H", 0, 1, 7) + b"\0\0"), indent=1) + "\n")
write("bad/nan_position.gltf",
      json.dumps(gltf(positions=struct.pack("<9f", 0, 0, 0, float("nan"), 0, 0, 0, 1, 0)), indent=1) + "\n")
