#!/usr/bin/env python3
"""Makes the damaged state files of the corpus from a checkpoint of cases/restart_small.toml.

    python3 make_states.py build/repose

Each file is a real state changed in one way (docs/state-format.md, the version the binary
writes); corpus.txt says what `repose run --restart` must answer. Run again after a change of the
state format. Version 6's checksum needs python3-xxhash (scripts/install-deps.sh).
"""
import os
import struct
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
CASE = os.path.join(HERE, "..", "cases", "restart_small.toml")


def fnv1a(data):
    h = 1469598103934665603
    for b in data:
        h = ((h ^ b) * 1099511628211) & 0xFFFFFFFFFFFFFFFF
    return h


def checksum(data):
    """The checksum a writer ends these bytes with: FNV-1a 64 in version 5, XXH3-64 from 6."""
    if data[:8] == b"REPOSES5":
        return fnv1a(data)
    import xxhash
    return xxhash.xxh3_64_intdigest(data)


def state_of(repose, *sets):
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "s.state")
        args = [repose, "run", CASE, "--backend", "cpu", "--quiet", "--steps", "50", "--out",
                os.path.join(tmp, "o"), "--state-out", path]
        for s in sets:
            args += ["--set", s]
        subprocess.run(args, check=True)
        return open(path, "rb").read()


def forged(data):
    return data[:-8] + struct.pack("<Q", checksum(data[:-8]))


def main():
    good = state_of(sys.argv[1])
    n, c = struct.unpack_from("<II", good, 8)
    pos = 8 + 16 + 16 + 16  # magic, counts, step and time, case hash
    row_start = pos + 5 * 16 * n
    partner = row_start + 4 * (n + 1)
    flipped = bytearray(good)
    flipped[len(good) // 2] ^= 0x10
    files = {
        "flipped_byte.state": bytes(flipped),
        "truncated.state": good[:-100],
        "appended.state": good + bytes(64),
        "other_case.state": state_of(sys.argv[1], "simulation.seed=2"),
        "version4.state": b"REPOSES4" + good[8:40] + good[56:-8],
        "radius_negative.state": forged(good[:pos + 12] + struct.pack("<f", -1.0) + good[pos + 16:]),
    }
    if c > 0:
        files["partner_beyond.state"] = forged(good[:partner] + struct.pack("<I", 0xFFFFFFFF) + good[partner + 4:])
    for name, data in files.items():
        open(os.path.join(HERE, name), "wb").write(data)
    open(os.path.join(HERE, "not_a_state.state"), "w").write("x,y,z,radius\n0,0,0,0.005\n")


if __name__ == "__main__":
    main()
