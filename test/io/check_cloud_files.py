#!/usr/bin/env python3
"""Reads rangefit's binary PLY and PCD output with nothing but Python's standard library (struct)
and checks every value against what the writer was given: an independent reader, as other tools
(PCL, Open3D, CloudCompare, numpy users) would parse the files.

    check_cloud_files.py WRITER   # WRITER: the write_fixture_clouds program

Exits 0 when every file holds the expected values, 1 (naming file and value) otherwise.
"""
import json
import math
import os
import struct
import subprocess
import sys
import tempfile

PLY_TYPES = {"char": "b", "uchar": "B", "short": "h", "ushort": "H", "int": "i", "uint": "I",
             "float": "f", "double": "d", "int8": "b", "uint8": "B", "int16": "h",
             "uint16": "H", "int32": "i", "uint32": "I", "float32": "f", "float64": "d"}
PCD_TYPES = {("F", 4): "f", ("F", 8): "d", ("I", 1): "b", ("I", 2): "h", ("I", 4): "i",
             ("I", 8): "q", ("U", 1): "B", ("U", 2): "H", ("U", 4): "I", ("U", 8): "Q"}

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)


def header_lines(data, last):
    """Header lines up to and including the one starting with `last`; returns (lines, offset)."""
    lines, pos = [], 0
    while True:
        end = data.index(b"\n", pos)
        line = data[pos:end].decode("ascii").rstrip("\r")
        lines.append(line)
        pos = end + 1
        if line.startswith(last):
            return lines, pos


def read_ply(path):
    data = open(path, "rb").read()
    lines, pos = header_lines(data, "end_header")
    assert lines[0] == "ply", path
    fmt = lines[1].split()[1]
    order = {"binary_little_endian": "<", "binary_big_endian": ">"}[fmt]
    names, codes, comments, count = [], [], [], 0
    for line in lines[2:]:
        words = line.split()
        if words[0] == "element":
            assert words[1] == "vertex", line
            count = int(words[2])
        elif words[0] == "property":
            codes.append(PLY_TYPES[words[1]])
            names.append(words[2])
        elif words[0] == "comment":
            comments.append(words[1:])
    record = struct.Struct(order + "".join(codes))
    check(len(data) - pos == count * record.size, f"{path}: {len(data) - pos} data bytes")
    rows = [dict(zip(names, record.unpack_from(data, pos + i * record.size)))
            for i in range(count)]
    return {"names": names, "codes": dict(zip(names, codes)), "comments": comments, "rows": rows}


def read_pcd(path):
    data = open(path, "rb").read()
    lines, pos = header_lines(data, "DATA")
    header = {}
    for line in lines:
        if line.startswith("#"):
            continue
        words = line.split()
        header[words[0]] = words[1:]
    assert header["DATA"] == ["binary"], path
    names = header["FIELDS"]
    codes = [PCD_TYPES[(t, int(s))] for t, s in zip(header["TYPE"], header["SIZE"])]
    assert all(c == "1" for c in header["COUNT"]), path
    width, height = int(header["WIDTH"][0]), int(header["HEIGHT"][0])
    check(int(header["POINTS"][0]) == width * height, f"{path}: POINTS != WIDTH * HEIGHT")
    record = struct.Struct("<" + "".join(codes))  # PCD binary data is little endian
    check(len(data) - pos == width * height * record.size, f"{path}: {len(data) - pos} bytes")
    rows = [dict(zip(names, record.unpack_from(data, pos + i * record.size)))
            for i in range(width * height)]
    comments = [line.split()[1:] for line in lines if line.startswith("# rangefit")]
    return {"names": names, "codes": dict(zip(names, codes)), "rows": rows, "width": width,
            "height": height, "comments": comments}


def stored(value, code):
    """The value a field of struct type `code` holds for `value` (float rounds to nearest)."""
    return struct.unpack("<" + code, struct.pack("<" + code, value))[0]


def stamp(row):
    bits = (row["rangefit_stamp_hi"] & 0xFFFFFFFF) << 32 | row["rangefit_stamp_lo"]
    return bits - (1 << 64) if bits >= 1 << 63 else bits


def check_point(path, what, row, expected, real, i):
    for axis, name in zip(range(3), ("x", "y", "z")):
        got, want = row[name], stored(expected["points"][i][axis], real)
        check(got == want, f"{path}: {what} {name} = {got!r}, expected {want!r}")
    if expected["normals"]:
        for axis, name in zip(range(3), ("nx", "ny", "nz")):
            field = name if name in row else "normal_" + name[1]
            got, want = row[field], stored(expected["normals"][i][axis], real)
            check(got == want, f"{path}: {what} {field} = {got!r}, expected {want!r}")
    if expected["stamps_ns"]:
        check(stamp(row) == expected["stamps_ns"][i], f"{path}: {what} stamp {stamp(row)}")


def check_ply(path, expected, real):
    ply = read_ply(path)
    wanted = ["x", "y", "z"] + (["nx", "ny", "nz"] if expected["normals"] else [])
    check(ply["names"][:len(wanted)] == wanted, f"{path}: properties {ply['names']}")
    for name in wanted:
        check(ply["codes"][name] == real, f"{path}: {name} is {ply['codes'][name]}, not {real}")
    check(["rangefit", "frame_id", expected["frame_id"]] in ply["comments"], f"{path}: frame")
    check(len(ply["rows"]) == len(expected["points"]), f"{path}: {len(ply['rows'])} vertices")
    cells = {p: c for c, p in enumerate(expected["index"]) if p >= 0}
    if expected["rows"]:
        grid = ["rangefit", "grid", str(expected["rows"]), str(expected["cols"])]
        check(grid in ply["comments"], f"{path}: no grid comment")
    for i, row in enumerate(ply["rows"]):
        check_point(path, f"vertex {i}", row, expected, real, i)
        if expected["rows"]:
            check(row["rangefit_cell"] == cells[i], f"{path}: vertex {i} cell")


def check_pcd(path, expected, real):
    pcd = read_pcd(path)
    wanted = ["x", "y", "z"] + (["normal_x", "normal_y", "normal_z"] if expected["normals"] else [])
    check(pcd["names"][:len(wanted)] == wanted, f"{path}: fields {pcd['names']}")
    for name in wanted:
        check(pcd["codes"][name] == real, f"{path}: {name} is {pcd['codes'][name]}, not {real}")
    check(["rangefit", "frame_id", expected["frame_id"]] in pcd["comments"], f"{path}: frame")
    if expected["rows"]:
        # Organised: WIDTH x HEIGHT = cols x rows, row-major cells, NaN where a cell is empty.
        check((pcd["width"], pcd["height"]) == (expected["cols"], expected["rows"]),
              f"{path}: {pcd['width']} x {pcd['height']}")
        order = expected["index"]
    else:
        check(pcd["height"] == 1, f"{path}: HEIGHT {pcd['height']} for an unorganised cloud")
        order = list(range(len(expected["points"])))
    check(len(pcd["rows"]) == len(order), f"{path}: {len(pcd['rows'])} points")
    for cell, (row, i) in enumerate(zip(pcd["rows"], order)):
        if i < 0:
            check(all(math.isnan(row[n]) for n in ("x", "y", "z")), f"{path}: cell {cell} not NaN")
        else:
            check_point(path, f"cell {cell}", row, expected, real, i)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    with tempfile.TemporaryDirectory(prefix="rangefit_cloud_files_") as tmp:
        subprocess.run([sys.argv[1], tmp], check=True)
        for name in ("plain", "organised"):
            expected = json.load(open(os.path.join(tmp, name + ".json")))
            base = os.path.join(tmp, name)
            check_ply(base + ".ply", expected, "f")        # the default: float
            check_ply(base + "_be.ply", expected, "f")
            check_ply(base + "_double.ply", expected, "d")  # on request: double, exact
            check_pcd(base + ".pcd", expected, "f")
            check_pcd(base + "_double.pcd", expected, "d")
    for message in failures:
        print("FAIL:", message)
    print(f"{len(failures)} problems in rangefit's PLY and PCD files")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
