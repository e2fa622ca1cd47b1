#!/usr/bin/env python3
"""Picks the few inputs of a grown fuzz corpus that are worth committing as a harness's seeds.

libFuzzer's set-cover merge (-set_cover_merge=1) records every feature each input reaches in its
control file. From those, a greedy cover takes, one at a time, the input that adds the most
features not yet reached, until KEEP inputs are taken (named inputs, the hand-written regressions
such as `line-number-at-int32-end` or `seed-…`, are always kept and counted first). It prints the
features the seeds reach against the whole corpus's, so a reader sees what the trim costs.

usage: fuzz-seeds.py HARNESS SEEDS_DIR KEEP CORPUS_DIR [CORPUS_DIR…]
"""
import hashlib
import re
import subprocess
import sys
import tempfile
from pathlib import Path

HASH_NAME = re.compile(r"^[0-9a-f]{40}$")


def features_by_file(harness: str, corpora: list[Path]) -> dict[Path, set[int]]:
    """Each input's features: edges with their hit-count buckets, and compares."""
    with tempfile.TemporaryDirectory() as tmp:
        control = Path(tmp) / "control.txt"
        out = Path(tmp) / "out"
        out.mkdir()
        subprocess.run(
            [harness, "-set_cover_merge=1", f"-merge_control_file={control}", str(out), *map(str, corpora)],
            check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
        )
        lines = control.read_text().splitlines()
    count = int(lines[0])
    files = [Path(p) for p in lines[2:2 + count]]
    found: dict[Path, set[int]] = {}
    for line in lines[2 + count:]:
        if line.startswith("FT "):
            parts = line.split()
            found[files[int(parts[1])]] = {int(f) for f in parts[2:]}
    return found


def edges_reached(harness: str, dirs: list[Path]) -> int:
    """The edges a harness covers after loading DIRS and running nothing new (its INITED line)."""
    run = subprocess.run([harness, "-runs=0", *map(str, dirs)], capture_output=True, text=True)
    inited = re.search(r"INITED cov: (\d+)", run.stderr)
    return int(inited.group(1)) if inited else 0


def greedy_cover(found: dict[Path, set[int]], keep: int) -> list[Path]:
    named = sorted(p for p in found if not HASH_NAME.match(p.name))
    chosen = list(named)
    reached: set[int] = set().union(*(found[p] for p in named)) if named else set()
    rest = {p: f for p, f in found.items() if p not in chosen}
    while len(chosen) < keep and rest:
        best = max(rest, key=lambda p: (len(rest[p] - reached), -p.stat().st_size, p.name))
        if not rest[best] - reached:
            break
        chosen.append(best)
        reached |= rest.pop(best)
    return chosen


def percent(part: set, whole: set) -> str:
    return f"{100 * len(part) / max(1, len(whole)):.1f} %"


def main() -> int:
    if len(sys.argv) < 5:
        print(__doc__, file=sys.stderr)
        return 2
    harness, seeds_dir, keep = sys.argv[1], Path(sys.argv[2]), int(sys.argv[3])
    corpora = [Path(d) for d in sys.argv[4:] if Path(d).is_dir()]
    found = features_by_file(harness, corpora)
    chosen = greedy_cover(found, keep)
    everything = set().union(*found.values()) if found else set()
    reached = set().union(*(found[p] for p in chosen)) if chosen else set()
    # Read before the seeds folder is emptied: it may be one of the corpora.
    picked = {p.name if not HASH_NAME.match(p.name) else hashlib.sha1(p.read_bytes()).hexdigest(): p.read_bytes()
              for p in chosen}
    seeds_dir.mkdir(parents=True, exist_ok=True)
    for old in seeds_dir.iterdir():
        old.unlink()
    for name, data in picked.items():
        (seeds_dir / name).write_bytes(data)
    seed_edges, all_edges = edges_reached(harness, [seeds_dir]), edges_reached(harness, corpora)
    print(f"[fuzz seeds] {seeds_dir.name}: {len(chosen)} of {len(found)} inputs reach "
          f"{seed_edges} of {all_edges} edges ({100 * seed_edges / max(1, all_edges):.1f} %) and "
          f"{len(reached)} of {len(everything)} features ({percent(reached, everything)})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
