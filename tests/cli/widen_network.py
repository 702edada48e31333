"""Writes a copy of a network with another size_multiple and, on its input, an unused 1x1 conv of C channels
(zero weights): a network whose feature maps can be made as large as wanted from a small file.

Usage: widen_network.py IN OUT SIZE_MULTIPLE CHANNELS
"""
import json
import struct
import sys

source, target, size_multiple, channels = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
with open(source, "rb") as f:
    length = struct.unpack("<Q", f.read(8))[0]
    header = json.loads(f.read(length))
    data = f.read()
metadata = header.pop("__metadata__")
graph = json.loads(metadata["sixway.graph"])
graph["size_multiple"] = size_multiple
inputs = graph["nodes"][0]["out_channels"]
graph["nodes"].insert(1, {"name": "wide", "op": "conv2d", "inputs": ["input"], "in_channels": inputs,
                          "out_channels": channels, "kernel": 1, "stride": 1, "scale": 1, "activation": "none"})
metadata["sixway.graph"] = json.dumps(graph)
for name, shape in (("wide.weight", [channels, inputs, 1, 1]), ("wide.bias", [channels])):
    count = 1
    for dim in shape:
        count *= dim
    header[name] = {"dtype": "F32", "shape": shape, "data_offsets": [len(data), len(data) + 4 * count]}
    data += bytes(4 * count)
header["__metadata__"] = metadata
text = json.dumps(header).encode("utf-8")
text += b" " * ((8 - len(text) % 8) % 8)
with open(target, "wb") as f:
    f.write(struct.pack("<Q", len(text)) + text + data)
