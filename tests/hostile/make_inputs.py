"""Writes the hostile-input suite's files into a folder: bad, lying or extreme meshes, results and
gate configurations. Every file is made here from a few lines, so the suite needs nothing else."""
import json
import os
import struct

CUBE_V = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
CUBE_F = "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n"
CUBE = CUBE_V + CUBE_F
TRI_V = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"

OFF_CUBE_V = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
OFF_CUBE_F = "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n"


def big_face(n):
    import math
    vs = "".join(f"v {math.cos(6.283185307 * k / n):.7f} {math.sin(6.283185307 * k / n):.7f} 0\n" for k in range(n))
    return vs + "f " + " ".join(str(k + 1) for k in range(n)) + "\nf " + " ".join(str(n - k) for k in range(n)) + "\n"


def ply_ascii(nv, nf, body_v, body_f, extra=""):
    return (f"ply\nformat ascii 1.0\nelement vertex {nv}\nproperty float x\nproperty float y\nproperty float z\n"
            f"element face {nf}\nproperty list uchar int vertex_indices\n{extra}end_header\n" + body_v + body_f)


PLY_V = OFF_CUBE_V
PLY_F = OFF_CUBE_F


def ply_binary(nv, nf, vertices, faces):
    head = (f"ply\nformat binary_little_endian 1.0\nelement vertex {nv}\nproperty float x\nproperty float y\n"
            f"property float z\nelement face {nf}\nproperty list uchar int vertex_indices\nend_header\n").encode()
    body = b"".join(struct.pack("<3f", *v) for v in vertices)
    body += b"".join(struct.pack("<B", len(f)) + struct.pack(f"<{len(f)}i", *f) for f in faces)
    return head + body


CUBE_PTS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
CUBE_QUADS = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]


def results(rows, rounds=0):
    machine = {"cpu_model": "x", "cores": 2, "write_bandwidth_gbs": 10.0, "write_bandwidth_mt_gbs": 12.0}
    return json.dumps({"schema": 1, "machine": machine, "rounds": rounds, "runs": rows})


def files():
    f = {}
    # OBJ
    f["cube.obj"] = CUBE
    f["empty.obj"] = ""
    f["comments.obj"] = "# nothing here\n\n# still nothing\n"
    f["no_faces.obj"] = CUBE_V
    f["face_first.obj"] = "f 1 2 3\n" + TRI_V
    f["index0.obj"] = TRI_V + "f 0 1 2\n"
    f["index_high.obj"] = TRI_V + "f 1 2 4\n"
    f["index_rel.obj"] = TRI_V + "f -1 -2 -4\n"
    f["index_min.obj"] = TRI_V + "f 1 2 -9223372036854775808\n"
    f["index_over.obj"] = TRI_V + "f 1 2 9223372036854775808\n"
    f["index_wrap.obj"] = TRI_V + "f 1 2 4294967297\n"
    f["index_big.obj"] = TRI_V + "f 1 2 2147483649\n"
    f["index_intmax.obj"] = TRI_V + "f 1 2 2147483648\n"  # tests/fuzz: quoting it overflowed an int
    f["v2.obj"] = "v 0 0\n" + TRI_V + "f 1 2 3\n"
    f["vnan.obj"] = TRI_V + "v nan 0 0\nf 1 2 4\n"
    f["vinf.obj"] = TRI_V + "v 0 -inf 0\nf 1 2 4\n"
    f["vhuge.obj"] = TRI_V + "v 1e39 0 0\nf 1 2 4\n"
    f["vbad.obj"] = TRI_V + "v 1.x 0 0\nf 1 2 4\n"
    f["vhex.obj"] = TRI_V + "v 0x10 0 0\nf 1 2 4\n"
    f["f2.obj"] = TRI_V + "f 1 2\n"
    f["fslash.obj"] = TRI_V + "f 1/x 2 3\n"
    f["fslash_ok.obj"] = TRI_V + "vt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 3/1/1\n"
    f["nul.obj"] = TRI_V + "f 1 2\x003\n"
    f["bom.obj"] = "\ufeff" + CUBE
    f["crlf.obj"] = CUBE.replace("\n", "\r\n")
    f["longnum.obj"] = TRI_V + "v " + "1" * 2_000_000 + " 0 0\nf 1 2 4\n"
    f["longtok.obj"] = TRI_V + "v x" + "y" * 2_000_000 + " 0 0\nf 1 2 4\n"
    f["tag_over.obj"] = CUBE + "t crease 9223372036854775807/1/0 1 2 3\n"
    f["tag_over2.obj"] = CUBE + "t crease 2/9223372036854775807/9223372036854775807 0 1 2.0\n"
    f["tag_neg.obj"] = CUBE + "t crease -2/1/0 0 1 2.0\n"
    f["tag_counts.obj"] = CUBE + "t crease 2/1 0 1 2.0\n"
    f["tag_short.obj"] = CUBE + "t crease 4/1/0 0 1 2.0\n"
    f["tag_noname.obj"] = CUBE + "t\n"
    f["crease_wrap.obj"] = CUBE + "t crease 2/1/0 4294967296 1 2.0\n"
    f["crease_neg.obj"] = CUBE + "t crease 2/1/0 -1 1 2.0\n"
    f["crease_notedge.obj"] = CUBE + "t crease 2/1/0 0 6 2.0\n"
    f["crease_odd.obj"] = CUBE + "t crease 3/1/0 0 1 2 2.0\n"
    f["crease_nosharp.obj"] = CUBE + "t crease 2/0/0 0 1\n"
    f["crease_nan.obj"] = CUBE + "t crease 2/1/0 0 1 nan\n"
    f["crease_ok.obj"] = CUBE + "t crease 2/1/0 0 1 2.5\n"
    f["corner_range.obj"] = CUBE + "t corner 1/1/0 8 2.0\n"
    f["corner_wrap.obj"] = CUBE + "t corner 1/1/0 4294967296 2.0\n"
    f["hole_range.obj"] = CUBE + "t hole 1/0/0 6\n"
    f["hole_wrap.obj"] = CUBE + "t hole 1/0/0 4294967296\n"
    f["hole_all.obj"] = CUBE + "t hole 6/0/0 0 1 2 3 4 5\n"
    f["boundary_bad.obj"] = CUBE + "t interpolateboundary 1/0/0 7\n"
    f["creasemethod_bad.obj"] = CUBE + "t creasemethod 0/0/1 sharp\n"
    f["smoothtri_bad.obj"] = CUBE + "t smoothtriangles 0/0/1 wobbly\n"
    f["tag_unknown.obj"] = CUBE + "t vertexedit 0/0/0\n"
    f["nonmanifold.obj"] = TRI_V + "v 0 0 1\nv 0 0 -1\nf 1 2 3\nf 1 2 4\nf 1 2 5\n"
    f["degenerate.obj"] = TRI_V + "v 1 1 0\nf 1 1 2\nf 1 2 3\nf 2 4 3\n"
    f["coincident.obj"] = CUBE_V + "v 0 0 0\nv 0 0 0\nv 0 0 0\nv 0 0 0\nv 0 0 0\nv 0 0 0\nv 0 0 0\nv 0 0 0\n" + \
        "f 9 12 11 10\nf 13 14 15 16\nf 9 10 14 13\nf 10 11 15 14\nf 11 12 16 15\nf 12 9 13 16\n"
    f["inconsistent.obj"] = CUBE_V + CUBE_F.replace("f 5 6 7 8", "f 8 7 6 5")
    f["face10000.obj"] = big_face(10000)
    f["face1000.obj"] = big_face(1000)
    f["face65.obj"] = big_face(65)
    f["face3000.obj"] = big_face(3000)
    f["unused.obj"] = CUBE + "v 5 5 5\n"
    f["dup_face.obj"] = CUBE + "f 1 4 3 2\n"
    f["mixed.obj"] = CUBE_V + "v 0.5 0.5 -0.5\n" + CUBE_F.replace("f 1 4 3 2\n", "f 1 4 9\nf 4 3 9\nf 3 2 9\nf 2 1 9\n")
    # OFF
    f["cube.off"] = "OFF\n8 6 12\n" + OFF_CUBE_V + OFF_CUBE_F
    f["comment.off"] = "OFF # a cube\n# counts\n8 6 0\n" + OFF_CUBE_V + OFF_CUBE_F
    f["empty.off"] = ""
    f["noheader.off"] = "8 6 0\n" + OFF_CUBE_V + OFF_CUBE_F
    f["badcount.off"] = "OFF\n8 x 0\n" + OFF_CUBE_V + OFF_CUBE_F
    f["negcount.off"] = "OFF\n8 -6 0\n" + OFF_CUBE_V + OFF_CUBE_F
    f["nocount.off"] = "OFF\n"
    f["hugecount.off"] = "OFF\n8 1000000000000 0\n" + OFF_CUBE_V + OFF_CUBE_F
    f["hugecount2.off"] = "OFF\n99999999999999999999 6 0\n" + OFF_CUBE_V + OFF_CUBE_F
    f["fewer.off"] = "OFF\n8 5 0\n" + OFF_CUBE_V + OFF_CUBE_F
    f["more.off"] = "OFF\n8 7 0\n" + OFF_CUBE_V + OFF_CUBE_F
    f["fewer_v.off"] = "OFF\n7 6 0\n" + OFF_CUBE_V + OFF_CUBE_F
    f["facecount.off"] = "OFF\n8 6 0\n" + OFF_CUBE_V + OFF_CUBE_F.replace("4 3 0 4 7", "9 3 0 4 7")
    f["facecount2.off"] = "OFF\n8 6 0\n" + OFF_CUBE_V + OFF_CUBE_F.replace("4 3 0 4 7", "2 3 0")
    f["faceneg.off"] = "OFF\n8 6 0\n" + OFF_CUBE_V + OFF_CUBE_F.replace("4 3 0 4 7", "-4 3 0 4 7")
    f["faceidx.off"] = "OFF\n8 6 0\n" + OFF_CUBE_V + OFF_CUBE_F.replace("4 3 0 4 7", "4 3 0 4 8")
    f["faceidxneg.off"] = "OFF\n8 6 0\n" + OFF_CUBE_V + OFF_CUBE_F.replace("4 3 0 4 7", "4 3 0 4 -1")
    f["faceidxfloat.off"] = "OFF\n8 6 0\n" + OFF_CUBE_V + OFF_CUBE_F.replace("4 3 0 4 7", "4 3 0 4 7.5")
    f["faceidxwrap.off"] = "OFF\n8 6 0\n" + OFF_CUBE_V + OFF_CUBE_F.replace("4 3 0 4 7", "4 3 0 4 4294967296")
    f["facecolour.off"] = "OFF\n8 6 0\n" + OFF_CUBE_V + OFF_CUBE_F.replace("4 3 0 4 7", "4 3 0 4 7 255 0 0")
    f["vnan.off"] = "OFF\n8 6 0\n" + OFF_CUBE_V.replace("1 1 1", "nan 1 1") + OFF_CUBE_F
    f["vshort.off"] = "OFF\n8 6 0\n" + OFF_CUBE_V.replace("1 1 1", "1 1") + OFF_CUBE_F
    f["vbad.off"] = "OFF\n8 6 0\n" + OFF_CUBE_V.replace("1 1 1", "1 1.x 1") + OFF_CUBE_F
    f["nofaces.off"] = "OFF\n8 0 0\n" + OFF_CUBE_V
    f["bom.off"] = "\ufeffOFF\n8 6 0\n" + OFF_CUBE_V + OFF_CUBE_F
    f["crlf.off"] = ("OFF\n8 6 0\n" + OFF_CUBE_V + OFF_CUBE_F).replace("\n", "\r\n")
    f["counts_inline.off"] = "OFF 8 6 0\n" + OFF_CUBE_V + OFF_CUBE_F
    f["binary_lying.off"] = b"OFF BINARY\n" + struct.pack(">3i", 2000000000, 2000000000, 0) + b"\0" * 16
    cube_bin = (b"OFF BINARY\n" + struct.pack("<3i", 8, 6, 0) + b"".join(struct.pack("<3f", *v) for v in CUBE_PTS) +
                b"".join(struct.pack("<5i", 4, *q) for q in CUBE_QUADS))
    f["cube_bin.off"] = cube_bin
    f["bin_truncated.off"] = cube_bin[:-6]
    f["bin_noff.off"] = b"N" + cube_bin
    f["bin_keyword.off"] = b"OFF\t777777777777777733BINARY\t\x13"  # tests/fuzz's first finding
    f["counts_overflow.off"] = "OFF 8888000000000000000 2122324063000000000\n0 0 0\n"  # tests/fuzz
    f["version.ply"] = ply_ascii(8, 6, PLY_V, PLY_F).replace("ascii 1.0", "ascii o")  # tests/fuzz: OpenMesh hung
    # PLY
    f["cube.ply"] = ply_ascii(8, 6, PLY_V, PLY_F)
    f["cube_bin.ply"] = ply_binary(8, 6, CUBE_PTS, CUBE_QUADS)
    f["fewer.ply"] = ply_ascii(8, 5, PLY_V, PLY_F)
    f["more.ply"] = ply_ascii(8, 7, PLY_V, PLY_F)
    f["fewer_v.ply"] = ply_ascii(7, 6, PLY_V, PLY_F)
    f["huge.ply"] = ply_ascii(8, 4000000000, PLY_V, PLY_F)
    f["huge_bin.ply"] = ply_binary(2000000000, 2000000000, CUBE_PTS, CUBE_QUADS)
    # tests/fuzz: an element without properties takes no bytes; 9e18 of them hung the binary walk.
    f["empty_element.ply"] = ply_binary(8, 6, CUBE_PTS, CUBE_QUADS).replace(
        b"element face", b"element junk 9000000000000000000\nelement face")
    # tests/fuzz: a NUL or form feed in a header word made OpenMesh read other words than ours, and hang.
    f["header_nul.ply"] = ply_binary(8, 6, CUBE_PTS, CUBE_QUADS).replace(b"element face", b"element f\0ace")
    f["truncated_bin.ply"] = ply_binary(8, 6, CUBE_PTS, CUBE_QUADS)[:-10]
    f["nan.ply"] = ply_ascii(8, 6, PLY_V.replace("1 1 1", "nan 1 1"), PLY_F)
    f["idx.ply"] = ply_ascii(8, 6, PLY_V, PLY_F.replace("4 3 0 4 7", "4 3 0 4 8"))
    f["idxneg.ply"] = ply_ascii(8, 6, PLY_V, PLY_F.replace("4 3 0 4 7", "4 3 0 4 -1"))
    f["listcount.ply"] = ply_ascii(8, 6, PLY_V, PLY_F.replace("4 3 0 4 7", "9 3 0 4 7"))
    f["list2.ply"] = ply_ascii(8, 6, PLY_V, PLY_F.replace("4 3 0 4 7", "2 3 0"))
    f["noend.ply"] = ply_ascii(8, 6, PLY_V, PLY_F).replace("end_header\n", "")
    f["garbage.ply"] = "ply\nthis is not a header\n"
    f["notply.ply"] = "hello\n"
    f["empty.ply"] = ""
    f["vbad.ply"] = ply_ascii(8, 6, PLY_V.replace("1 1 1", "1 1.x 1"), PLY_F)
    f["bin_idx.ply"] = ply_binary(8, 6, CUBE_PTS, CUBE_QUADS[:-1] + [(3, 0, 4, 99)])
    f["bin_nan.ply"] = ply_binary(8, 6, CUBE_PTS[:-1] + [(float("nan"), 1, 1)], CUBE_QUADS)
    f["bin_bigface.ply"] = ply_binary(8, 1, CUBE_PTS, [tuple(range(8)) * 31])
    f["unknown.stl"] = "solid x\nendsolid\n"
    # results and gate configurations
    zero = {"median": 0.0, "min": 0.0, "max": 0.0, "reps": 5, "samples": [0, 0, 0, 0, 0]}
    peer = {"scheme": "osd-uniform", "backend": "cpu", "mesh": "cube", "level": 2, "tessellation": 2,
            "status": "ok", "triangles": 10, "time_ms": zero}
    row = dict(peer, scheme="cpatch-2pass", peer="osd-uniform", peer_backend="cpu")
    f["zero_times.json"] = results([peer, row])
    f["zero_times_rounds.json"] = results([peer, row], rounds=5)
    f["notjson.json"] = "{ this is not json"
    f["wrongshape.json"] = json.dumps({"runs": 5})
    f["array.json"] = "[1, 2, 3]"
    f["emptyobj.json"] = "{}"
    f["nulls.json"] = results([dict(row, time_ms=None, triangles=None)])
    f["gate_badregex.json"] = json.dumps({"thresholds": [{"match": "([", "threshold": 0.1}]})
    # normalisers: a backend nobody has, a pattern that is not one, a backend that is not a string.
    f["gate_norm_backend.json"] = json.dumps({"normalisers": [{"match": "/vulkan/", "backend": "gpu"}]})
    f["gate_norm_regex.json"] = json.dumps({"normalisers": [{"match": "([", "backend": "cpu-mt"}]})
    f["gate_norm_type.json"] = json.dumps({"normalisers": [{"match": "/vulkan/", "backend": 7}]})
    f["gate_badtype.json"] = json.dumps({"alpha": "small"})
    f["gate_shell.json"] = json.dumps({"workload": ["osd-uniform/cpu/cube' ; touch SHELL_RAN ; echo '/2"]})
    f["gate_badname.json"] = json.dumps({"workload": ["not-a-run-name"]})
    f["gate_ok.json"] = json.dumps({"alpha": 0.01, "min_repetitions": 3, "default_threshold": 0.1})
    # tests/fuzz's findings: values the gate cannot judge with, numbers past int or double
    f["gate_alpha.json"] = json.dumps({"alpha": 1.01})
    f["gate_reps_float.json"] = '{"min_repetitions": 1e300}'
    f["level_float.json"] = results([{"scheme": "osd-bfr", "backend": "cpu", "mesh": "cube", "level": 1e300}])
    f["number_overflow.json"] = '{"schema": 1, "runs": [], "created": 22E517456166666665}'
    f["callgrind_bad.json"] = "{\"x\": 1}"
    f.update(gate_files())
    f.update(impossible_results())
    f["paper_binary.md"] = b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR binary, not a table\n"
    f["paper_latin1.md"] = "| a | b |\n|---|---|\n| caf\xe9 | 1 |\n".encode("latin-1")
    f["sweep2500.json"] = corpus_sweep(2500)
    f.update(round_two_files())
    return f


def scaled_cube(scale, offset=0.0):
    return "".join(f"v {x * scale + offset!r} {y * scale + offset!r} {z * scale + offset!r}\n" for x, y, z in CUBE_PTS) + CUBE_F


def round_two_files():
    """Issue 45's families: readers that dropped or misread, geometry at any scale, degenerate
    shapes, tags, and facts."""
    f = {}
    # Blanks and line ends as C has them: a form feed or vertical tab after v or f, CR-only lines.
    f["ff_vt.obj"] = CUBE_V.replace("v ", "v\f") + CUBE_F.replace("f ", "f\v")
    f["cr_only.obj"] = CUBE.replace("\n", "\r")
    f["cr_only.off"] = ("OFF\n8 6 0\n" + OFF_CUBE_V + OFF_CUBE_F).replace("\n", "\r")
    f["cr_only.ply"] = ply_ascii(8, 6, PLY_V, PLY_F).replace("\n", "\r")
    f["ff_vt.off"] = ("OFF\n8 6 0\n" + OFF_CUBE_V + OFF_CUBE_F).replace(" ", "\f")
    # Coordinates below the smallest float are numbers (zero or a denormal), not out of range.
    f["vdenormal.obj"] = CUBE_V.replace("v 0 0 0", "v -1e-50 1e-40 1e-400") + CUBE_F
    f["vdenormal.ply"] = ply_ascii(8, 6, PLY_V.replace("0 0 0", "-1e-50 1e-40 1e-400", 1), PLY_F)
    f["vdenormal.off"] = "OFF\n8 6 0\n" + OFF_CUBE_V.replace("0 0 0", "-1e-50 1e-40 1e-400", 1) + OFF_CUBE_F
    # A file name that would steer the terminal, and a PLY uint index that OpenMesh reads as -1.
    f["esc\n\x1b[31mname.obj"] = TRI_V + "f 1 2 4\n"
    f["uint_idx.ply"] = ply_ascii(8, 6, PLY_V, PLY_F.replace("4 3 0 4 7", "4 3 0 4 4294967295")).replace(
        "list uchar int", "list uchar uint")
    f["uint_idx_bin.ply"] = ply_binary(8, 6, CUBE_PTS, CUBE_QUADS).replace(b"list uchar int", b"list uchar uint")[:-4] + \
        b"\xff\xff\xff\xff"
    # Scale: the verdicts of the unit cube, whatever the size or the place.
    f["cube_1e10.obj"] = scaled_cube(1e10)
    f["cube_1e-30.obj"] = scaled_cube(1e-30)
    f["cube_off1e7.obj"] = scaled_cube(1.0, 1e7)
    f["cube_1e19.obj"] = scaled_cube(1e19)
    f["cube_1e38.obj"] = scaled_cube(1e38)
    f["flat.obj"] = CUBE_V.replace(" 1\n", " 0\n") + CUBE_F  # closed and flat: the top lies on the bottom
    f["pillow.obj"] = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf 4 3 2 1\n"  # two-sided
    f["far_unused.obj"] = CUBE + "v 1e4 1e4 1e4\n"
    # Geometry nothing can be judged on.
    f["line.obj"] = "".join(f"v {x} 0 0\n" for x in (0, 1, 2, 3, 0.5, 1.5, 2.5, 3.5)) + CUBE_F
    f["point.obj"] = "v 1 1 1\n" * 8 + CUBE_F
    f["zero_area.obj"] = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\nv 3 1 0\nf 1 2 3 4\nf 5 6 7 8\n"
    f["coincident_face.obj"] = CUBE + "v 2 2 2\nv 2 2 2\nv 2 2 2\nv 2 2 2\nf 9 10 11 12\n"
    # Faces without a limit surface: an open cube under interpolateboundary 0, a hole.
    f["open_none.obj"] = CUBE_V + CUBE_F.replace("f 5 6 7 8\n", "") + "t interpolateboundary 1/0/0 0\n"
    f["hole_one.obj"] = CUBE + "t hole 1/0/0 1\n"
    # Facts: a pinch, a bowtie, tags given twice.
    second = [(x + 1, y + 1, z + 1) for x, y, z in CUBE_PTS[1:]]  # the second cube's corner 0 is the first's 7
    renumber = lambda i: 7 if i == 0 else 7 + i
    f["pinch.obj"] = CUBE + "".join(f"v {x} {y} {z}\n" for x, y, z in second) + \
        "".join("f " + " ".join(str(renumber(i) + 1) for i in q) + "\n" for q in CUBE_QUADS)
    f["bowtie.obj"] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv -1 0 0\nv 0 -1 0\nf 1 2 3\nf 1 4 5\n"
    f["crease_twice.obj"] = CUBE + "t crease 2/1/0 0 1 2.0\nt crease 2/1/0 1 0 3.0\n"
    f["hole_twice.obj"] = CUBE + "t hole 1/0/0 1\nt hole 1/0/0 1\n"
    return f


def timed(scheme, mesh, level, ms, peer="", status="ok", message="", triangles=20000, samples=9):
    """An ok results row of a bench --rounds file: `samples` rounds around `ms`."""
    times = [ms * (1 + 0.01 * ((i * 7) % 5 - 2)) for i in range(samples)]
    row = {"scheme": scheme.split(":")[0], "spec": scheme, "backend": "cpu", "mesh": mesh, "level": level,
           "tessellation": level - 1, "triangles": triangles, "vertices": triangles // 2, "status": status,
           "message": message, "time_ms": {"median": sorted(times)[samples // 2], "min": min(times), "max": max(times),
                                            "reps": samples, "samples": times},
           "triangle_rate_mtris": triangles / sorted(times)[samples // 2] / 1e3}
    if peer:
        row.update(peer=peer, peer_backend="cpu")
    return row


def gate_files():
    """The gate against a baseline whose benchmark crashed, became unsupported, went missing or was
    renamed in the current file, or whose times are negative (tests/hostile/cases.txt)."""
    probe = timed("calibration", "probe", 1, 1.0)
    probe.update(triangles=0, triangle_rate_mtris=0, tessellation=0)
    anchor = timed("osd-bfr", "cube", 9, 2.0)
    method = timed("cpatch-2pass", "cube", 9, 1.0, peer="osd-bfr")
    other = timed("embree-subdiv", "cube", 9, 3.0, peer="osd-bfr")
    crashed = dict(method, status="failed", message="crashed during execute: killed by signal 11 (SIGSEGV, Segmentation fault)")
    negative = dict(method, time_ms=dict(method["time_ms"], samples=[-x for x in method["time_ms"]["samples"]]))
    return {
        "gate_base.json": results([probe, anchor, method, other], rounds=9),
        "gate_crashed.json": results([probe, anchor, crashed, other], rounds=9),
        "gate_unsupported.json": results([probe, anchor, dict(method, status="unsupported", message="no Vulkan device"), other],
                                         rounds=9),
        "gate_dropped.json": results([probe, anchor, other], rounds=9),
        "gate_renamed.json": results([probe, anchor, dict(method, spec="cpatch-2pass:n=2"), other], rounds=9),
        "gate_negative.json": results([probe, anchor, negative, other], rounds=9),
    }


def impossible_results():
    """Figures no run can give, which the results reader refuses naming the row."""
    row = timed("cpatch-2pass", "cube", 9, 1.0, peer="osd-bfr")
    peer = timed("osd-bfr", "cube", 9, 2.0)
    cell = {"mesh": "cube", "scheme": "cpatch-2pass", "backend": "cpu", "level": 9, "triangles": 20000,
            "peer": {"scheme": "osd-bfr", "backend": "cpu", "level": 9, "triangles": 20000}, "rounds": 3,
            "rate_ratio": {"median": 2.0, "min": 1.9, "max": 2.1, "per_round": [1.9, 2.0, 2.1]},
            "time_ms": {"median": 1.0}, "peer_time_ms": {"median": 2.0}}

    def with_cell(**ratio):
        return json.dumps({"schema": 1, "machine": {"cpu_model": "x", "cores": 2}, "runs": [peer, row],
                           "paired": [dict(cell, rate_ratio=dict(cell["rate_ratio"], **ratio))]})
    return {
        "impossible_median.json": with_cell(median=5.0),
        "impossible_ratio.json": with_cell(median=-2.0, min=-2.1, max=-1.9, per_round=[-1.9, -2.0, -2.1]),
        "impossible_rate.json": results([peer, dict(row, triangles=0, triangle_rate_mtris=122.0)]),
        "impossible_open_edges.json": results([peer, dict(row, watertight={"open_edges": -7, "rays": 10, "ray_cracks": 0})]),
        "impossible_no_machine.json": json.dumps({"schema": 1, "runs": [peer, row]}),
        "impossible_time.json": results([peer, dict(row, time_ms=dict(row["time_ms"], median=-1.0, min=-1.0))]),
    }


def corpus_sweep(meshes):
    """A sweep's merged results over `meshes` meshes: two methods and their peer at two levels on
    cpu and cpu-mt, validated, every mesh its own name (the report must stay usable on it)."""
    rows = []
    for m in range(meshes):
        mesh = f"corpus/mesh-{m:04d}"
        for backend in ("cpu", "cpu-mt"):
            for scheme, peer, scale in (("osd-bfr", "", 2.0), ("cpatch-2pass", "osd-bfr", 1.0), ("osd-uniform", "osd-bfr", 3.0)):
                for level in (5, 9):
                    r = timed(scheme, mesh, level, scale * level * (1 + m % 7 / 10), peer=peer, samples=3,
                              triangles=2 * (level - 1) ** 2 * (100 + m % 50))
                    r.update(backend=backend, mesh_faces=100 + m % 50, mesh_vertices=102 + m % 50,
                             watertight={"open_edges": 0, "rays": 1000, "ray_cracks": 0, "seed": 1},
                             deviation={"pos_max_pct": 0.1, "pos_mean_pct": 0.01, "pos_rms_pct": 0.02, "pos_p95_pct": 0.05,
                                        "pos_max_rel_diag": 1e-5, "normal_max_deg": 0.5, "normal_mean_deg": 0.05,
                                        "hausdorff_rel": 1e-4})
                    if peer:
                        r["peer_backend"] = backend
                    rows.append(r)
    return results(rows)


def journals():
    """Run journals for `run --resume` (harness/run/journal.h): a folder each, holding journal.jsonl."""
    selection = {"schemes": ["osd-uniform"], "meshes": ["cube"], "backends": [], "levels": [1], "all": False,
                 "all_corpus": False, "max_triangles": 1000000, "headline": True, "reps": 5, "rays": 50000,
                 "seed": 1, "validate": True}
    header = {"journal": 1, "schema": 1, "created": "2026-01-01T00:00:00Z", "cwd": "/nowhere",
              "machine": {"git_commit": "0000000"}, "selection": selection, "runs": ["osd-uniform/cpu/cube/1"]}
    row = json.dumps({"scheme": "osd-uniform", "backend": "cpu", "mesh": "cube", "level": 1, "status": "ok"})
    return {
        "journal_commit": json.dumps(header) + "\n",
        "journal_corrupt": json.dumps(header) + "\n" + row + "\n" + "{\"scheme\": \n" + row + "\n",
        "journal_header": "this is not a journal\n" + row + "\n",
        "journal_version": json.dumps(dict(header, journal=99)) + "\n",
    }


def write_all(folder):
    os.makedirs(folder, exist_ok=True)
    for name, content in files().items():
        data = content if isinstance(content, bytes) else content.encode("utf-8")
        with open(os.path.join(folder, name), "wb") as out:
            out.write(data)
    os.makedirs(os.path.join(folder, "dir.obj"), exist_ok=True)
    os.makedirs(os.path.join(folder, "outdir"), exist_ok=True)
    os.makedirs(os.path.join(folder, "resultsdir", "results.json"), exist_ok=True)  # results.json a folder
    os.makedirs(os.path.join(folder, "journal_none"), exist_ok=True)
    for name, text in journals().items():
        os.makedirs(os.path.join(folder, name), exist_ok=True)
        with open(os.path.join(folder, name, "journal.jsonl"), "w") as out:
            out.write(text)
    pictures_with(folder, "evil", "evil.png", lambda path: os.symlink("/etc/passwd", path))
    pictures_with(folder, "notpng", "notpng.png", lambda path: open(path, "w").write("root:x:0:0:root:/root:/bin/bash\n"))
    # A corpus folder holding a symbolic-link loop beside a mesh ($SUBDIVBENCH_DATASETS in cases.txt).
    loop = os.path.join(folder, "loop_corpus")
    os.makedirs(loop, exist_ok=True)
    with open(os.path.join(loop, "cube.obj"), "w") as out:
        out.write(CUBE)
    for name, target in (("loop_a.obj", "loop_b.obj"), ("loop_b.obj", "loop_a.obj"), ("self", ".")):
        if not os.path.lexists(os.path.join(loop, name)):
            os.symlink(target, os.path.join(loop, name))
    fifo = os.path.join(folder, "fifo.obj")
    if not os.path.exists(fifo):
        os.mkfifo(fifo)
    fifo_off = os.path.join(folder, "fifo.off")
    if not os.path.exists(fifo_off):
        os.mkfifo(fifo_off)


def pictures_with(folder, name, picture, make):
    """FOLDER/NAME/results.json with a pictures/pictures.json beside it naming `picture`, made by
    `make` (a link to /etc/passwd, a text file named .png): the report must not inline it."""
    base = os.path.join(folder, name)
    os.makedirs(os.path.join(base, "pictures"), exist_ok=True)
    with open(os.path.join(base, "results.json"), "w") as out:
        out.write(results([timed("osd-bfr", "cube", 9, 2.0)]))
    manifest = {"schema": 1, "available": True, "device": "test", "pictures": [
        {"scheme": "osd-bfr", "mesh": "cube", "backend": "cpu", "level": 9, "triangles": 20000, "kind": "shaded",
         "file": picture}]}
    with open(os.path.join(base, "pictures", "pictures.json"), "w") as out:
        json.dump(manifest, out)
    path = os.path.join(base, "pictures", picture)
    if os.path.lexists(path):
        os.remove(path)
    make(path)
