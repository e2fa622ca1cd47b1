#!/usr/bin/env python3
"""Authoring tool for the protocol test vectors: an independent reference (Python's own
zlib CRC-32 and a hand XOR) that writes nano.json, mega.json, job.json and esp.json.

The JSON files are the contract; both the TypeScript and the C++ suites read them. Run
`python3 protocol/vectors/author.py` after changing a case here, and commit both.
Strings are byte strings: every character stands for one byte (Latin-1).
"""
import json
import os
import random
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def cs(s):
    x = 0
    for ch in s.encode("latin-1"):
        x ^= ch
    return x


def crc16(s):
    """CRC-16/CCITT-FALSE: poly 0x1021, init 0xFFFF, no reflection, no final XOR."""
    c = 0xFFFF
    for b in s.encode("latin-1"):
        c ^= b << 8
        for _ in range(8):
            c = ((c << 1) ^ 0x1021) & 0xFFFF if c & 0x8000 else (c << 1) & 0xFFFF
    return c


def numbered(n, body, strong=True):
    """A numbered line as the app sends it (XOR and CRC-16), or as Marlin hosts do (XOR only)."""
    head = f"N{n} {body}"
    return f"{head}*{cs(head)}#{crc16(head):04x}" if strong else f"{head}*{cs(head)}"


def write(name, doc):
    with open(os.path.join(HERE, name), "w", encoding="utf-8") as f:
        json.dump(doc, f, indent=1, ensure_ascii=True)
        f.write("\n")


# ---------------------------------------------------------------- Nano link
NANO_COLOURS = {
    "green": [0, 40, 0], "dim_white": [24, 24, 24], "purple": [96, 0, 128],
    "cyan": [0, 96, 96], "orange": [160, 48, 0], "red": [128, 0, 0],
}

nano_commands = [
    {"line": "S\n", "command": {"op": "S"}, "flash": "dim_white"},
    {"line": "F:15,100,200,300,400\n", "command": {"op": "F", "mask": 15, "durations": [100, 200, 300, 400]}, "flash": "purple"},
    {"line": "F:0,0,0,0,0\n", "command": {"op": "F", "mask": 0, "durations": [0, 0, 0, 0]}, "flash": "purple"},
    {"line": "F:5,10,0,4294967295,0\n", "command": {"op": "F", "mask": 5, "durations": [10, 0, 4294967295, 0]}, "flash": "purple"},
    {"line": "D\n", "command": {"op": "D"}, "flash": "cyan"},
    {"line": "U\n", "command": {"op": "U"}, "flash": "cyan"},
    {"line": "X\n", "command": {"op": "X"}, "flash": "cyan"},
    {"line": "P\n", "command": {"op": "P"}, "flash": "cyan"},
    {"line": "T\n", "command": {"op": "T"}, "flash": "dim_white"},
    {"line": "R\n", "command": {"op": "R"}, "flash": "orange"},
    {"line": "E\n", "command": {"op": "E"}, "flash": "dim_white"},
    {"line": "V\n", "command": {"op": "V"}, "flash": "dim_white"},
    {"line": "C\n", "command": {"op": "C"}, "flash": "dim_white"},
    {"line": "G\n", "command": {"op": "G"}, "flash": "purple"},
    {"line": "Q\n", "command": {"op": "Q"}, "flash": "dim_white"},
    # O: the oldest dose record not yet reported (nano.md "Dose records").
    {"line": "O\n", "command": {"op": "O"}, "flash": "dim_white"},
    {"line": "W\n", "command": {"op": "W"}, "flash": "dim_white"},
    # L: the link speed, 115200 (power-on) or one exact at 16 MHz with U2X (nano.md "Link speed").
    {"line": "L:1000000\n", "command": {"op": "L", "baud": 1000000}, "flash": "dim_white"},
    {"line": "L:500000\n", "command": {"op": "L", "baud": 500000}, "flash": "dim_white"},
    {"line": "L:250000\n", "command": {"op": "L", "baud": 250000}, "flash": "dim_white"},
    {"line": "L:115200\n", "command": {"op": "L", "baud": 115200}, "flash": "dim_white"},
]
nano_parse_only = [
    {"line": "S\r\n", "command": {"op": "S"}},
    {"line": "F:015,0100,0,00,0\r\n", "command": {"op": "F", "mask": 15, "durations": [100, 0, 0, 0]}},
    {"line": "F:8,0,0,0,10000000\n", "command": {"op": "F", "mask": 8, "durations": [0, 0, 0, 10000000]}},
    {"line": "L:0001000000\r\n", "command": {"op": "L", "baud": 1000000}},
]
nano_malformed = [
    {"line": "s\n", "why": "lower case"},
    {"line": "Z\n", "why": "unknown command"},
    {"line": "G1\n", "why": "trailing characters after G"},
    {"line": "W:1\n", "why": "W takes nothing"},
    {"line": "O:1\n", "why": "O takes nothing"},
    {"line": "S1\n", "why": "trailing characters"},
    {"line": "S \n", "why": "trailing space"},
    {"line": "F:16,1,1,1,1\n", "why": "mask over 15"},
    {"line": "F:15,1,1,1\n", "why": "three durations"},
    {"line": "F:15,1,1,1,1,1\n", "why": "five durations"},
    {"line": "F:15,1,1,1,4294967296\n", "why": "duration over 32 bits"},
    {"line": "F:15,1,1,1,12345678901\n", "why": "eleven digits"},
    {"line": "F:15,-1,1,1,1\n", "why": "negative"},
    {"line": "F:15,1,,1,1\n", "why": "empty field"},
    {"line": "F:15,1,1,1,1,\n", "why": "trailing comma"},
    {"line": "F15,1,1,1,1\n", "why": "no colon"},
    {"line": "F:+5,1,1,1,1\n", "why": "plus sign"},
    {"line": "F: 5,1,1,1,1\n", "why": "space"},
    {"line": "F:\n", "why": "no fields"},
    {"line": "T\u00ff\n", "why": "byte outside 0x20-0x7E"},
    {"line": "S\r\r\n", "why": "two carriage returns"},
    {"line": "L\n", "why": "L without a speed"},
    {"line": "L:\n", "why": "L with an empty speed"},
    {"line": "L:9600\n", "why": "a speed not in the table"},
    {"line": "L:1000001\n", "why": "a speed one off the table"},
    {"line": "L:2000000\n", "why": "a speed above the table"},
    # 4295967296 is 2^32 + 1000000: refused, never wrapped to 1000000.
    {"line": "L:4295967296\n", "why": "a speed past 32 bits"},
    {"line": "L:00001000000\n", "why": "eleven digits"},
    {"line": "L:+500000\n", "why": "a signed speed"},
    {"line": "L:500000,1\n", "why": "a field after the speed"},
    {"line": "L:500 000\n", "why": "a space inside the speed"},
]
nano_replies = [
    {"line": "S:0\n", "reply": {"op": "S", "mask": 0}},
    {"line": "S:15\n", "reply": {"op": "S", "mask": 15}},
    {"line": "S:9\n", "reply": {"op": "S", "mask": 9}},
    {"line": "P:1\n", "reply": {"op": "P", "triggered": True}},
    {"line": "P:0\n", "reply": {"op": "P", "triggered": False}},
    {"line": "T:23.5,24.0,-5.2,100.0,22.1,0.0\n", "reply": {"op": "T", "deciC": [235, 240, -52, 1000, 221, 0]}},
    {"line": "T:-50.0,125.0,-0.5,0.5,999.9,-99.9\n", "reply": {"op": "T", "deciC": [-500, 1250, -5, 5, 9999, -999]}},
    {"line": "E:0\n", "reply": {"op": "E", "flags": 0}},
    {"line": "E:161\n", "reply": {"op": "E", "flags": 161}},
    {"line": "V:1,0.1.0\n", "reply": {"op": "V", "protocol": 1, "firmware": "0.1.0"}},
    {"line": "C:0,0,1\n", "reply": {"op": "C", "boot": 0, "fires": 0, "whole": True}},
    {"line": "C:65535,4294967295,0\n", "reply": {"op": "C", "boot": 65535, "fires": 4294967295, "whole": False}},
    {"line": "C:17,3,1\n", "reply": {"op": "C", "boot": 17, "fires": 3, "whole": True}},
    {"line": "K:0\n", "reply": {"op": "K", "code": 0}},
    {"line": "K:7\n", "reply": {"op": "K", "code": 7}},
    {"line": "Q:2,0,0\n", "reply": {"op": "Q", "free": 2, "armed": 0, "pass": 0}},
    {"line": "Q:0,2,6\n", "reply": {"op": "Q", "free": 0, "armed": 2, "pass": 6}},
    {"line": "Q:1,0,1\n", "reply": {"op": "Q", "free": 1, "armed": 0, "pass": 1}},
    {"line": "Q:2,0,7\n", "reply": {"op": "Q", "free": 2, "armed": 0, "pass": 7}},
    {"line": "W:0\n", "reply": {"op": "W", "us": 0}},
    {"line": "W:1024000\n", "reply": {"op": "W", "us": 1024000}},
    {"line": "W:4294967295\n", "reply": {"op": "W", "us": 4294967295}},
    # L: the Nano took the speed; both sides change once this reply has gone out (nano.md "Link speed").
    {"line": "L:1000000\n", "reply": {"op": "L", "baud": 1000000}},
    {"line": "L:115200\n", "reply": {"op": "L", "baud": 115200}},
    # O: a dose record (exposure number, program in its chain, each LED's on-time in µs), or O:0 for none.
    {"line": "O:0\n", "reply": {"op": "O", "exposure": 0}},
    {"line": "O:1,0,1500,0,0,1500\n", "reply": {"op": "O", "exposure": 1, "program": 0, "onUs": [1500, 0, 0, 1500]}},
    {"line": "O:17,3,40210,39988,0,2\n", "reply": {"op": "O", "exposure": 17, "program": 3, "onUs": [40210, 39988, 0, 2]}},
    # The longest reply of the link: 62 bytes before its newline.
    {"line": "O:4294967295,65535,4294967295,4294967295,4294967295,4294967295\n",
     "reply": {"op": "O", "exposure": 4294967295, "program": 65535, "onUs": [4294967295] * 4}},
]
nano_bad_replies = [
    {"line": "S:16\n"}, {"line": "S:\n"}, {"line": "S15\n"}, {"line": "P:2\n"},
    {"line": "T:23.5,24.0,-5.2,100.0,22.1\n"}, {"line": "T:23,24.0,-5.2,100.0,22.1,0.0\n"},
    {"line": "T:23.55,24.0,-5.2,100.0,22.1,0.0\n"}, {"line": "T:1000.0,24.0,-5.2,100.0,22.1,0.0\n"},
    {"line": "T:-0.0x,24.0,-5.2,100.0,22.1,0.0\n"}, {"line": "E:256\n"}, {"line": "V:1\n"},
    {"line": "Z:1\n"}, {"line": "S:1"},
    {"line": "K:8\n"}, {"line": "K:\n"}, {"line": "K:12\n"}, {"line": "Q:3,0,0\n"}, {"line": "Q:0,3,0\n"},
    {"line": "Q:0,0,8\n"}, {"line": "Q:0,0\n"}, {"line": "Q:0,0,0,0\n"},
    {"line": "W:4294967296\n"}, {"line": "W:\n"}, {"line": "W:-1\n"}, {"line": "W:12345678901\n"}, {"line": "W:1,2\n"},
    {"line": "C:65536,0,1\n"}, {"line": "C:1,4294967296,1\n"}, {"line": "C:1,2,3\n"}, {"line": "C:1,2\n"}, {"line": "C:1,2,1,0\n"},
    # L: a speed not in the table is refused, as the Nano refuses it.
    {"line": "L:\n"}, {"line": "L:9600\n"}, {"line": "L:4295467296\n"}, {"line": "L:1000000,1\n"},
    # O: exposure 0 carries no record; every number in range and in place, never wrapped.
    {"line": "O:\n"}, {"line": "O:0,0,0,0,0,0\n"}, {"line": "O:1\n"}, {"line": "O:1,0,1,2,3\n"},
    {"line": "O:1,0,1,2,3,4,5\n"}, {"line": "O:1,65536,0,0,0,0\n"}, {"line": "O:4294967296,0,0,0,0,0\n"},
    {"line": "O:1,0,0,0,0,4294967296\n"}, {"line": "O:1,0,0,-1,0,0\n"}, {"line": "O:1,0,0,,0,0\n"},
]
nano_streams = [
    {"name": "lines split anywhere", "bytes": "S\nT\r\n\nP\n", "lines": ["S", "T", "P"], "dropped": 0},
    {"name": "overlong line dropped whole", "bytes": "S\n" + "F:15," + "1" * 59 + "\nP\n", "lines": ["S", "P"], "dropped": 1},
    {"name": "63 bytes is the limit", "bytes": "A" * 63 + "\n" + "B" * 64 + "\nS\n", "lines": ["A" * 63, "S"], "dropped": 1},
    {"name": "bad byte poisons its line only", "bytes": "S\u0000\nT\nP\u00ff\n", "lines": ["T"], "dropped": 2},
    {"name": "unterminated tail stays pending", "bytes": "S\nT", "lines": ["S"], "dropped": 0},
]
write("nano.json", {
    "link": "nano", "version": 1,
    "maxLine": 63,
    "colours": NANO_COLOURS,
    "commands": nano_commands,
    "parseOnly": nano_parse_only,
    "malformed": nano_malformed,
    "replies": nano_replies,
    "badReplies": nano_bad_replies,
    "streams": nano_streams,
})

# ---------------------------------------------------------------- Mega dialect
frames = [
    {"line": numbered(1, "G28"), "frame": {"n": 1, "body": "G28"}, "canonical": True},
    {"line": numbered(1, "G28", strong=False), "frame": {"n": 1, "body": "G28"}, "canonical": False},
    {"line": numbered(9, "M105", strong=False), "frame": {"n": 9, "body": "M105"}, "canonical": False},
    {"line": numbered(0, "M110"), "frame": {"n": 0, "body": "M110"}, "canonical": True},
    {"line": numbered(2147483646, "M105"), "frame": {"n": 2147483646, "body": "M105"}, "canonical": True},
    {"line": numbered(12, "r 3 0 00ff10"), "frame": {"n": 12, "body": "r 3 0 00ff10"}, "canonical": True},
    {"line": numbered(7, "G1 X10.5 Y-2 ; move"), "frame": {"n": 7, "body": "G1 X10.5 Y-2"}, "canonical": False},
    {"line": "N3   M105*" + str(cs("N3   M105")), "frame": {"n": 3, "body": "M105"}, "canonical": False},
    {"line": numbered(-1, "M110 N-1", strong=False), "frame": {"n": -1, "body": "M110 N-1"}, "canonical": False},
    {"line": "M105", "frame": {"body": "M105"}, "canonical": True},
    {"line": "  g28 x ", "frame": {"body": "g28 x"}, "canonical": False},
    {"line": "; only a comment", "frame": {"body": ""}, "canonical": False},
]
frame_errors = [
    {"line": "N1 G28*19", "error": 2, "n": 1},
    {"line": "N1 G28*18#39c4", "error": 2, "n": 1},
    {"line": "N1 G28*18#39C3", "error": 2, "n": 1},
    {"line": "N1 G28*18#39c", "error": 2, "n": 1},
    {"line": "N1 G28*19#39c3", "error": 2, "n": 1},
    {"line": "N1 G29*" + str(cs("N1 G29")) + "#39c3", "error": 2, "n": 1},
    {"line": "N1 G28*", "error": 2, "n": 1},
    {"line": "N1 G28*256", "error": 2, "n": 1},
    {"line": "N1 G28*1x", "error": 2, "n": 1},
    {"line": "N1 G28", "error": 3, "n": 1},
    {"line": "G28*18", "error": 4},
    {"line": "N1 G\u00ff28*" + str(cs("N1 G\u00ff28")), "error": 1, "n": 1},
    {"line": "M105\u0007", "error": 1},
    # The last number is 2147483646, so that `Resend: <last + 1>` always names a number (mega.md §2).
    {"line": numbered(2147483647, "M105"), "error": 2},
    {"line": "N2147483648 M105*" + str(cs("N2147483648 M105")), "error": 2},
    {"line": "N-2 M105*" + str(cs("N-2 M105")), "error": 2},
    {"line": "N1G28*" + str(cs("N1G28")), "error": 2},
    {"line": "N" + "1" * 3 + " " + "G1 X1" * 19, "error": 5, "n": 111},
    {"line": "G1 X1" * 20, "error": 5},
]
commands = [
    {"body": "G28", "command": {"word": "G28", "params": {}}},
    {"body": "G1 X10.5 Y-2 F3000", "command": {"word": "G1", "params": {"X": 10500, "Y": -2000, "F": 3000000}}},
    {"body": "g28 x y", "command": {"word": "G28", "params": {"X": None, "Y": None}}},
    {"body": "G0 X1.23456 Y-0.0005 Z.5", "error": 11},
    {"body": "G0 X1.23456 Y-0.0005 Z0.5", "command": {"word": "G0", "params": {"X": 1235, "Y": -1, "Z": 500}}},
    {"body": "G0 X2000000 Y-2000000.000", "command": {"word": "G0", "params": {"X": 2000000000, "Y": -2000000000}}},
    {"body": "G0 X2000000.001", "error": 11},
    # Whole parts past the range are refused, however many digits: 4294968 * 1000 would wrap 32 bits.
    {"body": "G1 X4294968 Y4294969.5", "error": 11},
    {"body": "G1 X2000001", "error": 11},
    {"body": "G1 X0002000000", "command": {"word": "G1", "params": {"X": 2000000000}}},
    {"body": "M850 bed.x 4295167", "command": {"word": "M850", "text": "bed.x 4295167"}},
    {"body": "M155 S2", "command": {"word": "M155", "params": {"S": 2000}}},
    {"body": "M820 X-1 S1", "command": {"word": "M820", "params": {"X": -1000, "S": 1000}}},
    {"body": "M23 PCB_TOP.UVJ", "command": {"word": "M23", "text": "PCB_TOP.UVJ"}},
    {"body": "M28 job-3.uvj", "command": {"word": "M28", "text": "job-3.uvj"}},
    {"body": "M30 a b", "error": 11},
    # OctoPrint names card files from the root (`/`), in DOS short form (`~1`); the root is the card's only folder.
    {"body": "M23 /PART.GCO", "command": {"word": "M23", "text": "PART.GCO"}},
    {"body": "M28 /my_lon~1.gco", "command": {"word": "M28", "text": "my_lon~1.gco"}},
    {"body": "M32 part.gco", "command": {"word": "M32", "text": "part.gco"}},
    {"body": "M23 //PART.GCO", "error": 11},
    {"body": "M23 /", "error": 11},
    {"body": "M26 S1024", "command": {"word": "M26", "params": {"S": 1024000}}},
    {"body": "M113 S2", "command": {"word": "M113", "params": {"S": 2000}}},
    {"body": "M400", "command": {"word": "M400", "params": {}}},
    {"body": "M23", "error": 11},
    {"body": "M850 bed.x 200", "command": {"word": "M850", "text": "bed.x 200"}},
    {"body": "M850 led.offset.1", "command": {"word": "M850", "text": "led.offset.1"}},
    {"body": "M850", "error": 11},
    # M117 alone clears the panel's message, as Marlin's does.
    {"body": "M117", "command": {"word": "M117", "text": ""}},
    {"body": "M117 UV-PRINTER 192.168.4.1", "command": {"word": "M117", "text": "UV-PRINTER 192.168.4.1"}},
    {"body": "M1000 S", "command": {"word": "M1000", "params": {"S": None}}},
    {"body": "M420", "command": {"word": "M420", "params": {}}},
    {"body": "G1 X1 X2", "error": 11},
    {"body": "G1 X1e3", "error": 11},
    {"body": "G1 X--1", "error": 11},
    {"body": "G1 X1.", "error": 11},
    {"body": "G1 #1", "error": 11},
    {"body": "G", "error": 10},
    {"body": "Q5", "error": 10},
    {"body": "G1X10", "error": 10},
    {"body": "M99999", "error": 10},
]


def ok(n=None, p=8, b=8):
    """The reply block's last line: `n` is the line it answers, None when it accepts none."""
    head = f"ok P{p} B{b}" if n is None else f"ok N{n} P{p} B{b}"
    return f"{head}*{crc16(head):04x}"


def err(code, msg, last):
    return [f"Error:E{code} {msg}, Last Line: {last}", f"Resend: {last + 1}", ok()]


sessions = [
    {"name": "in-order lines execute", "steps": [
        {"rx": numbered(1, "M105"), "execute": "M105"},
        {"rx": numbered(2, "G28"), "execute": "G28"},
        {"rx": "M114", "execute": "M114"},
        {"rx": numbered(3, "M114"), "execute": "M114"},
    ]},
    {"name": "corrupt line inside a full window resyncs", "steps": [
        {"rx": numbered(1, "M105"), "execute": "M105"},
        {"rx": "N2 M105*0", "reply": err(2, "checksum mismatch", 1)},
        {"rx": numbered(3, "M105"), "reply": [ok()]},
        {"rx": numbered(4, "M114"), "reply": [ok()]},
        {"rx": "N5 G28*0", "reply": err(2, "checksum mismatch", 1)},
        {"rx": numbered(2, "M105"), "execute": "M105"},
        {"rx": numbered(3, "M105"), "execute": "M105"},
        {"rx": numbered(5, "M105"), "reply": err(6, "line number is not last line number+1", 3)},
    ]},
    {"name": "duplicates are acknowledged, not executed", "steps": [
        {"rx": numbered(1, "G28"), "execute": "G28"},
        {"rx": numbered(2, "G1 X1"), "execute": "G1 X1"},
        {"rx": numbered(1, "G28"), "reply": [ok()]},
        {"answered": 1},
        {"rx": numbered(1, "G28"), "reply": [ok(1)]},
        {"rx": numbered(2, "G1 X1"), "reply": [ok()]},
        {"answered": 2},
        {"rx": numbered(2, "G1 X1"), "reply": [ok(2)]},
        {"rx": numbered(3, "M105"), "execute": "M105"},
    ]},
    {"name": "M110 sets the line number and ends resync", "steps": [
        {"rx": numbered(1, "M105"), "execute": "M105"},
        {"rx": "N2 M105", "reply": err(3, "line number without checksum", 1)},
        {"rx": numbered(100, "M110"), "reply": [ok(100)]},
        {"rx": numbered(101, "M105"), "execute": "M105"},
        {"rx": "M110 N0", "reply": [ok(0)]},
        {"rx": "N1 ; a numbered comment*" + str(cs("N1 ; a numbered comment")), "reply": [ok(1)]},
        {"rx": "; a plain comment", "reply": [ok()]},
        {"rx": numbered(2, "M105"), "execute": "M105"},
        {"rx": numbered(3, "M105"), "execute": "M105"},
    ]},
    {"name": "line numbers do not wrap: after the last one only M110 starts again", "steps": [
        {"rx": numbered(2147483646, "M110"), "reply": [ok(2147483646)]},
        {"rx": numbered(0, "M105"), "reply": [ok(0)]},  # a duplicate, as every number up to the last is
        {"rx": numbered(2147483646, "M105"), "reply": [ok(2147483646)]},
        # A damaged line asks for the next number, which no line can carry: the sender must M110.
        {"rx": "N5 M105*0", "reply": err(2, "checksum mismatch", 2147483646)},
        {"rx": numbered(2147483647, "M105"), "reply": err(2, "checksum mismatch", 2147483646)},
        {"rx": "M110 N0", "reply": [ok(0)]},
        {"rx": numbered(1, "M105"), "execute": "M105"},
    ]},
    {"name": "printrun's reset: N-1 M110 N-1 makes the next line N0", "steps": [
        {"rx": numbered(1, "M105", strong=False), "execute": "M105"},
        {"rx": numbered(-1, "M110 N-1", strong=False), "reply": [ok()]},
        {"rx": numbered(0, "G28", strong=False), "execute": "G28"},
        {"rx": numbered(1, "M105", strong=False), "execute": "M105"},
    ]},
    {"name": "errors on plain lines ask for no resend", "steps": [
        {"rx": "G28*18", "reply": ["Error:E4 checksum without line number", ok()]},
        {"rx": "M105\u0007", "reply": ["Error:E1 invalid byte in line", ok()]},
        {"rx": "G1 X1" * 20, "reply": ["Error:E5 line too long", ok()]},
        {"rx": "", "reply": []},
        {"rx": numbered(1, "M105"), "execute": "M105"},
    ]},
    {"name": "an overlong numbered line asks for a resend", "steps": [
        {"rx": numbered(1, "M105"), "execute": "M105"},
        {"rx": "N2 " + "G1 X1" * 19, "reply": err(5, "line too long", 1)},
        {"rx": numbered(2, "M105"), "execute": "M105"},
    ]},
]

def dose(stop, program, exposure, on, plan=None, cut=False, again=False):
    d = {"kind": "dose", "stop": stop, "program": program, "exposure": exposure, "onUs": on, "cut": cut, "again": again}
    if plan is not None:
        d["planUs"] = plan
    return d


replies = [
    {"line": ok(4, 8, 7), "reply": {"kind": "ok", "n": 4, "p": 8, "b": 7}, "canonical": True},
    {"line": "ok N4 P8 B7*%04x" % (crc16("ok N4 P8 B7") ^ 1), "reply": {"kind": "ok"}, "canonical": False},
    {"line": "ok N5 P8 B7*%04x" % crc16("ok N4 P8 B7"), "reply": {"kind": "ok"}, "canonical": False},
    {"line": "ok N4 P8 B7*" + str(cs("ok N4 P8 B7")), "reply": {"kind": "ok"}, "canonical": False},
    {"line": "ok N4 P8 B7", "reply": {"kind": "ok"}, "canonical": False},
    {"line": ok(None, 8, 7), "reply": {"kind": "ok", "p": 8, "b": 7}, "canonical": True},
    {"line": "ok", "reply": {"kind": "ok"}, "canonical": False},
    {"line": "ok T:20.0 /0.0", "reply": {"kind": "ok"}, "canonical": False},
    {"line": "Error:E2 checksum mismatch, Last Line: 4", "reply": {"kind": "error", "code": 2, "message": "checksum mismatch, Last Line: 4"}, "canonical": True},
    # Refusals (errors.csv class `refusal`) leave the machine fine and are answered as Marlin does, with echo:
    {"line": "echo:E10 unknown command: M999x", "reply": {"kind": "error", "code": 10, "message": "unknown command: M999x"}, "canonical": True},
    {"line": "echo:E14 axis not homed: X", "reply": {"kind": "error", "code": 14, "message": "axis not homed: X"}, "canonical": True},
    {"line": "Error:E10 unknown command: M999x", "reply": {"kind": "error", "code": 10, "message": "unknown command: M999x"}, "canonical": False},
    {"line": "Error:E13 machine halted: send M999", "reply": {"kind": "error", "code": 13, "message": "machine halted: send M999"}, "canonical": True},
    {"line": "echo:E13 machine halted: send M999", "reply": {"kind": "error", "code": 13, "message": "machine halted: send M999"}, "canonical": False},
    {"line": "Error:Printer halted. kill() called!", "reply": {"kind": "error", "code": 0, "message": "Printer halted. kill() called!"}, "canonical": False},
    {"line": "Resend: 5", "reply": {"kind": "resend", "n": 5}, "canonical": True},
    {"line": "rs 5", "reply": {"kind": "resend", "n": 5}, "canonical": False},
    # T: is the hottest sensor; the sensors are S0-S5. Nothing heats: every target is 0.0, and the soft
    # limits are config (M850 thermal.limit.<i>), never a target a host would show (issue 26).
    {"line": "T:31.2 /0.0 S0:24.0 /0.0 S1:31.2 /0.0 S2:23.9 /0.0 S3:24.1 /0.0 S4:22.0 /0.0 S5:-3.5 /0.0",
     "reply": {"kind": "temps", "deciC": [240, 312, 239, 241, 220, -35]}, "canonical": True},
    {"line": "X:10.000 Y:20.500 Z:-0.125 E:0.000 Count X:800 Y:1640 Z:-50",
     "reply": {"kind": "position", "um": [10000, 20500, -125], "steps": [800, 1640, -50]}, "canonical": True},
    {"line": "JOB:running file=PCB.UVJ stop=120/4000 elapsed=12 remaining=345 leds=5",
     "reply": {"kind": "job", "state": "running", "fields": {"file": "PCB.UVJ", "stop": "120/4000", "elapsed": "12", "remaining": "345", "leds": "5"}}, "canonical": True},
    {"line": "JOB:idle", "reply": {"kind": "job", "state": "idle", "fields": {}}, "canonical": True},
    {"line": "PROBE:triggered", "reply": {"kind": "probe", "state": "triggered"}, "canonical": True},
    {"line": "Bed X: 10.000 Y: 20.000 Z: 0.125", "reply": {"kind": "probePoint", "um": [10000, 20000, 125]}, "canonical": True},
    {"line": "TEST:quick x=pass x_steps=16002 y=fail y_steps=15873",
     "reply": {"kind": "test", "mode": "quick", "fields": {"x": "pass", "x_steps": "16002", "y": "fail", "y_steps": "15873"}}, "canonical": True},
    {"line": "FAULT:E31 over-temperature T3 71.2", "reply": {"kind": "fault", "code": 31, "message": "over-temperature T3 71.2"}, "canonical": True},
    {"line": "echo:Done saving file.", "reply": {"kind": "echo", "text": "Done saving file."}, "canonical": True},
    {"line": "echo:leveling on", "reply": {"kind": "echo", "text": "leveling on"}, "canonical": True},
    {"line": "busy: processing", "reply": {"kind": "busy"}, "canonical": True},
    {"line": "start", "reply": {"kind": "start"}, "canonical": True},
    {"line": "FIRMWARE_NAME:UVExposure 0.1.0 (Mega) PROTOCOL_VERSION:1 MACHINE_TYPE:UV-LED exposure printer LEDS:4 SENSORS:6",
     "reply": {"kind": "firmware", "name": "UVExposure 0.1.0 (Mega)", "protocol": 1}, "canonical": True},
    {"line": "Cap:RX_WINDOW:4", "reply": {"kind": "cap", "name": "RX_WINDOW", "value": 4}, "canonical": True},
    {"line": "MESH:row 0 0.010 -0.020 0.000", "reply": {"kind": "other", "text": "MESH:row 0 0.010 -0.020 0.000"}, "canonical": False},
    # Dose reports (mega.md "Dose reports"): a stop, a pass's program, a cut stop with what it was to
    # give and its exposure again, every number at its widest.
    {"line": "DOSE:stop=12 prog=0 exp=345 on=40200,40000,0,0",
     "reply": dose(12, 0, 345, [40200, 40000, 0, 0]), "canonical": True},
    {"line": "DOSE:stop=7 prog=3 exp=19 on=14000,0,30011,2",
     "reply": dose(7, 3, 19, [14000, 0, 30011, 2]), "canonical": True},
    {"line": "DOSE:stop=40 prog=0 exp=81 on=1200,0,0,0 plan=90000,0,0,0 cut=1",
     "reply": dose(40, 0, 81, [1200, 0, 0, 0], plan=[90000, 0, 0, 0], cut=True), "canonical": True},
    {"line": "DOSE:stop=40 prog=0 exp=82 on=90000,0,0,0 again=1",
     "reply": dose(40, 0, 82, [90000, 0, 0, 0], again=True), "canonical": True},
    {"line": "DOSE:stop=4294967295 prog=65535 exp=4294967295 on=4294967295,4294967295,4294967295,4294967295"
             " plan=4294967295,4294967295,4294967295,4294967295 cut=1 again=1",
     "reply": dose(4294967295, 65535, 4294967295, [4294967295] * 4, plan=[4294967295] * 4, cut=True, again=True), "canonical": True},
    {"line": "DOSE:stop=007 prog=0 exp=1 on=0,0,0,0", "reply": dose(7, 0, 1, [0, 0, 0, 0]), "canonical": False},
]
bad_reports = [
    {"line": "T:31.2 /0.0 S0:24.0 /0.0", "why": "fewer than six sensors"},
    {"line": "T:31.2 /0.0 S0:24.0 /60.0 S1:31.2 /60.0 S2:23.9 /60.0 S3:24.1 /60.0 S4:22.0 /55.0 S5:-3.5 /55.0",
     "why": "the soft limits as the sensors' targets (before issue 26)"},
    {"line": "T:31.2 /60.0 T0:24.0 /60.0 T1:31.2 /60.0 T2:23.9 /60.0 T3:24.1 /60.0 T4:22.0 /55.0 T5:-3.5 /55.0", "why": "sensors as hotends with their limits as targets (before issue 16)"},
    {"line": "X:10.000 Y:20.500", "why": "no Z"},
    {"line": "Resend: x", "why": "not a number"},
    {"line": "DOSE:stop=12 prog=0 exp=345 on=40210,39988,0", "why": "three LEDs"},
    {"line": "DOSE:stop=12 prog=0 exp=0 on=1,2,3,4", "why": "exposure 0 (no record is numbered 0)"},
    {"line": "DOSE:stop=12 prog=65536 exp=3 on=1,2,3,4", "why": "a program past 65535"},
    {"line": "DOSE:stop=12 prog=0 exp=3 on=4294967296,2,3,4", "why": "an on-time past 2^32 - 1"},
    {"line": "DOSE:stop=12 exp=3 prog=0 on=1,2,3,4", "why": "fields out of order"},
    {"line": "DOSE:stop=12 prog=0 exp=3 on=1,2,3,4 cut=0", "why": "a flag that is not 1"},
    {"line": "DOSE:stop=12 prog=0 exp=3 on=1,2,3,4 again=1 cut=1", "why": "flags out of order"},
    {"line": "DOSE:stop=12 prog=0 exp=3 on=1,2,3,4 plan=1,2", "why": "a plan of two LEDs"},
    {"line": "DOSE:stop=12 prog=0 exp=3 on=1,2,3,4 ", "why": "a trailing space"},
]
write("mega.json", {
    "link": "mega", "version": 1,
    "maxLine": 96, "window": 8, "movesFree": 8,
    "frames": frames, "frameErrors": frame_errors,
    "commands": commands, "sessions": sessions,
    "replies": replies, "badReplies": bad_reports,
})

# ---------------------------------------------------------------- Job format
def segments(row):
    out, c, n = [], 0, len(row)
    while c < n:
        if row[c] == 0:
            c += 1
            continue
        start = end = c
        while True:
            nxt = end + 1
            while nxt < n and row[nxt] == 0:
                nxt += 1
            if nxt < n and nxt - end - 1 <= 4 and nxt - start + 1 <= 32:
                end = nxt
            else:
                break
        out.append((start, row[start:end + 1]))
        c = end + 1
    return out


def run_tokens(row):
    """Maximal runs of equal cells from the first to the last non-zero cell: runs of 4 or more are
    (col, n, value) run tokens, shorter ones join into (col, [cells]) literal tokens."""
    nz = [i for i, v in enumerate(row) if v]
    if not nz:
        return []
    out, c, last = [], nz[0], nz[-1]
    while c <= last:
        e = c
        while e + 1 <= last and row[e + 1] == row[c]:
            e += 1
        if e - c + 1 >= 4:
            out.append((c, e - c + 1, row[c]))
        elif out and len(out[-1]) == 2:
            out[-1][1].extend(row[c:e + 1])
        else:
            out.append((c, list(row[c:e + 1])))
        c = e + 1
    return out


def run_records(r, row, limit=76):
    """Format 2's `rl` records of a row (job.md "Run-length rows"), filled greedily to `limit` bytes."""
    text = lambda t: f"{t[1]}x{t[2]:02x}" if len(t) == 3 else "".join(f"{v:02x}" for v in t[1])
    zero_run = lambda t: len(t) == 3 and t[2] == 0
    out, parts = [], []

    def close():
        while parts and zero_run(parts[-1]):
            parts.pop()
        if parts:
            out.append(f"rl {r} {parts[0][0]} " + " ".join(text(t) for t in parts))
        parts.clear()

    for t in run_tokens(row):
        while True:
            if not parts and zero_run(t):
                break
            head = f"rl {r} {(parts[0] if parts else t)[0]}"
            used = len(head + "".join(" " + text(p) for p in parts))
            if used + 1 + len(text(t)) <= limit:
                parts.append(t)
                break
            room = (limit - used - 1) // 2
            if len(t) == 2 and room >= 1:
                parts.append((t[0], t[1][:room]))
                t = (t[0] + room, t[1][room:])
            close()
    close()
    return out


def row_records(r, row, fmt):
    seg = [f"r {r} {col} " + "".join(f"{v:02x}" for v in cells) for col, cells in segments(row)]
    if fmt == 1 or not seg:
        return seg
    runs = run_records(r, row)
    size = lambda recs: sum(len(x) + 1 for x in recs)
    return runs if size(runs) < size(seg) else seg


def job_text(job, fmt=1):
    d, l = job["dose"], job["leds"]
    lines = [f"uvj {fmt}",
             f"grid {job['grid']['cols']} {job['grid']['rows']}",
             f"pitch {job['pitchUm']['x']} {job['pitchUm']['y']}",
             f"origin {job['originUm']['x']} {job['originUm']['y']}",
             "map linear" if d["map"] == "linear" else f"map threshold {d['level']}",
             f"full {d['fullUs']}" if "fullUs" in d else
             "target " + " ".join(str(v) for v in [d["targetUJcm2"]] + d["irradianceUWcm2"]),
             "gain " + " ".join(str(g) for g in l.get("gainPermille", [1000] * 4)),
             "thermal {} {}".format(job.get("thermal", {}).get("coeffCentiPctPerC", 0), job.get("thermal", {}).get("refDeciC", 250)),
             "leds " + " ".join(f"{dx} {dy}" for dx, dy in l["offsets"]),
             f"strategy {job['strategy']['name']} {job['strategy'].get('seed', 0) if job['strategy']['name'] == 'random' else 0}"]
    for r, row in enumerate(job["gridData"]):
        lines.extend(row_records(r, row, fmt))
    body = "".join(x + "\n" for x in lines)
    crc = zlib.crc32(body.encode("ascii")) & 0xFFFFFFFF
    return body + f"end {crc:08x}\n", f"{crc:08x}"


def base_job(**over):
    job = {
        "grid": {"cols": 4, "rows": 2}, "pitchUm": {"x": 100, "y": 100}, "originUm": {"x": 10000, "y": 10000},
        "dose": {"map": "threshold", "level": 128, "fullUs": 4000},
        "leds": {"offsets": [[0, 0], [0, 1], [0, 2], [0, 3]]},
        "strategy": {"name": "serpentine"},
        "gridData": [[0, 255, 255, 0], [0, 0, 128, 0]],
    }
    job.update(over)
    return job


def gap_row():
    row = [0] * 80
    for c in [3, 8, 9, 14, 19, 20, 21, 22, 23, 24, 25, 26, 27, 28, 29, 30, 31, 32, 33, 34, 35, 36, 37, 38, 39, 40, 41, 42, 43, 44, 45, 46, 60, 79]:
        row[c] = (c * 37) % 255 + 1
    return row


jobs = [
    {"name": "seed-like two-row threshold job", "job": base_job()},
    {"name": "all-zero grid has no records", "job": base_job(gridData=[[0, 0, 0, 0], [0, 0, 0, 0]])},
    {"name": "linear map, gains, thermal, target dose",
     "job": base_job(grid={"cols": 3, "rows": 3}, pitchUm={"x": 50, "y": 75}, originUm={"x": 0, "y": 12345},
                     dose={"map": "linear", "targetUJcm2": 150000, "irradianceUWcm2": [30000, 31000, 29500, 30500]},
                     leds={"offsets": [[0, 0], [0, 10], [0, 20], [0, 30]], "gainPermille": [1000, 980, 1020, 1005]},
                     thermal={"coeffCentiPctPerC": -35, "refDeciC": 250},
                     strategy={"name": "random", "seed": 4294967295},
                     gridData=[[1, 2, 3], [0, 0, 0], [255, 0, 17]])},
    {"name": "gaps of 4 merge, gaps of 5 split, 32-cell cap",
     "job": base_job(grid={"cols": 80, "rows": 1}, leds={"offsets": [[0, 0], [0, 0], [-3, 0], [4096, -4096]]},
                     strategy={"name": "shortest"}, gridData=[gap_row()])},
    {"name": "raster, full row of 40",
     "job": base_job(grid={"cols": 40, "rows": 2}, dose={"map": "linear", "fullUs": 10000000},
                     strategy={"name": "raster"}, gridData=[[255] * 40, [0] * 39 + [1]])},
    # Exposure on the move (planner.md "Scan mode"): 1-cell tracks and gray pads, seed written as 0.
    {"name": "scan, tracks and gray pads",
     "job": base_job(grid={"cols": 12, "rows": 3}, dose={"map": "linear", "fullUs": 4000},
                     leds={"offsets": [[0, 0], [0, 1], [0, 2], [0, 3]]}, strategy={"name": "scan"},
                     gridData=[[255, 0, 255, 0, 0, 128, 128, 128, 0, 255, 0, 255],
                               [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0],
                               [255, 255, 255, 255, 0, 64, 0, 0, 200, 200, 0, 1]])},
]
# Format 2 (job.md "Run-length rows"): rows written as `rl` records where those are shorter.
def pcb_row(cols, seed):
    row, x = [0] * cols, seed
    for c in range(cols):
        x = (x * 1103515245 + 12345) & 0x7FFFFFFF
        row[c] = 255 if (c // (6 + (x >> 20) % 9)) % 3 == 0 else 0
    return row


jobs += [
    {"name": "format 2: a filled row as one run, a gray ramp stays r", "format": 2,
     "job": base_job(grid={"cols": 600, "rows": 3}, gridData=[[255] * 600, [0] * 10 + [255] * 590, [(c * 7) % 256 for c in range(600)]])},
    {"name": "format 2: runs, zero runs inside, literals split at 76 bytes", "format": 2,
     "job": base_job(grid={"cols": 300, "rows": 2}, dose={"map": "linear", "fullUs": 4000},
                     gridData=[[0] * 3 + [200] * 4 + [1, 2, 3] + [0] * 50 + [9] * 3 + [0] * 4 + [7] + [(c * 13) % 251 + 1 for c in range(60)] + [0] * 171 + [255],
                               [0] * 300])},
    {"name": "format 2: PCB-like rows, equal lengths keep r", "format": 2,
     "job": base_job(grid={"cols": 120, "rows": 3}, strategy={"name": "raster"},
                     gridData=[pcb_row(120, 1), pcb_row(120, 2), [0] * 5 + [255, 0, 255] + [0] * 112])},
]

# Drawn jobs, seeded: any grid, cell, pitch, origin, dose and order in format 1, and rows of runs of
# every length in format 2. The app's encoder must write each byte for byte, and the firmware's
# verifier must read each back to its cells (the round trip that no single implementation can check).
def drawn_jobs(rng):
    out = []
    for i in range(16):
        cols, rows = rng.randint(1, 40), rng.randint(1, 12)
        name = rng.choice(["raster", "serpentine", "shortest", "random", "scan"])
        strategy = {"name": name, "seed": rng.randint(0, 2**32 - 1)} if name == "random" else {"name": name}
        dose = ({"map": "linear", "fullUs": rng.randint(1, 10_000_000)} if rng.random() < 0.7 else
                {"map": "threshold", "level": rng.randint(1, 255), "fullUs": rng.randint(1, 10_000_000)})
        out.append({"name": f"drawn {i + 1}: {cols}x{rows}, {name}, {dose['map']}", "job": base_job(
            grid={"cols": cols, "rows": rows},
            pitchUm={"x": rng.randint(1, 1000), "y": rng.randint(1, 1000)},
            originUm={"x": rng.randint(0, 200000), "y": rng.randint(0, 200000)},
            dose=dose, leds={"offsets": [[0, 0], [1, 0], [0, 1], [1, 1]]}, strategy=strategy,
            gridData=[[0 if rng.random() < 0.4 else rng.randint(0, 255) for _ in range(cols)] for _ in range(rows)])})
    for i in range(8):
        cols, rows = rng.randint(1, 400), rng.randint(1, 3)

        def run_row():
            row = []
            while len(row) < cols:
                row += [rng.choice([0, 0, 255, 128, 7])] * rng.randint(1, 90)
            return row[:cols]
        out.append({"name": f"drawn runs {i + 1}: {cols}x{rows}", "format": 2, "job": base_job(
            grid={"cols": cols, "rows": rows}, pitchUm={"x": 50, "y": 50}, originUm={"x": 0, "y": 0},
            dose={"map": "linear", "fullUs": 1000}, strategy={"name": "raster"}, gridData=[run_row() for _ in range(rows)])})
    return out


jobs += drawn_jobs(random.Random(38))
for j in jobs:
    j["text"], j["crc"] = job_text(j["job"], j.get("format", 1))

good = jobs[0]["text"]
good_lines = good.split("\n")[:-1]


def rebuild(lines):
    """Rejoin records and recompute the end CRC so only the named fault is present."""
    body = "".join(x + "\n" for x in lines if not x.startswith("end "))
    crc = zlib.crc32(body.encode("latin-1")) & 0xFFFFFFFF
    return body + f"end {crc:08x}\n"


def replace(i, new):
    ls = list(good_lines)
    ls[i] = new
    return rebuild(ls)


def drop(i):
    ls = list(good_lines)
    del ls[i]
    return rebuild(ls)


invalid_jobs = [
    {"why": "hash mismatch", "text": good[:-3] + ("00\n" if not good.endswith("00\n") else "11\n"), "error": 24},
    {"why": "missing end", "text": "".join(x + "\n" for x in good_lines[:-1]), "error": 25},
    {"why": "bytes after end", "text": good + "r 0 0 ff\n", "error": 25},
    {"why": "unterminated last line", "text": good[:-1], "error": 25},
    {"why": "wrong version", "text": replace(0, "uvj 3"), "error": 23},
    {"why": "version 0", "text": replace(0, "uvj 0"), "error": 23},
    {"why": "rl record in a format 1 job", "text": replace(10, "rl 0 1 ffff"), "error": 23},
    {"why": "header out of order", "text": rebuild([good_lines[0], good_lines[2], good_lines[1]] + good_lines[3:]), "error": 23},
    {"why": "missing header record", "text": drop(6), "error": 23},
    {"why": "grid too large", "text": replace(1, "grid 4097 2"), "error": 23},
    {"why": "grid zero", "text": replace(1, "grid 0 2"), "error": 23},
    {"why": "leading zero", "text": replace(2, "pitch 0100 100"), "error": 23},
    {"why": "double space", "text": replace(2, "pitch 100  100"), "error": 23},
    {"why": "trailing space", "text": replace(2, "pitch 100 100 "), "error": 23},
    {"why": "threshold level 0", "text": replace(4, "map threshold 0"), "error": 23},
    {"why": "linear with a level", "text": replace(4, "map linear 128"), "error": 23},
    {"why": "full over cap", "text": replace(5, "full 10000001"), "error": 23},
    {"why": "target with three irradiances", "text": replace(5, "target 100 1 1 1"), "error": 23},
    {"why": "gain zero", "text": replace(6, "gain 0 1000 1000 1000"), "error": 23},
    {"why": "unknown strategy", "text": replace(9, "strategy spiral 0"), "error": 23},
    {"why": "seed on a non-random strategy", "text": replace(9, "strategy serpentine 7"), "error": 23},
    {"why": "seed on scan", "text": replace(9, "strategy scan 7"), "error": 23},
    {"why": "scan misspelt", "text": replace(9, "strategy Scan 0"), "error": 23},
    {"why": "segment past the grid", "text": replace(10, "r 0 3 ffff"), "error": 23},
    {"why": "row past the grid", "text": replace(11, "r 2 2 80"), "error": 23},
    {"why": "segments out of order", "text": rebuild(good_lines[:10] + [good_lines[11], good_lines[10]]), "error": 23},
    {"why": "overlapping segments", "text": rebuild(good_lines[:11] + ["r 0 2 ff"] + good_lines[11:]), "error": 23},
    {"why": "odd hex length", "text": replace(10, "r 0 1 fff"), "error": 23},
    {"why": "upper-case hex", "text": replace(10, "r 0 1 FFFF"), "error": 23},
    {"why": "segment over 32 cells", "text": replace(10, "r 0 1 " + "ff" * 33), "error": 23},
    {"why": "empty segment", "text": replace(10, "r 0 1 "), "error": 23},
    {"why": "unknown record", "text": rebuild(good_lines[:10] + ["z 1"] + good_lines[10:]), "error": 23},
    {"why": "header after data", "text": rebuild(good_lines[:11] + ["gain 1000 1000 1000 1000"] + good_lines[11:]), "error": 23},
    {"why": "crc not 8 hex digits", "text": "".join(x + "\n" for x in good_lines[:-1]) + "end 1234\n", "error": 23},
]
v2_lines = ["uvj 2"] + good_lines[1:10] + ["rl 0 1 ffff", "r 1 2 80"]


def v2(i, new):
    ls = list(v2_lines)
    if new is None:
        del ls[i]
    else:
        ls[i] = new
    return rebuild(ls)


invalid_jobs += [
    {"why": "format 2 job with a run and a literal verifies", "text": v2(10, "rl 0 0 00ff ff"), "error": 0},
    {"why": "rl run of 3 (a run token holds 4 or more)", "text": v2(10, "rl 0 0 3xff"), "error": 23},
    {"why": "rl run past the grid", "text": v2(10, "rl 0 1 4xff"), "error": 23},
    {"why": "rl run with a leading zero", "text": rebuild(["uvj 2", "grid 9 2"] + v2_lines[2:10] + ["rl 0 0 04xff"]), "error": 23},
    {"why": "rl run with a count over 4096", "text": rebuild(["uvj 2", "grid 4096 2"] + v2_lines[2:10] + ["rl 0 0 4097xff"]), "error": 23},
    {"why": "rl run value of one digit", "text": v2(10, "rl 0 0 4xf"), "error": 23},
    {"why": "rl run value upper-case", "text": v2(10, "rl 0 0 4xFF"), "error": 23},
    {"why": "rl run without a count", "text": v2(10, "rl 0 0 xff"), "error": 23},
    {"why": "rl odd literal", "text": v2(10, "rl 0 0 fff"), "error": 23},
    {"why": "rl without tokens", "text": v2(10, "rl 0 0"), "error": 23},
    {"why": "rl double space between tokens", "text": v2(10, "rl 0 0 ff  ff"), "error": 23},
    {"why": "rl trailing space", "text": v2(10, "rl 0 0 ffff "), "error": 23},
    {"why": "rl over 76 bytes", "text": rebuild(["uvj 2", "grid 100 2"] + v2_lines[2:10] + ["rl 0 0 " + "ff" * 35]), "error": 23},
    {"why": "rl of 76 bytes verifies", "text": rebuild(["uvj 2", "grid 100 2"] + v2_lines[2:10] + ["rl 0 10 " + "ff" * 34]), "error": 0},
    {"why": "rl overlapping an r record", "text": v2(11, "rl 0 3 4x80"), "error": 23},
    {"why": "rl out of order", "text": rebuild(v2_lines[:10] + ["r 1 2 80", "rl 0 1 ffff"]), "error": 23},
    {"why": "format 2 truncated inside rl records", "text": "".join(x + "\n" for x in v2_lines[:11]), "error": 25},
    {"why": "format 2 hash over the rl record", "text": v2(10, "rl 0 1 ffff")[:-3] + "00\n", "error": 24},
]
write("job.json", {"version": 1, "maxCellsPerRecord": 32, "maxGap": 4, "jobs": jobs, "invalid": invalid_jobs})

# ---------------------------------------------------------------- ESP API
def body(obj):
    return json.dumps(obj, separators=(",", ":"))


def drop_key(obj, *path):
    obj = json.loads(json.dumps(obj))
    cur = obj
    for k in path[:-1]:
        cur = cur[k]
    del cur[path[-1]]
    return obj


def set_key(obj, value, *path):
    obj = json.loads(json.dumps(obj))
    cur = obj
    for k in path[:-1]:
        cur = cur[k]
    cur[path[-1]] = value
    return obj


bj = base_job()
esp_requests = [
    {"name": "valid job", "body": body(bj), "status": 202, "text": job_text(bj)[0]},
    {"name": "valid target-dose job", "body": body(jobs[2]["job"]), "status": 202, "text": jobs[2]["text"]},
    {"name": "valid scan job", "body": body(jobs[5]["job"]), "status": 202, "text": jobs[5]["text"]},
    {"name": "not JSON", "body": "{\"grid\":", "status": 400, "error": "bad_json"},
    {"name": "not an object", "body": "[1,2]", "status": 400, "error": "bad_job", "path": ""},
    {"name": "missing gridData", "body": body(drop_key(bj, "gridData")), "status": 400, "error": "bad_job", "path": "/gridData"},
    {"name": "unknown field", "body": body(set_key(bj, 1, "colour")), "status": 400, "error": "bad_job", "path": "/colour"},
    {"name": "cell over 255", "body": body(set_key(bj, [[0, 256, 0, 0], [0, 0, 0, 0]], "gridData")), "status": 400, "error": "bad_job", "path": "/gridData/0/1"},
    {"name": "cell not an integer", "body": body(set_key(bj, [[0, 1.5, 0, 0], [0, 0, 0, 0]], "gridData")), "status": 400, "error": "bad_job", "path": "/gridData/0/1"},
    {"name": "row of the wrong length", "body": body(set_key(bj, [[0, 1, 0, 0], [0, 0, 0]], "gridData")), "status": 400, "error": "bad_job", "path": "/gridData/1"},
    {"name": "too few rows", "body": body(set_key(bj, [[0, 1, 0, 0]], "gridData")), "status": 400, "error": "bad_job", "path": "/gridData"},
    {"name": "threshold without level", "body": body(drop_key(bj, "dose", "level")), "status": 400, "error": "bad_job", "path": "/dose/level"},
    {"name": "both full and target", "body": body(set_key(bj, 5, "dose", "targetUJcm2")), "status": 400, "error": "bad_job", "path": "/dose"},
    {"name": "cols beyond any integer", "body": body(bj).replace('"cols":4', '"cols":1e300', 1), "status": 400, "error": "bad_job", "path": "/grid/cols"},
    {"name": "cols beyond 64 bits", "body": body(set_key(bj, 2**64, "grid", "cols")), "status": 400, "error": "bad_job", "path": "/grid/cols"},
    {"name": "pitch zero", "body": body(set_key(bj, 0, "pitchUm", "x")), "status": 400, "error": "bad_job", "path": "/pitchUm/x"},
    {"name": "three LED offsets", "body": body(set_key(bj, [[0, 0], [0, 1], [0, 2]], "leds", "offsets")), "status": 400, "error": "bad_job", "path": "/leds/offsets"},
    {"name": "unknown strategy", "body": body(set_key(bj, "spiral", "strategy", "name")), "status": 400, "error": "bad_job", "path": "/strategy/name"},
    {"name": "bad name", "body": body(set_key(bj, "a/b", "name")), "status": 400, "error": "bad_job", "path": "/name"},
    {"name": "grid over 262144 cells", "body": body(set_key(bj, {"cols": 1024, "rows": 257}, "grid")), "status": 413, "error": "too_large"},
    # "paced" rides beside the job (mega.md "Pacing"): the same text, started with M24 P1.
    {"name": "paced job", "body": body(set_key(bj, True, "paced")), "status": 202, "text": job_text(bj)[0], "paced": True},
    {"name": "paced false", "body": body(set_key(bj, False, "paced")), "status": 202, "text": job_text(bj)[0], "paced": False},
    {"name": "paced as a string", "body": body(set_key(bj, "yes", "paced")), "status": 400, "error": "bad_job", "path": "/paced"},
    {"name": "paced as a number", "body": body(set_key(bj, 1, "paced")), "status": 400, "error": "bad_job", "path": "/paced"},
    {"name": "paced null", "body": body(set_key(bj, None, "paced")), "status": 400, "error": "bad_job", "path": "/paced"},
    {"name": "paced is checked before gridData's rows",
     "body": body(set_key(set_key(bj, [[0, 1, 0, 0], [0, 0, 0]], "gridData"), "yes", "paced")), "status": 400, "error": "bad_job", "path": "/paced"},
]
for r in esp_requests:  # an accepted request says whether it runs paced
    if r["status"] == 202:
        r.setdefault("paced", False)
write("esp.json", {"version": 1, "maxBody": 1200000, "maxCells": 262144, "requests": esp_requests})
# ---------------------------------------------------------------- Mesh interpolation (planner.md)
def mesh_z(m, x, y):
    """Exact integer reference of protocol/planner.md "Mesh interpolation"."""
    cx = min(max(x, m["x0"]), m["x0"] + (m["nx"] - 1) * m["dx"])
    cy = min(max(y, m["y0"]), m["y0"] + (m["ny"] - 1) * m["dy"])
    i = min((cx - m["x0"]) // m["dx"], m["nx"] - 2)
    j = min((cy - m["y0"]) // m["dy"], m["ny"] - 2)
    u = cx - (m["x0"] + i * m["dx"])
    w = cy - (m["y0"] + j * m["dy"])
    z, dx, dy = m["z"], m["dx"], m["dy"]
    n = (z[j][i] * (dx - u) * (dy - w) + z[j][i + 1] * u * (dy - w)
         + z[j + 1][i] * (dx - u) * w + z[j + 1][i + 1] * u * w)
    d = dx * dy
    q, r = divmod(abs(n), d)
    if 2 * r >= d:
        q += 1
    return -q if n < 0 else q


meshes = [
    {"name": "3x3 tilt", "mesh": {"nx": 3, "ny": 3, "x0": 10000, "y0": 10000, "dx": 90000, "dy": 90000,
                                  "z": [[0, 50, 100], [-30, 20, 70], [-60, -10, 40]]}},
    {"name": "5x4 bumps", "mesh": {"nx": 5, "ny": 4, "x0": 0, "y0": 5000, "dx": 50000, "dy": 60000,
                                   "z": [[12, -7, 33, 0, -120], [5, 5, 5, 5, 5], [-300, 250, -1, 1, 0], [77, -77, 3, -3, 4999]]}},
    {"name": "2x2 smallest", "mesh": {"nx": 2, "ny": 2, "x0": 1000, "y0": 1000, "dx": 3, "dy": 7, "z": [[-5, 5], [5, -5]]}},
    {"name": "9x9 largest", "mesh": {"nx": 9, "ny": 9, "x0": 0, "y0": 0, "dx": 50000, "dy": 50000,
                                     "z": [[(i * 37 + j * 91) % 400 - 200 for i in range(9)] for j in range(9)]}},
]
for m in meshes:
    mm = m["mesh"]
    xs = [mm["x0"] - 5000, mm["x0"], mm["x0"] + mm["dx"] // 3, mm["x0"] + mm["dx"], mm["x0"] + (mm["nx"] - 1) * mm["dx"] - 1,
          mm["x0"] + (mm["nx"] - 1) * mm["dx"], mm["x0"] + (mm["nx"] - 1) * mm["dx"] + 123456]
    ys = [mm["y0"] - 1, mm["y0"] + mm["dy"] // 2 + 1, mm["y0"] + (mm["ny"] - 1) * mm["dy"], mm["y0"] + 999999]
    m["points"] = [[x, y, mesh_z(mm, x, y)] for x in xs for y in ys]
write("mesh.json", {"version": 1, "cases": meshes})


# ---------------------------------------------------------------- Scan programs (nano.md)
MAX_DELTA = (1 << 28) - 1


def check_events(events):
    """CRC-16/CCITT-FALSE over each event's word d*16+m, 4 bytes little-endian."""
    c = 0xFFFF
    for d, m in events:
        for b in ((d << 4) | m).to_bytes(4, "little"):
            c ^= b << 8
            for _ in range(8):
                c = ((c << 1) ^ 0x1021) & 0xFFFF if c & 0x8000 else (c << 1) & 0xFFFF
    return c


def merge(leds):
    """Per-LED [on, off] lists -> (t, state) events, one per distinct switching time."""
    times = sorted({t for iv in leds for a, b in iv for t in (a, b)})
    out = []
    for t in times:
        m = 0
        for k, iv in enumerate(leds):
            if any(a <= t < b for a, b in iv):
                m |= 1 << k
        out.append((t, m))
    return out


def pack_word(w):
    """A B line's packing of the word d*16+m: 5 bits a character, most significant first, '?' + the
    bits, + 32 on every character but the word's last."""
    groups = []
    while True:
        groups.insert(0, w & 31)
        w >>= 5
        if not w:
            break
    return "".join(chr(63 + g + (32 if i < len(groups) - 1 else 0)) for i, g in enumerate(groups))


def program_lines(events, packed=True):
    """Absolute (t, m) events -> the chain's B (or A) and K lines, 64 events a program, 63 bytes a line."""
    lines, programs = [], []
    for i in range(0, len(events), 64):
        programs.append(events[i:i + 64])
    prev = None
    for p_i, prog in enumerate(programs):
        rel = []
        for t, m in prog:
            rel.append((t if prev is None else t - prev, m))
            prev = t
        seq, cur = 0, None
        for d, m in rel:
            item = pack_word(d * 16 + m) if packed else f",{d},{m}"
            if cur is not None and len(cur) + len(item) > 63:
                lines.append(cur)
                cur = None
            if cur is None:
                cur = f"B:{seq}," if packed else f"A:{seq}"
                seq += 1
            cur += item
        lines.append(cur)
        flags = (1 if p_i else 0) | (2 if p_i < len(programs) - 1 else 0)
        lines.append(f"K:{flags},{len(rel)},{check_events(rel)}")
    return lines


def gray_row():
    """A pass as the scan planner lays it out: 2000 us windows, every LED, gray and full cells."""
    W, leds = 2000, [[], [], [], []]
    for k in range(4):
        for j in range(40):
            v = (j * 37 + k * 11) % 7
            if v == 0:
                continue
            t = W if v == 6 else v * 250 + k
            on = j * W + (W - t) // 2
            if leds[k] and leds[k][-1][1] == on:
                leds[k][-1][1] = on + t
            else:
                leds[k].append([on, on + t])
    return leds


program_cases = [
    {"name": "one LED, one cell", "leds": [[[0, 2000]], [], [], []]},
    {"name": "LEDs switching together merge", "leds": [[[995, 1005], [2000, 6000]], [[995, 3000]], [], [[5999, 6000]]]},
    {"name": "a long dark gap", "leds": [[[0, 10], [268435000, 268435100]], [], [], []]},
    {"name": "a pass of gray cells: a chain of programs", "leds": gray_row()},
    {"name": "photo-like: short on-times, many events a line",
     "leds": [[[j * 40 + k, j * 40 + k + 4 + (j * 7 + k) % 13] for j in range(30)] for k in range(4)]},
]
for c in program_cases:
    c["events"] = [[t, m] for t, m in merge(c["leds"])]
    c["lines"] = program_lines(c["events"])  # as the Mega sends them: packed
    c["appendLines"] = program_lines(c["events"], packed=False)  # the same chain in A lines
    assert all(len(l) <= 63 for l in c["lines"] + c["appendLines"])
# Words at the packing's edges, each as a one-event B line.
packed_words = [[w, f"B:0,{pack_word(w)}"] for w in (0, 15, 31, 32, 1023, 1024, 32767, 32768, 2**25 - 1, 2**25, 2**32 - 1)]
program_bad = [
    {"line": "A:0", "why": "no events"},
    {"line": "A:0,1", "why": "half an event"},
    {"line": "A:0,1,16", "why": "state over 15"},
    {"line": "A:0,268435456,1", "why": "delay of 2^28 us"},
    {"line": "A:65536,1,1", "why": "line number over 65535"},
    {"line": "A:0,1,1,", "why": "trailing comma"},
    {"line": "A:0,-1,1", "why": "negative"},
    {"line": "B:0", "why": "packed: no events"},
    {"line": "B:0,", "why": "packed: nothing after the comma"},
    {"line": "B:0?", "why": "packed: no comma"},
    {"line": "B:,?", "why": "packed: no line number"},
    {"line": "B:65536,?", "why": "packed: line number over 65535"},
    {"line": "B:0,_?", "why": "packed: a leading zero group"},
    {"line": "B:0,?a", "why": "packed: the last word unfinished"},
    {"line": "B:0,? ?", "why": "packed: a character below '?'"},
    {"line": "B:0,?,?", "why": "packed: a comma between words"},
    {"line": "B:0,c_____?", "why": "packed: a word of 2^32"},
    {"line": "B:0,b~~~~~~^", "why": "packed: eight characters"},
    {"line": "K:4,1,0", "why": "flags over 3"},
    {"line": "K:0,0,0", "why": "no events"},
    {"line": "K:0,65,0", "why": "over 64 events"},
    {"line": "K:0,1,65536", "why": "check over 16 bits"},
    {"line": "K:0,1", "why": "no check"},
]


def load(events, flags):
    """One program's A line(s) and its K line, events given as (d, m)."""
    body = "".join(f",{d},{m}" for d, m in events)
    return [f"A:0{body}", f"K:{flags},{len(events)},{check_events(events)}"]


def steps(*items):
    """Lines sent and the reply each expects ('' for none); RUN lets the running chain play out."""
    out = []
    for it in items:
        if it == "RUN":
            out.append({"run": True})
        elif isinstance(it, tuple):
            out.append({"send": it[0], "reply": it[1]})
        else:
            out.append({"send": it})
    return out


def packed(events, flags):
    """One program's B line and its K line, events given as (d, m)."""
    body = "".join(pack_word(d * 16 + m) for d, m in events)
    return [f"B:0,{body}", f"K:{flags},{len(events)},{check_events(events)}"]


ONE = [(0, 1), (2000, 0)]
program_sessions = [
    {"name": "a program arms, runs whole, and frees its buffer",
     "steps": steps(load(ONE, 0)[0], (load(ONE, 0)[1], "K:0"), ("Q", "Q:1,1,0"), "G", ("Q", "Q:1,0,1"), "RUN", ("Q", "Q:2,0,2"))},
    {"name": "a chain of two: the continuation follows the first",
     "steps": steps(load([(0, 3), (500, 1)], 2)[0], (load([(0, 3), (500, 1)], 2)[1], "K:0"),
                    load([(700, 0)], 1)[0], (load([(700, 0)], 1)[1], "K:0"), ("Q", "Q:0,2,0"), "G", "RUN", ("Q", "Q:2,0,2"))},
    {"name": "a chain whose continuation never came is cut short",
     "steps": steps(load([(0, 1), (100, 1)], 2)[0], (load([(0, 1), (100, 1)], 2)[1], "K:0"), "G", "RUN", ("Q", "Q:2,0,5"))},
    {"name": "R cuts a running chain and drops the armed ones",
     "steps": steps(load(ONE, 0)[0], (load(ONE, 0)[1], "K:0"), load(ONE, 0)[0], (load(ONE, 0)[1], "K:0"), "G", "R", ("Q", "Q:2,0,3"))},
    {"name": "G with nothing armed is refused",
     "steps": steps("G", ("Q", "Q:2,0,6"))},
    {"name": "every refusal of a seal has its code",
     "steps": steps(("K:0,1,0", "K:1"),
                    "A:0,0,1,5,0", (f"K:0,1,{check_events([(0, 1), (5, 0)])}", "K:2"),
                    "A:0,0,1,5,0", (f"K:0,2,{check_events([(0, 1), (5, 0)]) ^ 1}", "K:2"),
                    load([(0, 1), (5, 2)], 0)[0], (load([(0, 1), (5, 2)], 0)[1], "K:4"),
                    load([(0, 1), (10000001, 0)], 0)[0], (load([(0, 1), (10000001, 0)], 0)[1], "K:3"),
                    load([(5, 0)], 1)[0], (load([(5, 0)], 1)[1], "K:7"),
                    "A:0,0,1", "A:2,5,0", (f"K:0,2,{check_events([(0, 1), (5, 0)])}", "K:1"),
                    "A:0,0,0", *[f"A:{q},10,1,10,0,10,1,10,0,10,1" for q in range(1, 14)], ("K:0,64,0", "K:5"),
                    ("Q", "Q:2,0,0"))},
    {"name": "the cap holds across the chain",
     "steps": steps(load([(0, 1), (6000000, 1)], 2)[0], (load([(0, 1), (6000000, 1)], 2)[1], "K:0"),
                    load([(4000001, 0)], 1)[0], (load([(4000001, 0)], 1)[1], "K:3"),
                    load([(4000000, 0)], 1)[0], (load([(4000000, 0)], 1)[1], "K:0"))},
    {"name": "a packed program arms and runs whole",
     "steps": steps(packed(ONE, 0)[0], (packed(ONE, 0)[1], "K:0"), "G", "RUN", ("Q", "Q:2,0,2"))},
    {"name": "A and B lines load one program together",
     "steps": steps("A:0,0,1", f"B:1,{pack_word(2000 * 16)}", (f"K:0,2,{check_events(ONE)}", "K:0"), ("Q", "Q:1,1,0"))},
    {"name": "a malformed B line latches MALFORMED and spoils the load",
     "steps": steps("B:0,?", "B:1,_?", (f"K:0,2,{check_events(ONE)}", "K:1"), ("E", "E:32"),
                    "B:0,?", "B:2,?", (f"K:0,2,{check_events([(0, 0), (0, 0)])}", "K:1"))},
    {"name": "a B line past 64 events spoils the load",
     "steps": steps("B:0," + "A" * 59, "B:1," + "A" * 6, ("K:0,64,0", "K:5"))},
    {"name": "no third buffer",
     "steps": steps(load(ONE, 0)[0], (load(ONE, 0)[1], "K:0"), load(ONE, 0)[0], (load(ONE, 0)[1], "K:0"),
                    load(ONE, 0)[0], (load(ONE, 0)[1], "K:6"), ("Q", "Q:0,2,0"))},
]
write("nano-program.json", {"version": 1, "maxEvents": 64, "startLeadUs": 1000, "capUs": 10000000,
                            "programs": program_cases, "packedWords": packed_words, "bad": program_bad,
                            "sessions": program_sessions})
print("wrote nano.json mega.json job.json esp.json mesh.json nano-program.json")
