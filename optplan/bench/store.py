"""Results database: one SQLite row per run, written by the parent process as runs finish.

Table ``runs`` has the run's identity (``key``, experiment, kind, target,
algorithm, label, refine, local planner, seed, and for ``program`` runs the program
as JSON: name or ``module:function``, args, init), its status (``ok`` or ``failed``
with the error message), each solver parameter as a ``param_<name>`` column and
each scalar metric of the result (``length``, ``feasible``, ``f``, ``reached``,
``time_s``, ...) as a column of its own; columns are added when a new parameter
or metric first appears. Table ``traces`` holds the arrays (convergence
history, path, trajectory) as JSON, keyed like ``runs``, so that ``runs``
stays light for queries and CSV export.

The database runs in WAL mode and each run is committed in its own
transaction, so a killed process loses at most the runs that were in flight;
:meth:`ResultStore.done_keys` is what a rerun skips.

Table ``claims`` lets several processes fill one database without computing a run
twice: a process claims a run (:meth:`ResultStore.claim`) before it starts it, and
the claim goes when the run is stored. A claim held by a process that is gone (same
host, its pid no longer alive) or older than :data:`CLAIM_LAPSE_S` may be taken over.

A file that holds tables of something else is refused, never written to.
"""
from __future__ import annotations

import csv
import functools
import hashlib
import json
import os
import re
import socket
import sqlite3
import time
import uuid
from pathlib import Path
from typing import Any, Iterable, Mapping

from ..errors import OptplanError, ParameterError

IDENTITY_COLUMNS = (
    ("key", "TEXT PRIMARY KEY"), ("experiment", "TEXT"), ("kind", "TEXT"), ("target", "TEXT"),
    ("algorithm", "TEXT"), ("label", "TEXT"), ("refine", "TEXT"), ("local_planner", "TEXT"), ("seed", "INTEGER"),
    ("status", "TEXT"), ("error", "TEXT"), ("wall_s", "REAL"), ("worker", "TEXT"), ("finished_at", "TEXT"),
    ("optplan_version", "TEXT"), ("params", "TEXT"), ("target_spec", "TEXT"), ("program", "TEXT"),
)
IDENTITY = tuple(c for c, _ in IDENTITY_COLUMNS)
TRACE_COLUMNS = ("history", "history_nfev", "path", "global_path", "trajectory", "x")
# result fields that repeat the identity columns under another name
_SKIP_METRICS = {"algorithm", "seed", "global_planner", "local_planner", "refine"}


@functools.lru_cache(maxsize=1)
def code_fingerprint() -> str:
    """16 hex digits of a SHA-256 over optplan's Python sources (paths and bytes), stored with
    every run: the package version does not change when the code does, and a rerun skips
    the runs already stored whatever code made them."""
    root = Path(__file__).resolve().parent.parent
    h = hashlib.sha256()
    for f in sorted(root.rglob("*.py")):
        h.update(f.relative_to(root).as_posix().encode())
        h.update(f.read_bytes())
    return h.hexdigest()[:16]


def column_name(name: str, prefix: str = "") -> str:
    """A safe SQL column name for a parameter or metric name."""
    col = prefix + re.sub(r"[^0-9a-zA-Z_]", "_", str(name)).lower()
    return col if not col[0].isdigit() else "_" + col


def _sql_type(value: Any) -> str:
    """The declared type of a new column, from the first value stored in it. A first value of
    ``None`` (a metric some runs do not have) declares none: SQLite then keeps each value as
    given, where a TEXT column would turn the later runs' numbers into strings."""
    if value is None:
        return ""
    if isinstance(value, bool) or isinstance(value, int):
        return "INTEGER"
    if isinstance(value, float):
        return "REAL"
    return "TEXT"


def _sql_value(value: Any) -> Any:
    if value is None or isinstance(value, (bool, int, float, str)):
        return value
    return json.dumps(value)


LOCK_TIMEOUT_S = 60.0  # how long a writer waits for another process's lock on the database
CLAIM_LAPSE_S = 24 * 3600.0  # a claim this old is taken over even if its owner cannot be checked
OWN_TABLES = ("runs", "traces", "claims")


def _pid_alive(pid: int) -> bool:
    try:
        os.kill(int(pid), 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OSError, ValueError):
        return True
    return True


def _foreign_tables(path: str) -> list[str]:
    """Tables of an existing SQLite file that are not optplan's (empty when none, or when the
    file is new or empty); a file that is no SQLite database is left to the caller's error."""
    p = Path(path)
    if not p.is_file() or p.stat().st_size == 0:
        return []
    try:
        conn = sqlite3.connect(f"file:{p.resolve().as_posix()}?mode=ro", uri=True, timeout=LOCK_TIMEOUT_S)
        try:
            names = [r[0] for r in conn.execute("SELECT name FROM sqlite_master WHERE type = 'table'")]
        finally:
            conn.close()
    except sqlite3.DatabaseError:
        return []
    return [n for n in names if n not in OWN_TABLES and not n.startswith("sqlite_")]


class ResultStore:
    """SQLite results of runs; ``path=":memory:"`` keeps them in memory.

    Only one process (the runner's parent) writes; readers may open the same
    file at any time (WAL mode).
    """

    def __init__(self, path: str | Path = ":memory:"):
        self.path = str(path)
        self.owner = f"{socket.gethostname()}:{os.getpid()}:{uuid.uuid4().hex[:8]}"
        if self.path != ":memory:":
            parent = Path(self.path).parent
            if not parent.is_dir():
                raise ParameterError(f"results database folder {parent} does not exist; create it or pick another "
                                     f"--db path")
            foreign = _foreign_tables(self.path)
            if foreign:
                raise ParameterError(f"{self.path} is not an optplan results database (it holds the table(s) "
                                     f"{', '.join(foreign[:5])}); nothing was written to it; pass another --db file")
        try:
            self.conn = sqlite3.connect(self.path, timeout=LOCK_TIMEOUT_S, isolation_level=None)
            self.conn.row_factory = sqlite3.Row
            self._set_up()
        except sqlite3.DatabaseError as exc:
            raise ParameterError(f"cannot use {self.path} as a results database ({exc}); pass another --db file") \
                from None
        self._columns = {r["name"] for r in self.conn.execute("PRAGMA table_info(runs)")}
        self._check_schema()

    def _set_up(self) -> None:
        """WAL mode and the two tables (idempotent). Two processes that create one new file at
        the same moment can meet a lock SQLite reports at once instead of waiting for it (seen
        once in CI: 'database is locked' in a fresh database): the set-up is retried until
        :data:`LOCK_TIMEOUT_S`."""
        deadline = time.monotonic() + LOCK_TIMEOUT_S
        while True:
            try:
                if self.path != ":memory:":
                    self.conn.execute("PRAGMA journal_mode=WAL")
                    self.conn.execute("PRAGMA synchronous=NORMAL")
                cols = ", ".join(f"{c} {t}" for c, t in IDENTITY_COLUMNS)
                self.conn.execute(f"CREATE TABLE IF NOT EXISTS runs ({cols})")
                tcols = ", ".join(f"{c} TEXT" for c in TRACE_COLUMNS)
                self.conn.execute(f"CREATE TABLE IF NOT EXISTS traces (key TEXT PRIMARY KEY, {tcols})")
                self.conn.execute("CREATE TABLE IF NOT EXISTS claims (key TEXT PRIMARY KEY, owner TEXT, host TEXT, "
                                  "pid INTEGER, at REAL)")
                return
            except sqlite3.OperationalError as exc:
                if "locked" not in str(exc) or time.monotonic() > deadline:
                    raise
                time.sleep(0.05)

    def _check_schema(self) -> None:
        """Refuse a database whose ``runs``/``traces`` tables were made by something else."""
        missing = [c for c in IDENTITY if c not in self._columns]
        tcols = {r["name"] for r in self.conn.execute("PRAGMA table_info(traces)")}
        missing += [f"traces.{c}" for c in ("key", *TRACE_COLUMNS) if c not in tcols]
        if missing:
            self.conn.close()
            raise ParameterError(f"{self.path} is not an optplan results database (its tables lack "
                                 f"{', '.join(missing[:5])}{', ...' if len(missing) > 5 else ''}); pass another "
                                 f"--db file")

    # ------------------------------------------------------------------ writing
    def _ensure_column(self, col: str, value: Any) -> None:
        if col not in self._columns:
            self.conn.execute(f'ALTER TABLE runs ADD COLUMN "{col}" {_sql_type(value)}')
            self._columns.add(col)

    def write(self, record: Mapping[str, Any], outcome: Mapping[str, Any]) -> None:
        """Store one finished run (``record`` from ``RunRecord.to_dict``, ``outcome`` from the runner)
        in its own transaction; a second write of the same key replaces the first."""
        from .. import __version__

        row: dict[str, Any] = {
            "key": record["key"], "experiment": record["experiment"], "kind": record["kind"],
            "target": record["target"], "algorithm": record["algorithm"], "label": record["label"],
            "refine": record["refine"], "local_planner": record["local_planner"], "seed": record["seed"],
            "status": outcome["status"], "error": outcome.get("error"), "wall_s": outcome.get("wall_s"),
            "worker": outcome.get("worker"), "finished_at": time.strftime("%Y-%m-%dT%H:%M:%S"),
            "optplan_version": __version__, "params": json.dumps(record["params"], sort_keys=True),
            "target_spec": json.dumps(record["target_spec"], sort_keys=True),
            "program": json.dumps(record["program"], sort_keys=True) if record.get("program") else None,
            "code": code_fingerprint(),
        }
        for k, v in record["params"].items():
            row[column_name(k, "param_")] = _sql_value(v)
        for k, v in (outcome.get("metrics") or {}).items():
            if k not in _SKIP_METRICS and k not in IDENTITY:
                row[column_name(k)] = _sql_value(v)
        traces = {k: json.dumps(v) for k, v in (outcome.get("traces") or {}).items() if k in TRACE_COLUMNS}
        try:
            self._write_row(row, traces, record["key"])
        except sqlite3.Error as exc:  # disk full, read-only file, locked for longer than the timeout
            raise OptplanError(f"cannot store run {record['key'][:12]} in {self.path}: {exc}; the runs stored so far "
                               f"are kept (free space or pass another --db, then rerun to finish)") from None

    def _write_row(self, row: dict, traces: dict, key: str) -> None:
        self.conn.execute("BEGIN IMMEDIATE")
        try:
            if any(col not in self._columns for col in row):
                # another process may have added the column since we last looked: re-read the
                # columns under the write lock this transaction holds, then add what is missing
                self._columns = {r["name"] for r in self.conn.execute("PRAGMA table_info(runs)")}
            for col, v in row.items():
                self._ensure_column(col, v)
            names = ", ".join(f'"{c}"' for c in row)
            marks = ", ".join("?" for _ in row)
            self.conn.execute(f"INSERT OR REPLACE INTO runs ({names}) VALUES ({marks})", list(row.values()))
            tnames = ", ".join(["key", *traces])
            tmarks = ", ".join("?" for _ in range(len(traces) + 1))
            self.conn.execute(f"INSERT OR REPLACE INTO traces ({tnames}) VALUES ({tmarks})",
                              [key, *traces.values()])
            self.conn.execute("DELETE FROM claims WHERE key = ?", (key,))
            self.conn.execute("COMMIT")
        except BaseException:
            if self.conn.in_transaction:  # SQLite may already have rolled back (disk full): no second error
                try:
                    self.conn.execute("ROLLBACK")
                except sqlite3.Error:
                    pass
            raise

    # ------------------------------------------------------------------ sharing the work
    def claim(self, key: str, include_failed: bool = True) -> bool:
        """Take run ``key`` for this process: ``False`` when it is stored already (a failed
        run counts unless ``include_failed`` is False) or another live process holds it."""
        if self.path == ":memory:":
            return True
        host = socket.gethostname()
        self.conn.execute("BEGIN IMMEDIATE")
        try:
            cond = "" if include_failed else " AND status = 'ok'"
            if self.conn.execute(f"SELECT 1 FROM runs WHERE key = ?{cond}", (key,)).fetchone():
                return False
            held = self.conn.execute("SELECT owner, host, pid, at FROM claims WHERE key = ?", (key,)).fetchone()
            free = (held is None or held["owner"] == self.owner
                    or (held["host"] == host and not _pid_alive(held["pid"]))
                    or time.time() - float(held["at"] or 0.0) > CLAIM_LAPSE_S)
            if free:
                self.conn.execute("INSERT OR REPLACE INTO claims (key, owner, host, pid, at) VALUES (?, ?, ?, ?, ?)",
                                  (key, self.owner, host, os.getpid(), time.time()))
            return free
        finally:
            self.conn.execute("COMMIT")

    def release_claims(self) -> None:
        """Give back the claims this process still holds (runs it did not finish)."""
        if self.path != ":memory:":
            self.conn.execute("DELETE FROM claims WHERE owner = ?", (self.owner,))

    # ------------------------------------------------------------------ reading
    def done_keys(self, keys: Iterable[str] | None = None, include_failed: bool = True) -> set[str]:
        """Keys already stored (those a rerun skips); failed runs count unless ``include_failed`` is False."""
        cond = "" if include_failed else " WHERE status = 'ok'"
        have = {r[0] for r in self.conn.execute(f"SELECT key FROM runs{cond}")}
        return have if keys is None else have & set(keys)

    def made_by_other_code(self, keys: Iterable[str]) -> int:
        """How many of the stored runs ``keys`` were made by other optplan code than this
        process's (:func:`code_fingerprint`; runs stored before it was recorded count too)."""
        if "code" not in self._columns:
            self._columns = {r["name"] for r in self.conn.execute("PRAGMA table_info(runs)")}
        if "code" not in self._columns:
            return len(list(keys))
        return sum(r["code"] != code_fingerprint() for r in self._select("runs", keys))

    def rows(self, keys: Iterable[str] | None = None) -> dict[str, dict[str, Any]]:
        """``{key: row dict}`` for ``keys`` (all rows when ``None``)."""
        return {r["key"]: dict(r) for r in self._select("runs", keys)}

    def traces(self, keys: Iterable[str]) -> dict[str, dict[str, Any]]:
        """``{key: {history: [...], path: [...], ...}}`` (missing arrays are absent)."""
        return {r["key"]: {c: json.loads(r[c]) for c in TRACE_COLUMNS if r[c] is not None}
                for r in self._select("traces", keys)}

    def _select(self, table: str, keys: Iterable[str] | None) -> list[sqlite3.Row]:
        if keys is None:
            return list(self.conn.execute(f"SELECT * FROM {table}"))
        keys = list(dict.fromkeys(keys))
        out = []
        for i in range(0, len(keys), 500):  # stay under SQLite's bound-parameter limit
            chunk = keys[i:i + 500]
            out += self.conn.execute(f"SELECT * FROM {table} WHERE key IN ({', '.join('?' * len(chunk))})", chunk)
        return out

    def count(self) -> int:
        return int(self.conn.execute("SELECT COUNT(*) FROM runs").fetchone()[0])

    def to_csv(self, filename: str | Path, keys: Iterable[str] | None = None) -> int:
        """Write the ``runs`` rows (no arrays) to ``filename``; returns the number of rows."""
        rows = self.rows(keys)
        cols = [c for c in (r["name"] for r in self.conn.execute("PRAGMA table_info(runs)"))]
        from ..world.files import written_whole

        with written_whole(filename, "CSV file") as tmp, open(tmp, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(cols)
            for r in rows.values():
                w.writerow(["" if r[c] is None else r[c] for c in cols])
        return len(rows)

    def close(self) -> None:
        self.conn.close()

    def __enter__(self) -> "ResultStore":
        return self

    def __exit__(self, *exc) -> None:
        self.close()
