"""Hostile inputs through the command line (issue 48): every case must end in one error line
(exit 2), never a traceback, an internal error, a hang or a partial output file.

Each case is a command run in a fresh folder with a time limit. Counted:

* ``handled``: exit status 2 with a one-line ``optplan: error: ...`` message (or success where
  the input is valid but odd), and no output file that is partial;
* ``traceback``: a Python traceback or ``internal error`` on stderr;
* ``hang``: the time limit was reached;
* ``partial``: an output file was left although the command failed.

    python benchmarks/hostile_inputs.py            # every case
    python benchmarks/hostile_inputs.py --list     # the cases' names
"""
from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROS = "resolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
SCEN = "map: [[0, 0, 0], [0, 0, 0], [0, 0, 0]]\nstart: [0.5, 0.5, 0]\ngoal: [2.5, 2.5]\n"
SPEC = "kind: plan\nmaps: [chen2025_20]\nalgorithms: [gwo]\nparams: {pop: 10, iters: 5}\nruns: 2\n"


def _setup(d: Path) -> None:
    """The files the cases point at."""
    for name in ("fifo.pgm", "fifo.yaml", "fifo.json", "fifo.npy", "fifo.map", "fifo.txt", "fifo_scen.yaml",
                 "fifo_spec.yaml"):
        os.mkfifo(d / name)
    os.symlink("/dev/urandom", d / "urandom.pgm")
    os.symlink("/dev/zero", d / "zero.map")
    (d / "img_fifo.yaml").write_text("image: fifo.pgm\n" + ROS)
    (d / "img_zero.yaml").write_text("image: /dev/zero\n" + ROS)
    (d / "img_zero_pgm.yaml").write_text("image: urandom.pgm\n" + ROS)
    (d / "img_nul.yaml").write_text('image: "a\\0b.pgm"\n' + ROS)
    (d / "m.pgm").write_bytes(b"P2\n3 2\n255\n254 0 254\n254 254 254\n")
    (d / "res_true.yaml").write_text("image: m.pgm\n" + ROS.replace("resolution: 0.05", "resolution: true"))
    (d / "res_zero.yaml").write_text("image: m.pgm\n" + ROS.replace("resolution: 0.05", "resolution: 0"))
    (d / "dup.yaml").write_text("image: m.pgm\nimage: m.pgm\n" + ROS)
    (d / "short.map").write_text("type octile\nheight 2\nwidth 3\nmap\n...\n...\n...\n")
    (d / "long.map").write_text("type octile\nheight 4\nwidth 3\nmap\n...\n...\n")
    (d / "huge.map").write_text("type octile\nheight 100000\nwidth 100000\nmap\n...\n")
    (d / "bad_pgm.pgm").write_bytes(b"P5\n99999 99999\n255\n\x00")
    (d / "bin.txt").write_bytes(b"0 0\x00 1\n")
    (d / "ragged.txt").write_text("0 0 1\n0 1\n")
    (d / "twos.txt").write_text("0 2\n0 0\n")
    (d / "big_num.yaml").write_text(SCEN + f"sensor_range: {'9' * 400}\n")
    (d / "dup_scen.yaml").write_text(SCEN + "goal: [1.5, 1.5]\n")
    (d / "bool_scen.yaml").write_text(SCEN + "dt: true\n")
    (d / "nan_scen.yaml").write_text(SCEN + "dt: .nan\n")
    (d / "bomb.yaml").write_text("a: &a [x, x, x, x, x, x, x, x, x]\nb: &b [*a, *a, *a, *a, *a, *a, *a, *a, *a]\n"
                                 "c: &c [*b, *b, *b, *b, *b, *b, *b, *b, *b]\nd: &d [*c, *c, *c, *c, *c, *c, *c, *c]\n"
                                 "e: &e [*d, *d, *d, *d, *d, *d, *d, *d, *d]\nf: &f [*e, *e, *e, *e, *e, *e, *e, *e]\n"
                                 "g: [*f, *f, *f, *f, *f, *f, *f, *f, *f]\n")
    (d / "python_tag.yaml").write_text(SCEN + "robot: !!python/object/apply:os.system ['echo pwned']\n")
    (d / "spec.yaml").write_text(SPEC)
    (d / "spec_nan.yaml").write_text(SPEC.replace("iters: 5", "iters: 5, clearance: .nan"))
    (d / "spec_dup.yaml").write_text(SPEC + "runs: 3\n")
    (d / "wall.txt").write_text("0 0 1 0 0\n0 0 1 0 0\n")
    (d / "spec_unreach.yaml").write_text("kind: plan\nmaps: [{name: w, map: wall.txt, start: [0.5, 0.5], goal: "
                                         "[4.5, 0.5]}]\nalgorithms: [astar]\nruns: 1\n")
    import sqlite3

    conn = sqlite3.connect(d / "foreign.sqlite")
    conn.execute("CREATE TABLE people (name TEXT)")
    conn.commit()
    conn.close()
    (d / "not_sqlite.sqlite").write_text("hello")


PLAN = ["--start", "0.5", "0.5", "--goal", "1.5", "0.5"]
# (name, argv, outputs that must not be left behind on failure)
CASES = [
    *[(f"fifo{s}", ["plan", f"fifo{s}", *PLAN], []) for s in (".pgm", ".yaml", ".json", ".npy", ".map", ".txt")],
    ("yaml image: fifo", ["plan", "img_fifo.yaml", *PLAN], []),
    ("yaml image: /dev/zero", ["plan", "img_zero.yaml", *PLAN], []),
    ("yaml image: symlink to /dev/urandom", ["plan", "img_zero_pgm.yaml", *PLAN], []),
    ("yaml image: NUL in the name", ["plan", "img_nul.yaml", *PLAN], []),
    ("/dev/zero as a map", ["plan", "/dev/zero", *PLAN], []),
    ("symlink to /dev/urandom", ["plan", "urandom.pgm", *PLAN], []),
    ("symlink .map to /dev/zero", ["plan", "zero.map", *PLAN], []),
    ("resolution: true", ["plan", "res_true.yaml", *PLAN], []),
    ("resolution: 0", ["plan", "res_zero.yaml", *PLAN], []),
    ("duplicate key in map yaml", ["plan", "dup.yaml", *PLAN], []),
    (".map with more rows than its header", ["plan", "short.map", *PLAN], []),
    (".map with fewer rows than its header", ["plan", "long.map", *PLAN], []),
    (".map header of 10^10 cells", ["plan", "huge.map", *PLAN], []),
    ("PGM header of 10^10 pixels", ["plan", "bad_pgm.pgm", *PLAN], []),
    ("binary .txt", ["plan", "bin.txt", *PLAN], []),
    ("ragged .txt", ["plan", "ragged.txt", *PLAN], []),
    ("a 2 in a .txt", ["plan", "twos.txt", *PLAN], []),
    ("missing map", ["plan", "nosuch.map", *PLAN], []),
    ("folder as a map", ["plan", ".", *PLAN], []),
    ("start outside the map", ["plan", "chen2025_20", "--start", "-5", "0", "--goal", "1.5", "1.5"], []),
    ("start = nan", ["plan", "chen2025_20", "--start", "nan", "0", "--goal", "1.5", "1.5"], []),
    ("pop = 0", ["plan", "chen2025_20", "--algo", "gwo", "--pop", "0"], []),
    ("clearance = 1e400", ["plan", "chen2025_20", "--algo", "astar", "--clearance", "1e400"], []),
    ("unknown algorithm", ["plan", "chen2025_20", "--algo", "nosuch"], []),
    ("--plot .xyz", ["plan", "chen2025_20", "--algo", "astar", "--plot", "p.xyz"], ["p.xyz"]),
    ("--plot into a file's path", ["plan", "chen2025_20", "--algo", "astar", "--plot", "spec.yaml/p.png"], []),
    ("--export into a missing folder's file", ["plan", "chen2025_20", "--algo", "astar", "--export",
                                               "/proc/nope/x.csv"], []),
    ("scenario: FIFO", ["simulate", "fifo_scen.yaml"], []),
    ("scenario: 400-digit number", ["simulate", "big_num.yaml"], []),
    ("scenario: duplicate key", ["simulate", "dup_scen.yaml"], []),
    ("scenario: dt: true", ["simulate", "bool_scen.yaml"], []),
    ("scenario: dt: .nan", ["simulate", "nan_scen.yaml"], []),
    ("scenario: YAML bomb", ["simulate", "bomb.yaml"], []),
    ("scenario: !!python tag", ["simulate", "python_tag.yaml"], []),
    ("simulate --gif .mp4", ["simulate", "hou2024_dynamic1", "--gif", "x.mp4"], ["x.mp4"]),
    ("spec: FIFO", ["bench", "fifo_spec.yaml", "--db", "r1.sqlite"], []),
    ("spec: clearance .nan", ["bench", "spec_nan.yaml", "--db", "r2.sqlite"], ["r2.sqlite"]),
    ("spec: duplicate key", ["bench", "spec_dup.yaml", "--db", "r3.sqlite"], ["r3.sqlite"]),
    ("spec: unreachable goal", ["bench", "spec_unreach.yaml", "--db", "r4.sqlite"], ["r4.sqlite"]),
    ("bench --layout foo", ["bench", "spec.yaml", "--db", "r5.sqlite", "--layout", "foo"], ["r5.sqlite"]),
    ("bench --db foreign SQLite", ["bench", "spec.yaml", "--db", "foreign.sqlite"], []),
    ("bench --db not SQLite", ["bench", "spec.yaml", "--db", "not_sqlite.sqlite"], []),
    ("bench --csv .txt", ["bench", "spec.yaml", "--db", "r6.sqlite", "--csv", "x.txt"], ["x.txt", "r6.sqlite"]),
    ("bench --workers 0", ["bench", "spec.yaml", "--db", "r7.sqlite", "--workers", "0"], ["r7.sqlite"]),
]


def run_case(argv: list[str], folder: Path, timeout: float) -> tuple[str, str, float]:
    t0 = time.perf_counter()
    try:
        done = subprocess.run([sys.executable, "-m", "optplan", *argv, "--no-progress"] if argv[0] == "bench"
                              else [sys.executable, "-m", "optplan", *argv], cwd=folder, capture_output=True,
                              text=True, timeout=timeout, stdin=subprocess.DEVNULL)
    except subprocess.TimeoutExpired:
        return "hang", "", time.perf_counter() - t0
    err = done.stderr.strip()
    if "Traceback" in err or "internal error" in err:
        return "traceback", err.splitlines()[-1][:150], time.perf_counter() - t0
    if done.returncode == 2 and len(err.splitlines()) >= 1 and err.splitlines()[-1].startswith("optplan: error:"):
        return "handled", err.splitlines()[-1][:150], time.perf_counter() - t0
    if done.returncode in (0, 1):
        return "handled", f"ran (exit {done.returncode})", time.perf_counter() - t0
    return "other", f"exit {done.returncode}: {err[:150]}", time.perf_counter() - t0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--timeout", type=float, default=60.0)
    ap.add_argument("--list", action="store_true")
    args = ap.parse_args(argv)
    if args.list:
        print("\n".join(name for name, _, _ in CASES))
        return 0
    counts = {"handled": 0, "traceback": 0, "hang": 0, "partial": 0, "other": 0}
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        _setup(folder)
        for name, cmd, outputs in CASES:
            kind, line, secs = run_case(cmd, folder, args.timeout)
            left = [o for o in outputs if (folder / o).exists() and kind != "handled" or
                    ((folder / o).exists() and line.startswith("optplan: error"))]
            if left:
                kind = "partial"
            counts[kind] += 1
            print(f"{kind:>9}  {secs:5.1f} s  {name}: {line}" + (f"  [left {', '.join(left)}]" if left else ""),
                  flush=True)
    print(f"{len(CASES)} cases: " + ", ".join(f"{v} {k}" for k, v in counts.items()))
    return 0 if counts["handled"] == len(CASES) else 1


if __name__ == "__main__":
    raise SystemExit(main())
