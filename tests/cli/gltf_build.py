"""Small glTF 2.0 files for the tests, with the standard library only: a Gltf collects
buffer views and accessors over one binary buffer, and writes .gltf (the buffer as a data:
URI or a .bin file beside it) or .glb."""
import base64
import json
import struct

FLOAT, UBYTE, USHORT, UINT = 5126, 5121, 5123, 5125
_TYPES = {1: "SCALAR", 2: "VEC2", 3: "VEC3", 4: "VEC4"}
_FMT = {FLOAT: "f", UBYTE: "B", USHORT: "H", UINT: "I"}


class Gltf:
    def __init__(self):
        self.bin = bytearray()
        self.doc = {"asset": {"version": "2.0"}, "buffers": [], "bufferViews": [],
                    "accessors": [], "meshes": [], "nodes": [], "scenes": [{"nodes": []}],
                    "scene": 0, "materials": []}

    def accessor(self, values, ncomp, ctype=FLOAT):
        """values: a flat list; returns the accessor's index."""
        while len(self.bin) % 4:
            self.bin.append(0)
        off = len(self.bin)
        self.bin += struct.pack("<%d%s" % (len(values), _FMT[ctype]), *values)
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": off,
                                        "byteLength": len(self.bin) - off})
        acc = {"bufferView": len(self.doc["bufferViews"]) - 1, "componentType": ctype,
               "count": len(values) // ncomp, "type": _TYPES[ncomp]}
        if ctype == FLOAT and ncomp == 3:
            acc["min"] = [min(values[i::3]) for i in range(3)]
            acc["max"] = [max(values[i::3]) for i in range(3)]
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def mesh(self, positions, indices=None, normals=None, uvs=None, material=None, mode=None,
             index_type=UINT):
        prim = {"attributes": {"POSITION": self.accessor(positions, 3)}}
        if normals is not None:
            prim["attributes"]["NORMAL"] = self.accessor(normals, 3)
        if uvs is not None:
            prim["attributes"]["TEXCOORD_0"] = self.accessor(uvs, 2)
        if indices is not None:
            prim["indices"] = self.accessor(indices, 1, index_type)
        if material is not None:
            prim["material"] = material
        if mode is not None:
            prim["mode"] = mode
        self.doc["meshes"].append({"primitives": [prim]})
        return len(self.doc["meshes"]) - 1

    def node(self, root=True, **fields):
        self.doc["nodes"].append(fields)
        i = len(self.doc["nodes"]) - 1
        if root:
            self.doc["scenes"][0]["nodes"].append(i)
        return i

    def material(self, **fields):
        self.doc["materials"].append(fields)
        return len(self.doc["materials"]) - 1

    def _doc(self, uri):
        d = json.loads(json.dumps(self.doc))
        d["buffers"] = [{"byteLength": len(self.bin)}]
        if uri is not None:
            d["buffers"][0]["uri"] = uri
        for k in [k for k, v in d.items() if v == []]:
            del d[k]
        return d

    def write_gltf(self, path, bin_name=None):
        """A .gltf; its buffer in bin_name beside it, else a data: URI."""
        if bin_name:
            import os
            with open(os.path.join(os.path.dirname(path), bin_name), "wb") as f:
                f.write(self.bin)
            uri = bin_name
        else:
            uri = "data:application/octet-stream;base64," + base64.b64encode(self.bin).decode()
        with open(path, "w") as f:
            json.dump(self._doc(uri), f)

    def glb_bytes(self):
        js = json.dumps(self._doc(None)).encode()
        js += b" " * (-len(js) % 4)
        bn = bytes(self.bin) + b"\0" * (-len(self.bin) % 4)
        body = struct.pack("<I4s", len(js), b"JSON") + js + struct.pack("<I4s", len(bn), b"BIN\0") + bn
        return struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body

    def write_glb(self, path):
        with open(path, "wb") as f:
            f.write(self.glb_bytes())


def cube():
    """A unit cube (|x|, |y|, |z| <= 0.5) as 12 triangles, 24 vertices with face normals."""
    pos, nrm, idx = [], [], []
    for axis in range(3):
        for sign in (1, -1):
            n = [0, 0, 0]
            n[axis] = sign
            u, v = [0, 0, 0], [0, 0, 0]
            u[(axis + 1) % 3] = 1
            v[(axis + 2) % 3] = 1
            base = len(pos) // 3
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                pos += [0.5 * (n[k] + a * u[k] + b * v[k]) for k in range(3)]
                nrm += n
            quad = [0, 1, 2, 0, 2, 3] if sign > 0 else [0, 2, 1, 0, 3, 2]
            idx += [base + q for q in quad]
    return pos, nrm, idx
