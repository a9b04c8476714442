"""Wall time of every quick mode (issue 47 item 7: a --quick spec <= 30 s, a
``optplan reproduce PAPER --quick`` <= 60 s, on 2 cores).

Each command runs in a fresh process with a fresh in-memory or temporary database, as a
newcomer would run it (the spec's own quick overrides, the default workers), and its wall
time is printed in a table next to the target.

    python benchmarks/quick_times.py                   # every shipped spec and every paper
    python benchmarks/quick_times.py --only reproduce  # the five papers
"""
from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from optplan.bench.command import PAPERS
from optplan.bench.spec import shipped_specs


def _run(argv: list[str], timeout: float) -> tuple[float, int | str]:
    t0 = time.perf_counter()
    try:
        done = subprocess.run([sys.executable, "-m", "optplan", *argv, "--no-progress"], capture_output=True,
                              text=True, timeout=timeout, stdin=subprocess.DEVNULL)
    except subprocess.TimeoutExpired:
        return time.perf_counter() - t0, "timeout"
    return time.perf_counter() - t0, done.returncode


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", choices=("specs", "reproduce"), default=None)
    ap.add_argument("--timeout", type=float, default=600.0)
    args = ap.parse_args(argv)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        if args.only in (None, "specs"):
            for name in shipped_specs():
                secs, code = _run(["bench", name, "--quick", "--db", str(Path(tmp) / f"{name}.sqlite")],
                                  args.timeout)
                rows.append((f"bench {name} --quick", secs, code, 30.0))
                print(f"  {rows[-1][0]}: {secs:.1f} s (exit {code})", flush=True)
        if args.only in (None, "reproduce"):
            for paper in PAPERS:
                secs, code = _run(["reproduce", paper, "--quick"], args.timeout)
                rows.append((f"reproduce {paper} --quick", secs, code, 60.0))
                print(f"  {rows[-1][0]}: {secs:.1f} s (exit {code})", flush=True)
    print("\n| command | wall s | exit | target s | within |")
    print("|---|---|---|---|---|")
    for name, secs, code, target in rows:
        print(f"| `optplan {name}` | {secs:.1f} | {code} | {target:.0f} | {'yes' if secs <= target else '**no**'} |")
    over = [r for r in rows if r[1] > r[3]]
    print(f"\n{len(rows) - len(over)} of {len(rows)} within their target")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
