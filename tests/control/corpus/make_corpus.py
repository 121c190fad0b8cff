#!/usr/bin/env python3
"""Writes the checked-in fuzz corpus of the control protocol and its MANIFEST.

Each .bin file is sent as-is over one connection; MANIFEST says which replies
come back (error codes, or "ok"), whether the server then closes the
connection, and how many requests reach the CommandHandler. Rerun after
editing: python3 tests/control/corpus/make_corpus.py
"""
import json
import os
import random
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
MAX = 64 * 1024
entries = []


def frame(payload):
    if isinstance(payload, str):
        payload = payload.encode("utf-8")
    return struct.pack(">I", len(payload)) + payload


def req(i, cmd, args=None, v=1):
    m = {"v": v, "id": i, "cmd": cmd}
    if args is not None:
        m["args"] = args
    return frame(json.dumps(m, separators=(",", ":")))


def add(name, data, replies, after, handler_calls=0):
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(data)
    entries.append((name, ",".join(replies) if replies else "-", after, handler_calls))


PING = req(1, "ping")

# --- framing -----------------------------------------------------------------
add("truncated_header.bin", b"\x00\x00", ["bad_frame"], "closed")
add("truncated_payload.bin", struct.pack(">I", 100) + b'{"v":1,"id":1,"cmd":', ["bad_frame"], "closed")
add("valid_then_truncated.bin", PING + struct.pack(">I", 50) + b'{"v":1,"id"', ["ok", "bad_frame"], "closed")
add("zero_length.bin", struct.pack(">I", 0), ["bad_frame"], "open")
add("zero_length_then_valid.bin", struct.pack(">I", 0) + PING, ["bad_frame", "ok"], "open")
add("length_ffffffff.bin", b"\xff\xff\xff\xff", ["oversized"], "closed")
add("length_ffffffff_with_payload.bin", b"\xff\xff\xff\xff" + b"A" * 1000, ["oversized"], "closed")
ping = b'{"v":1,"id":1,"cmd":"ping"}'
add("length_65537.bin", frame(ping + b" " * (MAX + 1 - len(ping))), ["oversized"], "closed")
add("length_65536_exact.bin", frame(ping + b" " * (MAX - len(ping))), ["ok"], "open")
add("random_binary.bin", b"\xa7" + random.Random(20240601).randbytes(4095), ["oversized"], "closed")
add("valid_then_garbage.bin", PING + b"GARBAGE GARBAGE GARBAGE", ["ok", "oversized"], "closed")
add("valid_then_small_garbage.bin", PING + frame(b"hello") + PING, ["ok", "bad_json", "ok"], "open")

# --- encoding ----------------------------------------------------------------
add("non_utf8_in_string.bin", frame(b'{"v":1,"id":1,"cmd":"start_trial","args":{"study":"\xff\xfe","participant":1,"condition":1}}'),
    ["bad_frame"], "open")
add("non_utf8_overlong.bin", frame(b'{"v":1,"id":1,"cmd":"\xc0\xafping"}'), ["bad_frame"], "open")
add("non_utf8_surrogate.bin", frame(b'{"v":1,"id":1,"cmd":"\xed\xa0\x80"}'), ["bad_frame"], "open")
add("non_utf8_latin1.bin", frame(b'{"v":1,"id":1,"cmd":"start_capture","args":{"knob":"caf\xe9"}}'), ["bad_frame"], "open")
add("non_utf8_outside_string.bin", frame(b'{"v":1,\x80"id":1}'), ["bad_frame"], "open")
add("nul_byte.bin", frame(b'{"v":1,"id":1,"cmd":"pi\x00ng"}'), ["bad_json"], "open")
add("bom_prefixed.bin", frame(b"\xef\xbb\xbf" + ping), ["ok"], "open")

# --- nesting -----------------------------------------------------------------
add("deep_array_60000.bin", frame(b"[" * 60000), ["bad_json"], "open")
add("deep_array_100000.bin", frame(b"[" * 100000), ["oversized"], "closed")
add("deep_object_1000.bin", frame(b'{"a":' * 1000 + b"1" + b"}" * 1000), ["bad_json"], "open")
add("deep_in_args.bin", frame(b'{"v":1,"id":1,"cmd":"get_state","args":{"x":' + b"[" * 40 + b"]" * 40 + b"}}"),
    ["bad_json"], "open")
add("brackets_in_string.bin", req(1, "start_trial", {"study": "[" * 100, "participant": "{" * 100, "condition": 3}),
    ["ok"], "open", 1)

# --- numbers -----------------------------------------------------------------
add("huge_number_overflow.bin", frame(b'{"v":1,"id":1,"cmd":"set_params","args":{"B_vel":1e400}}'), ["bad_json"], "open")
add("huge_integer_id.bin", frame(b'{"v":1,"id":123456789012345678901234567890,"cmd":"ping"}'), ["bad_args"], "open")
add("huge_value_out_of_range.bin", req(1, "set_params", {"M_acc": 1e308}), ["bad_args"], "open")
add("negative_zero_ok.bin", frame(b'{"v":1,"id":-0,"cmd":"set_params","args":{"B_vel":-0.0}}'), ["ok"], "open", 1)
add("long_digit_string.bin", frame(b'{"v":1,"id":' + b"9" * 60000 + b',"cmd":"ping"}'), ["bad_json"], "open")

# --- types, versions, commands -------------------------------------------------
capture = {"swept_sine": {"a": 0, "b": 1.5, "c": 1, "d": 3}, "seconds": 6, "knob": "demo"}
model = {"M_acc": 1.3e-05, "B_vel": 0.0002, "A_pos": 0.01, "P_pos": 0.05}
wrong = [
    ("load_model", dict(model, M_acc="heavy")),
    ("load_model", dict(model, P_pos=None)),
    ("load_model", dict(model, dv=[0.1], D_neg=0.01, D_pos=0.01)),
    ("set_params", {"B_vel": True}),
    ("set_params", {"K_vm": {"k": 1}}),
    ("start_capture", dict(capture, seconds="6")),
    ("start_capture", dict(capture, swept_sine=[0, 1.5, 1, 3])),
    ("start_capture", dict(capture, swept_sine={"a": 0, "b": 1.5, "c": "1", "d": 3})),
    ("start_capture", dict(capture, pid={"Kp": None})),
    ("start_capture", dict(capture, knob=5)),
    ("start_trial", {"study": 1.5, "participant": 1, "condition": 1}),
    ("start_trial", {"study": "S", "participant": True, "condition": 1}),
    ("calibrate", {"kind": 3}),
    ("set_mode", {"mode": None}),
    ("subscribe", {"events": "state"}),
    ("subscribe", {"events": [1]}),
    ("subscribe", {"events": [], "telemetry": "yes"}),
    ("hello", {"versions": 1}),
    ("hello", {"versions": [1], "watchdog_ms": 100.5}),
    ("hello", {"versions": [1], "client": 7}),
]
add("wrong_types.bin", b"".join(req(i, c, a) for i, (c, a) in enumerate(wrong)), ["bad_args"] * len(wrong), "open")
add("wrong_version.bin",
    req(1, "ping", v=2) + req(2, "ping", v="1") + req(3, "ping", v=None) + req(4, "ping", v=1.5) +
    frame(b'{"id":5,"cmd":"ping"}'), ["unsupported_version"] * 5, "open")
add("unknown_command.bin", req(1, "reboot") + req(2, "PING") + req(3, "") + req(4, "ping "),
    ["unknown_command"] * 4, "open")
add("not_an_object.bin", frame("[1,2]") + frame('"s"') + frame("42") + frame("null") + frame("true"),
    ["not_an_object"] * 5, "open")
bad = [b"{", b"{'v':1}", b'{"v":1,}', b'{"v":1} {}', b"NaN", b"undefined", b"   ", b'{"v":1,"id":1,"cmd":"ping"/*c*/}']
add("bad_json.bin", b"".join(frame(b) for b in bad), ["bad_json"] * len(bad), "open")
add("envelope_errors.bin",
    frame(b'{"v":1,"cmd":"ping"}') + frame(b'{"v":1,"id":"1","cmd":"ping"}') +
    frame(b'{"v":1,"id":1,"cmd":"ping","extra":1}') + frame(b'{"v":1,"id":1,"cmd":"ping","args":[]}') +
    frame(b'{"v":1,"event":"state","data":{}}'), ["bad_args"] * 5, "open")
valid = [
    ("hello", {"versions": [1], "client": "corpus"}), ("ping", {}), ("get_state", None),
    ("load_model", dict(model, dv=0.1, D_neg=0.01, D_pos=0.01, K_vm=1, B_vm=0.01)),
    ("set_params", {"B_vel": 0.0005}), ("start_capture", dict(capture, pid={"Kp": 200, "Ki": 5000, "Kd": 1})),
    ("stop_capture", {}), ("start_trial", {"study": "S1", "participant": 7, "condition": "detents-12"}),
    ("stop_trial", {}), ("calibrate", {"kind": "accel_gain"}), ("clear_fault", {}), ("set_mode", {"mode": "idle"}),
    ("subscribe", {"events": ["*"]}),
]
add("every_command_valid.bin", b"".join(req(i, c, a) for i, (c, a) in enumerate(valid)), ["ok"] * len(valid), "open", 10)

with open(os.path.join(HERE, "MANIFEST"), "w") as f:
    f.write("# Generated by make_corpus.py.\n# file  replies(in order, '-' = none)  after(open|closed)  handler_calls\n")
    for name, replies, after, calls in entries:
        f.write(f"{name} {replies} {after} {calls}\n")
print(f"wrote {len(entries)} corpus files")
