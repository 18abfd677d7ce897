#!/usr/bin/python3
"""Writes the seed corpora of the fuzz targets (tests/fuzz/corpus/<target>/), small valid and
invalid inputs that reach every branch worth mutating. Deterministic; run it again after
changing it and commit the files:  /usr/bin/python3 tests/fuzz/make_corpus.py

gltf/           .gltf and .glb files for fuzz_gltf (a few hundred bytes each)
metrics_input/  inputs of fuzz_metrics_input: option byte, u32 size of image A, A, B
"""
import base64
import io
import json
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
FLOAT, UBYTE, USHORT, UINT = 5126, 5121, 5123, 5125


class Gltf:
    """A glTF document with one binary buffer, built element by element."""

    def __init__(self):
        self.doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": []}]}
        self.bin = bytearray()

    def view(self, data, stride=0):
        while len(self.bin) % 4:
            self.bin.append(0)
        view = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if stride:
            view["byteStride"] = stride
        self.bin += data
        self.doc.setdefault("bufferViews", []).append(view)
        return len(self.doc["bufferViews"]) - 1

    def accessor(self, view, component, count, kind, **extra):
        accessor = {"componentType": component, "count": count, "type": kind}
        if view is not None:
            accessor["bufferView"] = view
        accessor.update(extra)
        self.doc.setdefault("accessors", []).append(accessor)
        return len(self.doc["accessors"]) - 1

    def floats(self, values, kind, components):
        data = struct.pack("<%df" % len(values), *values)
        extra = {}
        if kind == "VEC3":
            xs, ys, zs = values[0::3], values[1::3], values[2::3]
            extra = {"min": [min(xs), min(ys), min(zs)], "max": [max(xs), max(ys), max(zs)]}
        return self.accessor(self.view(data), FLOAT, len(values) // components, kind, **extra)

    def indices(self, values, component=UINT):
        fmt = {UBYTE: "B", USHORT: "H", UINT: "I"}[component]
        return self.accessor(self.view(struct.pack("<%d%s" % (len(values), fmt), *values)), component, len(values),
                             "SCALAR")

    def mesh(self, primitive, name=None):
        mesh = {"primitives": [primitive]}
        if name:
            mesh["name"] = name
        self.doc.setdefault("meshes", []).append(mesh)
        return len(self.doc["meshes"]) - 1

    def quad(self, size=1.0, material=None, component=UINT):
        position = self.floats([0, 0, 0, size, 0, 0, size, size, 0, 0, size, 0], "VEC3", 3)
        primitive = {"attributes": {"POSITION": position}, "indices": self.indices([0, 1, 2, 0, 2, 3], component)}
        if material is not None:
            primitive["material"] = material
        return self.mesh(primitive)

    def node(self, node, root=True):
        self.doc.setdefault("nodes", []).append(node)
        index = len(self.doc["nodes"]) - 1
        if root:
            self.doc["scenes"][0]["nodes"].append(index)
        return index

    def padded_bin(self):
        data = bytes(self.bin)
        return data + b"\0" * (-len(data) % 4)

    def gltf(self):
        doc = json.loads(json.dumps(self.doc))
        if self.bin:
            data = self.padded_bin()
            doc["buffers"] = [{"byteLength": len(data),
                               "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}]
        return json.dumps(doc, separators=(",", ":")).encode()

    def glb(self):
        doc = json.loads(json.dumps(self.doc))
        data = self.padded_bin()
        if data:
            doc["buffers"] = [{"byteLength": len(data)}]
        text = json.dumps(doc, separators=(",", ":")).encode()
        text += b" " * (-len(text) % 4)
        body = struct.pack("<II", len(text), 0x4E4F534A) + text
        if data:
            body += struct.pack("<II", len(data), 0x004E4942) + data
        return struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body


def png(width, height, channels, bit_depth=8, seed=1):
    """A small PNG written by hand (no imaging library), deterministic pixels."""
    color_type = {1: 0, 2: 4, 3: 2, 4: 6}[channels]
    sample_bytes = bit_depth // 8
    rows = bytearray()
    for y in range(height):
        rows.append(0)
        for x in range(width):
            for c in range(channels):
                value = (x * 37 + y * 91 + c * 53 + seed * 17) & 0xFF
                if c == 3:
                    value = 255 if (x + y) % 3 else 128
                rows += bytes([value] * sample_bytes)

    def chunk(kind, payload):
        return struct.pack(">I", len(payload)) + kind + payload + struct.pack(">I", zlib.crc32(kind + payload))

    header = struct.pack(">IIBBBBB", width, height, bit_depth, color_type, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(bytes(rows), 9)) +
            chunk(b"IEND", b""))


def jpeg(width, height, seed):
    from PIL import Image  # Debian's python3-pil, only for the JPEG and TGA seeds
    image = Image.new("RGB", (width, height))
    image.putdata([((x * 29 + seed * 7) & 255, (y * 41) & 255, ((x + y) * 13) & 255)
                   for y in range(height) for x in range(width)])
    out = io.BytesIO()
    image.save(out, format="JPEG", quality=80)
    return out.getvalue()


def tga(width, height, seed):
    from PIL import Image
    image = Image.new("RGBA", (width, height))
    image.putdata([((x * 29 + seed) & 255, (y * 41) & 255, 90, 255) for y in range(height) for x in range(width)])
    out = io.BytesIO()
    image.save(out, format="TGA")
    return out.getvalue()


def ppm(width, height, seed):
    pixels = bytes(((x * 23 + y * 7 + c * 31 + seed) & 255) for y in range(height) for x in range(width) for c in range(3))
    return b"P6\n%d %d\n255\n" % (width, height) + pixels


# Compressed streams for the extension seeds, made once with the decoders' own libraries
# (meshoptimizer 0.18 encoders, libwebp's lossless encoder, glTF-Transform 3.10.1's Draco):
# a unit quad's positions, its +Z normals through the OCTAHEDRAL filter (8 bit), its two
# triangles; a 2x2 RGBA image; the quad as a Draco mesh (POSITION is attribute 0).
MESHOPT_POSITIONS = bytes.fromhex(
    "a000000133000000ffff01330000007e7d0000010c000000ff010c0000007e00000000000000000000000000000000000000000000"
    "0000000000000000000000000000")
MESHOPT_OCT_NORMALS = bytes.fromhex("a0000000000000000000000000000000000000000000000000000000000000000000007f00")
MESHOPT_TRIANGLES = bytes.fromhex("e0f000007687566778a9866589689801690000")
WEBP_2X2 = bytes.fromhex("5249464630000000574542505650384c230000002f014000101f201048de1f3a8df9171014fc1f9d80a0e8bae522660fc20d"
                         "1822fa1f0200")
DRACO_QUAD = bytes.fromhex("445241434f02020101000000040200020000011fff011101ff0000010009030000020101010003030130011003002882"
                           "980000000000ff3f00000000000000000000000000000000803f0e")


def meshopt_quad():
    """The quad with meshopt-compressed views in buffer 1, a fallback buffer without data."""
    g = Gltf()
    fallback = 0
    for data, count, stride, mode, extra in [(MESHOPT_POSITIONS, 4, 12, "ATTRIBUTES", {}),
                                             (MESHOPT_OCT_NORMALS, 4, 4, "ATTRIBUTES", {"filter": "OCTAHEDRAL"}),
                                             (MESHOPT_TRIANGLES, 6, 2, "TRIANGLES", {})]:
        view = g.view(data)
        meshopt = {"buffer": 0, "byteOffset": g.doc["bufferViews"][view]["byteOffset"], "byteLength": len(data),
                   "byteStride": stride, "count": count, "mode": mode}
        meshopt.update(extra)
        g.doc["bufferViews"][view] = {"buffer": 1, "byteOffset": fallback, "byteLength": count * stride,
                                      "extensions": {"EXT_meshopt_compression": meshopt}}
        if mode == "ATTRIBUTES":
            g.doc["bufferViews"][view]["byteStride"] = stride
        fallback += (count * stride + 3) // 4 * 4
    position = g.accessor(0, FLOAT, 4, "VEC3", min=[0, 0, 0], max=[1, 1, 0])
    normal = g.accessor(1, 5120, 4, "VEC3", normalized=True)
    indices = g.accessor(2, USHORT, 6, "SCALAR")
    g.node({"name": "quad", "mesh": g.mesh({"attributes": {"POSITION": position, "NORMAL": normal},
                                            "indices": indices})})
    g.doc["extensionsUsed"] = g.doc["extensionsRequired"] = ["EXT_meshopt_compression"]
    data = g.padded_bin()
    doc = json.loads(json.dumps(g.doc))
    doc["buffers"] = [{"byteLength": len(data)},
                      {"byteLength": fallback, "extensions": {"EXT_meshopt_compression": {"fallback": True}}}]
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    body = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(data), 0x004E4942) + data
    return struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body


def gltf_corpus():
    files = {}
    # 1. One indexed quad, as .gltf (data URI) and .glb.
    g = Gltf()
    g.node({"name": "quad", "mesh": g.quad()})
    files["quad.gltf"] = g.gltf()
    files["quad.glb"] = g.glb()

    # 2. MSFT_lod chain with screen coverage, a camera looking at it.
    g = Gltf()
    g.doc["extensionsUsed"] = ["MSFT_lod"]
    fine, coarse = g.quad(1.0), g.quad(1.0, component=USHORT)
    lod = g.node({"name": "coarse", "mesh": coarse}, root=False)
    g.node({"name": "object", "mesh": fine, "translation": [0, 0, -3],
            "extensions": {"MSFT_lod": {"ids": [lod]}}, "extras": {"MSFT_screencoverage": [0.5, 0.1]}})
    g.doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "zfar": 100}}]
    g.node({"name": "eye", "camera": 0, "translation": [0, 0, 2]})
    files["msft_lod_camera.glb"] = g.glb()

    # 3. Strip and fan primitives, non-indexed, with normals and texcoords.
    g = Gltf()
    position = g.floats([0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 2, 0], "VEC3", 3)
    normal = g.floats([0, 0, 1] * 5, "VEC3", 3)
    uv = g.floats([0, 0, 1, 0, 0, 1, 1, 1, 0, 1], "VEC2", 2)
    strip = g.mesh({"attributes": {"POSITION": position, "NORMAL": normal, "TEXCOORD_0": uv}, "mode": 5})
    fan = g.mesh({"attributes": {"POSITION": position}, "mode": 6})
    g.node({"name": "strip", "mesh": strip})
    g.node({"name": "fan", "mesh": fan, "scale": [-1, 1, 1]})
    files["strip_fan.gltf"] = g.gltf()

    # 4. Sparse accessor on a bufferView-less POSITION, and sparse indices.
    g = Gltf()
    sparse_indices = g.view(struct.pack("<3H", 1, 2, 3))
    sparse_values = g.view(struct.pack("<9f", 1, 0, 0, 1, 1, 0, 0, 1, 0))
    position = g.accessor(None, FLOAT, 4, "VEC3", sparse={
        "count": 3, "indices": {"bufferView": sparse_indices, "componentType": USHORT},
        "values": {"bufferView": sparse_values}})
    index_values = g.view(struct.pack("<B", 3))
    index_positions = g.view(struct.pack("<B", 5))
    indices = g.accessor(g.view(struct.pack("<6B", 0, 1, 2, 0, 2, 0)), UBYTE, 6, "SCALAR", sparse={
        "count": 1, "indices": {"bufferView": index_positions, "componentType": UBYTE},
        "values": {"bufferView": index_values}})
    g.node({"name": "sparse", "mesh": g.mesh({"attributes": {"POSITION": position}, "indices": indices})})
    files["sparse.gltf"] = g.gltf()

    # 5. KHR_mesh_quantization: normalized short positions, byte normals, strided view.
    g = Gltf()
    g.doc["extensionsUsed"] = g.doc["extensionsRequired"] = ["KHR_mesh_quantization"]
    interleaved = g.view(struct.pack("<3h2x3b1x", 0, 0, 0, 0, 0, 127) + struct.pack("<3h2x3b1x", 32767, 0, 0, 0, 0, 127) +
                         struct.pack("<3h2x3b1x", 0, 32767, 0, 0, 0, 127), stride=12)
    position = g.accessor(interleaved, 5122, 3, "VEC3", normalized=True)
    normal = g.accessor(interleaved, 5120, 3, "VEC3", normalized=True, byteOffset=8)
    g.node({"name": "quantized", "mesh": g.mesh({"attributes": {"POSITION": position, "NORMAL": normal}}),
            "rotation": [0, 0.7071068, 0, 0.7071068]})
    files["quantized.glb"] = g.glb()

    # 6. A base-color texture (PNG in a bufferView) and a material MSFT_lod.
    g = Gltf()
    image = g.view(png(4, 4, 4))
    g.doc["images"] = [{"bufferView": image, "mimeType": "image/png"}]
    g.doc["textures"] = [{"source": 0}]
    g.doc["materials"] = [
        {"name": "fine", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "baseColorFactor": [1, 0.5, 0.5, 1]},
         "extensions": {"MSFT_lod": {"ids": [1]}}},
        {"name": "coarse", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.4, 0.4, 1]}}]
    g.doc["extensionsUsed"] = ["MSFT_lod"]
    position = g.floats([0, 0, 0, 1, 0, 0, 1, 1, 0], "VEC3", 3)
    uv = g.floats([0, 0, 1, 0, 1, 1], "VEC2", 2)
    g.node({"name": "textured", "mesh": g.mesh({"attributes": {"POSITION": position, "TEXCOORD_0": uv}, "material": 0})})
    files["texture_material_lod.glb"] = g.glb()

    # 7. Sibling <name>_LOD<k> nodes under a transform-only parent, with a child joining level 0.
    g = Gltf()
    mesh = g.quad()
    child = g.node({"name": "detail", "mesh": mesh, "translation": [0, 1, 0]}, root=False)
    lod0 = g.node({"name": "tree_LOD0", "mesh": mesh, "children": [child]}, root=False)
    lod1 = g.node({"name": "tree_LOD1", "mesh": mesh}, root=False)
    g.node({"name": "group", "children": [lod0, lod1], "matrix": [2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 1, 2, 3, 1]})
    files["name_lods.gltf"] = g.gltf()

    # 8. A dense grid (LOD generation has work to do).
    g = Gltf()
    n = 12
    positions, idx = [], []
    for y in range(n):
        for x in range(n):
            positions += [x / (n - 1), y / (n - 1), ((x * 7 + y * 3) % 5) * 0.01]
    for y in range(n - 1):
        for x in range(n - 1):
            a = y * n + x
            idx += [a, a + 1, a + n + 1, a, a + n + 1, a + n]
    g.node({"name": "grid", "mesh": g.mesh({"attributes": {"POSITION": g.floats(positions, "VEC3", 3)},
                                           "indices": g.indices(idx, USHORT)})})
    files["grid.glb"] = g.glb()

    # 9. Extensions: meshopt with a fallback buffer, Draco, a WebP base color.
    files["meshopt.glb"] = meshopt_quad()
    g = Gltf()
    view = g.view(DRACO_QUAD)
    position = g.accessor(None, FLOAT, 4, "VEC3", min=[0, 0, 0], max=[1, 1, 0])
    indices = g.accessor(None, UINT, 6, "SCALAR")
    g.node({"name": "quad", "mesh": g.mesh({"attributes": {"POSITION": position}, "indices": indices, "extensions": {
        "KHR_draco_mesh_compression": {"bufferView": view, "attributes": {"POSITION": 0}}}})})
    g.doc["extensionsUsed"] = g.doc["extensionsRequired"] = ["KHR_draco_mesh_compression"]
    files["draco.glb"] = g.glb()
    g = Gltf()
    g.doc["images"] = [{"bufferView": g.view(WEBP_2X2), "mimeType": "image/webp"}]
    g.doc["textures"] = [{"extensions": {"EXT_texture_webp": {"source": 0}}}]
    g.doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
    g.doc["extensionsUsed"] = g.doc["extensionsRequired"] = ["EXT_texture_webp"]
    position = g.floats([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0], "VEC3", 3)
    uv = g.floats([0, 1, 1, 1, 1, 0, 0, 0], "VEC2", 2)
    g.node({"name": "quad", "mesh": g.mesh({"attributes": {"POSITION": position, "TEXCOORD_0": uv},
                                            "indices": g.indices([0, 1, 2, 0, 2, 3]), "material": 0})})
    files["webp.glb"] = g.glb()

    # Invalid seeds: the fuzzer starts next to each refusal.
    g = Gltf()
    g.node({"name": "quad", "mesh": g.quad()})
    whole = g.glb()
    files["truncated.glb"] = whole[:len(whole) - 8]
    g = Gltf()
    a = g.node({"name": "a", "children": [1]}, root=True)
    g.node({"name": "b", "children": [a]}, root=False)
    files["node_loop.gltf"] = g.gltf()
    g = Gltf()
    position = g.floats([0, 0, 0, 1, 0, 0, 1, 1, 0], "VEC3", 3)
    g.node({"mesh": g.mesh({"attributes": {"POSITION": position}, "indices": g.indices([0, 1, 7])})})
    files["index_past_vertices.gltf"] = g.gltf()
    g = Gltf()
    g.node({"name": "empty"})
    files["no_objects.gltf"] = g.gltf()
    return files


def metrics_corpus():
    def entry(flags, a, b=b""):
        return bytes([flags]) + struct.pack("<I", len(a)) + a + b

    return {
        "rgb_pair.bin": entry(0x00, png(8, 6, 3, seed=1), png(8, 6, 3, seed=2)),
        "rgba_vs_rgb.bin": entry(0x01, png(7, 5, 4, seed=3), png(7, 5, 3, seed=4)),
        "gray_paper_modes.bin": entry(0x06, png(9, 9, 1, seed=5), png(9, 9, 1, seed=6)),
        "gray_alpha_16bit.bin": entry(0x08, png(5, 4, 2, bit_depth=16, seed=7), png(5, 4, 2, bit_depth=16, seed=8)),
        "one_pixel_self.bin": entry(0x00, png(1, 1, 3)),
        "size_mismatch.bin": entry(0x00, png(4, 4, 3), png(4, 5, 3)),
        "gray_vs_rgb.bin": entry(0x00, png(4, 4, 1), png(4, 4, 3)),
        "jpeg_pair.bin": entry(0x10, jpeg(16, 8, 1), jpeg(16, 8, 2)),
        "tga_self.bin": entry(0x20, tga(6, 6, 3)),
        "ppm_pair.bin": entry(0x31, ppm(5, 7, 1), ppm(5, 7, 2)),
        "not_an_image.bin": entry(0x00, b"this is not an image", b"nor is this"),
    }


def write(target, files):
    folder = os.path.join(HERE, "corpus", target)
    os.makedirs(folder, exist_ok=True)
    for name, data in sorted(files.items()):
        with open(os.path.join(folder, name), "wb") as out:
            out.write(data)
    total = sum(len(d) for d in files.values())
    print(f"{folder}: {len(files)} files, {total} bytes")


if __name__ == "__main__":
    write("gltf", gltf_corpus())
    write("metrics_input", metrics_corpus())
