"""Execute run records in parallel and store each result as it finishes.

Executors:

* ``"local"`` (default): a pool of worker processes (``concurrent.futures`` with
  the forkserver start method where the platform has it, spawn elsewhere);
  ``workers=1`` runs in this process, which avoids the start-up cost for small grids.
* ``"dask://HOST:PORT"`` (or ``"tcp://HOST:PORT"``): the Dask distributed
  scheduler at that address; its workers need the same optplan installed, and map
  or scenario files named by path must exist at that path on the workers (shipped
  maps and scenarios always do).
* ``"dask-local"``: a Dask ``LocalCluster`` of ``workers`` processes on this machine.
* a ``distributed.Client`` object (Python API only).

Every run carries its own seed, so a run gives the same numbers whichever
executor ran it (wall times differ). Only this (parent) process writes the
results database; a run that raises is stored as ``failed`` with its message
and the others continue. Runs whose key is already stored are skipped, which is
how an interrupted experiment resumes.
"""
from __future__ import annotations

import json
import os
import socket
import sys
import time
from dataclasses import dataclass
from contextlib import contextmanager
from typing import Any, Callable, Iterable, Mapping

from ..errors import ParameterError
# each kind runs its own records (optplan/bench/kinds); the target loaders stay importable from here
from .kinds.optimize import function_target
from .kinds.plan import plan_target

EXECUTORS_HELP = "local | dask://HOST:PORT | dask-local"


# ------------------------------------------------------------------- one run (worker side)
def _exit_with_parent(parent_pid: int, period_s: float = 1.0) -> None:
    """In a worker: end the process once ``parent_pid`` (the bench process) is gone, so a
    ``kill -9`` of the bench leaves no orphan workers holding memory."""
    import threading

    def watch():
        while True:
            time.sleep(period_s)
            try:
                os.kill(parent_pid, 0)
            except ProcessLookupError:
                os._exit(1)
            except PermissionError:  # the pid was reused by another user's process: the parent is gone
                os._exit(1)

    threading.Thread(target=watch, name="optplan-parent-watch", daemon=True).start()


def warm_up(extra: tuple[str, ...] = (), parent_pid: int | None = None) -> None:
    """Import what the solvers import lazily, so that no run's ``runtime_s`` includes one-time
    module loading (scipy.spatial alone takes ~0.5 s, cvxpy 1.5 s); called once per worker
    process. ``extra`` names further modules the runs need (:func:`warm_modules`);
    ``parent_pid``, when given, is the bench process this worker must not outlive."""
    import importlib

    if parent_pid is not None:
        _exit_with_parent(parent_pid)

    for mod in ("scipy.spatial", "scipy.interpolate", "scipy.stats", "optplan.planning", "optplan.solvers.paths",
                "optplan.solvers.metaheuristics", "optplan.formulations.functions", "optplan.world.papermaps",
                *extra):
        importlib.import_module(mod)


def warm_modules(records: Iterable[Mapping[str, Any]]) -> tuple[str, ...]:
    """The modules beyond :func:`warm_up`'s own list that these runs (record dicts) need:
    for ``program`` runs, the program layer and the packages of their solvers."""
    programs = [r["algorithm"] for r in records if r.get("kind") == "program"]
    if not programs:
        return ()
    from .programs import solver_modules

    return ("optplan.programs", *solver_modules(dict.fromkeys(programs)))


def execute_run(record: Mapping[str, Any]) -> dict[str, Any]:
    """Run one record (a ``RunRecord.to_dict()``) and return its outcome.

    The outcome is ``{"key", "status": "ok"|"failed", "error", "metrics": {scalar
    fields of the result}, "traces": {array fields}, "wall_s", "worker"}``; an
    exception inside the run becomes ``status="failed"`` with its message.
    """
    from .spec import RunRecord
    from .store import TRACE_COLUMNS

    t0 = time.perf_counter()
    worker = f"{socket.gethostname()}:{os.getpid()}"
    key = record.get("key")
    try:
        rec = RunRecord.from_dict(record)
        from .kinds import get_kind

        result, extra = get_kind(rec.kind).run(rec)
        d = result.to_dict()
        metrics = {k: v for k, v in d.items() if v is None or isinstance(v, (bool, int, float, str))}
        metrics.update(extra)
        if "status" in metrics:  # the result's own status (timeout, max_evals, ...); 'status' is the run's
            metrics["result_status"] = metrics.pop("status")
        traces = {k: v for k, v in d.items() if k in TRACE_COLUMNS and v is not None}
        return {"key": key, "status": "ok", "error": None, "metrics": metrics, "traces": traces,
                "wall_s": time.perf_counter() - t0, "worker": worker}
    except Exception as exc:  # recorded, never fatal: the other runs continue
        msg = str(exc).strip().splitlines()[0] if str(exc).strip() else ""
        return {"key": key, "status": "failed", "error": f"{type(exc).__name__}: {msg}"[:2000], "metrics": {},
                "traces": {}, "wall_s": time.perf_counter() - t0, "worker": worker}


# ------------------------------------------------------------------- progress bar
def _hms(seconds: float) -> str:
    s = int(round(seconds))
    return f"{s // 3600}:{s // 60 % 60:02d}:{s % 60:02d}" if s >= 3600 else f"{s // 60}:{s % 60:02d}"


class Progress:
    """A one-line progress bar on stderr: runs done, failures, elapsed time and ETA.

    On a terminal the line redraws in place; otherwise (logs, pipes) a line is
    printed at every tenth of the work and at the end.
    """

    def __init__(self, total: int, label: str = "", stream=None, enabled: bool = True, width: int = 24):
        self.total, self.label, self.width = total, label, width
        self.stream = stream if stream is not None else sys.stderr
        self.enabled = enabled and total > 0
        self.done = self.failed = 0
        self.t0 = time.perf_counter()
        self._last_draw = 0.0
        self._last_tenth = -1
        self.tty = bool(getattr(self.stream, "isatty", lambda: False)())

    def line(self) -> str:
        frac = self.done / self.total if self.total else 1.0
        fill = int(round(frac * self.width))
        elapsed = time.perf_counter() - self.t0
        eta = elapsed / self.done * (self.total - self.done) if self.done else float("nan")
        eta_s = _hms(eta) if self.done else "?"
        head = f"{self.label} " if self.label else ""
        return (f"{head}[{'#' * fill}{'.' * (self.width - fill)}] {self.done}/{self.total} runs, "
                f"{self.failed} failed, {_hms(elapsed)} elapsed, ETA {eta_s}")

    def update(self, failed: bool = False) -> None:
        self.done += 1
        self.failed += int(bool(failed))
        if not self.enabled:
            return
        now = time.perf_counter()
        if self.tty:
            if now - self._last_draw > 0.1 or self.done == self.total:
                print("\r" + self.line(), end="", file=self.stream, flush=True)
                self._last_draw = now
        else:
            tenth = int(10 * self.done / self.total)
            if tenth != self._last_tenth:
                print(self.line(), file=self.stream, flush=True)
                self._last_tenth = tenth

    def close(self) -> None:
        if self.enabled and self.tty:
            print(file=self.stream, flush=True)


# ------------------------------------------------------------------- executors
@dataclass
class RunReport:
    """What one call of :func:`run_records` did."""

    total: int
    skipped: int
    other_code: int = 0  # of the skipped runs, those stored by other optplan code
    ran: int = 0
    failed: int = 0
    wall_s: float = 0.0
    interrupted: bool = False
    elsewhere: int = 0  # runs another process sharing the database computed meanwhile

    def describe(self) -> str:
        s = (f"{self.total} runs: {self.skipped} already in the database, {self.ran} ran "
             f"({self.failed} failed) in {self.wall_s:.1f} s")
        if self.elsewhere:
            s += f", {self.elsewhere} computed by another process sharing the database"
        if self.other_code:
            s += (f"; {self.other_code} of the runs already stored were made by other optplan code (its sources "
                  "differ) and are reported as they are: pass a fresh --db to measure this code")
        return s + (" (interrupted; rerun to resume)" if self.interrupted else "")


def parse_executor(executor: Any) -> tuple[str, Any]:
    """``("local", None)``, ``("dask-local", None)``, ``("dask", address)`` or ``("client", client)``."""
    if executor is None or executor == "local":
        return "local", None
    if isinstance(executor, str):
        if executor == "dask-local":
            return "dask-local", None
        for prefix, scheme in (("dask://", "tcp://"), ("tcp://", "tcp://"), ("tls://", "tls://")):
            if executor.startswith(prefix):
                address = executor[len(prefix):]
                if ":" not in address:
                    raise ParameterError(f"executor {executor!r} needs a port: dask://HOST:PORT")
                return "dask", scheme + address
        raise ParameterError(f"unknown executor {executor!r}; use {EXECUTORS_HELP}")
    if hasattr(executor, "submit") and hasattr(executor, "scheduler_info"):
        return "client", executor
    raise ParameterError(f"executor must be a string ({EXECUTORS_HELP}) or a distributed.Client, got {executor!r}")


def run_records(records: Iterable, store, executor: Any = "local", workers: int | None = None,
                progress: bool = True, retry_failed: bool = False, label: str = "",
                on_result: Callable[[Mapping, Mapping], None] | None = None) -> RunReport:
    """Execute ``records`` (RunRecords) not yet in ``store`` and write each outcome as it arrives.

    Args:
        records: the runs (``ExperimentSpec.expand()``); duplicates by key run once.
        store: a :class:`~optplan.bench.store.ResultStore`.
        executor: see the module docstring.
        workers: processes for ``"local"`` / ``"dask-local"`` (default: CPU count); 1 runs in-process.
        progress: draw the progress bar on stderr.
        retry_failed: run again the runs stored as failed (default: skip them like finished ones).
        label: text in front of the progress bar.
        on_result: ``callback(record_dict, outcome)`` after each stored run.

    Returns:
        A :class:`RunReport`. On KeyboardInterrupt the runs already stored stay
        stored and the interrupt propagates.
    """
    unique = {}
    for r in records:
        unique.setdefault(r.key, r)
    done = store.done_keys(unique, include_failed=not retry_failed)
    todo = [r.to_dict() for k, r in unique.items() if k not in done]
    report = RunReport(total=len(unique), skipped=len(unique) - len(todo),
                       other_code=store.made_by_other_code(done) if done else 0)
    if workers is not None and (not isinstance(workers, int) or workers < 1):
        raise ParameterError(f"workers must be a positive integer, got {workers!r}")
    kind, target = parse_executor(executor)
    if not todo:
        return report
    bar = Progress(len(todo), label=label, enabled=progress)
    t0 = time.perf_counter()

    def record(rec: Mapping, outcome: Mapping) -> None:
        store.write(rec, outcome)
        report.ran += 1
        report.failed += outcome["status"] != "ok"
        bar.update(outcome["status"] != "ok")
        if on_result is not None:
            on_result(rec, outcome)

    queue = ClaimQueue(todo, store, include_failed=not retry_failed)

    def execute() -> None:
        if kind == "local":
            n = workers or os.cpu_count() or 1
            if n == 1 or len(queue) == 1:
                warm_up(warm_modules(todo))
                while (rec := queue.pop()) is not None:
                    record(rec, execute_run(rec))
            else:
                _run_process_pool(queue, min(n, len(queue)), record)
        else:
            _run_dask(queue, kind, target, workers, record)

    try:
        execute()
        # runs another process claimed: wait for them, taking over those whose owner is gone,
        # so the report is the one a single process would give
        while queue.elsewhere:
            waiting, queue.elsewhere = queue.elsewhere, []
            stored = store.done_keys([r["key"] for r in waiting], include_failed=not retry_failed)
            report.elsewhere += sum(r["key"] in stored for r in waiting)
            rest = [r for r in waiting if r["key"] not in stored]
            taken = [store.claim(r["key"], not retry_failed) for r in rest]
            mine = [r for r, t in zip(rest, taken) if t]
            queue.elsewhere = [r for r, t in zip(rest, taken) if not t]
            if mine:                    # their owner is gone: this process runs them
                queue.refill(mine, claimed=True)
                execute()
            elif queue.elsewhere:
                time.sleep(CLAIM_POLL_S)
    except KeyboardInterrupt:
        report.interrupted = True
        raise
    finally:
        store.release_claims()
        bar.close()
        report.wall_s = time.perf_counter() - t0
    return report


CLAIM_POLL_S = 0.5  # how often a process looks whether runs another process holds are stored


class ClaimQueue:
    """The runs still to do, in order. :meth:`pop` hands out the next run this process
    could claim in the database (:meth:`ResultStore.claim`); runs another live process
    holds are set aside in ``elsewhere``."""

    def __init__(self, todo: list[dict], store, include_failed: bool = True) -> None:
        self.store, self.include_failed = store, include_failed
        self.items: list[dict] = []
        self.elsewhere: list[dict] = []
        self.claimed = False
        self.refill(todo)

    def refill(self, todo: list[dict], claimed: bool = False) -> None:
        """Runs to hand out; ``claimed``: this process holds their claims already."""
        self.items, self.claimed = list(reversed(todo)), claimed

    def __len__(self) -> int:
        return len(self.items)

    def pop(self) -> dict | None:
        while self.items:
            rec = self.items.pop()
            if self.claimed or self.store.claim(rec["key"], self.include_failed):
                return rec
            self.elsewhere.append(rec)
        return None


def _failed(rec: Mapping, message: str) -> dict[str, Any]:
    return {"key": rec["key"], "status": "failed", "error": message, "metrics": {}, "traces": {}, "wall_s": None,
            "worker": None}


def _pool_context():
    import multiprocessing as mp

    return mp.get_context("forkserver" if "forkserver" in mp.get_all_start_methods() else "spawn")


@contextmanager
def _main_script_not_reimported(todo: list[dict]):
    """Keep worker processes from re-running the caller's script.

    forkserver and spawn workers normally import the parent's ``__main__`` file again; a
    script that calls ``run_experiment(..., workers=2)`` without an
    ``if __name__ == "__main__":`` guard then starts the whole experiment inside every
    worker. The workers only need ``optplan`` (each run is a plain dict executed by
    :func:`execute_run`), so while the pool runs the main module's file is hidden from
    multiprocessing, as for an interactive session. A spec that names code in
    ``__main__`` keeps the usual behaviour (it needs the script in the workers).
    """
    main = sys.modules.get("__main__")
    hide = main is not None and getattr(main, "__file__", None) is not None and \
        "__main__" not in json.dumps(todo, default=str)
    if not hide:
        yield
        return
    saved = {k: main.__dict__[k] for k in ("__file__", "__spec__") if k in main.__dict__}
    for k in saved:
        if k == "__spec__":
            main.__spec__ = None
        else:
            del main.__dict__[k]
    try:
        yield
    finally:
        main.__dict__.update(saved)


def _run_process_pool(queue: ClaimQueue, workers: int, record: Callable) -> None:
    """Run the runs of ``queue`` on a process pool (see :func:`_pool_loop`), never re-running
    the caller's script in the workers (:func:`_main_script_not_reimported`)."""
    with _main_script_not_reimported(queue.items):
        _pool_loop(queue, workers, record)


def _pool_loop(queue: ClaimQueue, workers: int, record: Callable) -> None:
    """A process pool with at most ``2 * workers`` runs in flight.

    A worker that dies hard (segfault, out of memory) breaks the pool; the runs
    that were in flight become suspects and are run again one at a time on a
    fresh pool, so only the run that kills its worker is stored as failed.
    """
    from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
    from concurrent.futures.process import BrokenProcessPool

    suspects: list[dict] = []
    modules = warm_modules(queue.items)
    while len(queue) or suspects:
        pool = ProcessPoolExecutor(max_workers=workers, mp_context=_pool_context(), initializer=warm_up,
                                   initargs=(modules, os.getpid()))
        in_flight: dict = {}
        broken = alone = False
        try:
            while in_flight or (not broken and (len(queue) or suspects)):
                if not broken:
                    if suspects and not in_flight:
                        rec = suspects.pop()
                        in_flight[pool.submit(execute_run, rec)] = rec
                        alone = True
                    elif not suspects:
                        while len(in_flight) < 2 * workers and (rec := queue.pop()) is not None:
                            in_flight[pool.submit(execute_run, rec)] = rec
                        alone = False
                if not in_flight:
                    break        # every run left is claimed by another process
                finished, _ = wait(in_flight, return_when=FIRST_COMPLETED)
                for fut in finished:
                    rec = in_flight.pop(fut)
                    try:
                        outcome = fut.result()
                    except BrokenProcessPool:
                        broken = True
                        if alone:
                            record(rec, _failed(rec, "the worker process died while running this run "
                                                     "(crash or out of memory)"))
                        else:
                            suspects.append(rec)
                        continue
                    except Exception as exc:  # pickling problems and the like
                        outcome = _failed(rec, f"{type(exc).__name__}: {exc}")
                    record(rec, outcome)
        except BaseException:
            pool.shutdown(wait=False, cancel_futures=True)
            raise
        pool.shutdown(wait=not broken, cancel_futures=True)


def _run_dask(queue: ClaimQueue, kind: str, target: Any, workers: int | None, record: Callable) -> None:
    try:
        from distributed import Client, LocalCluster, as_completed
    except ImportError:
        raise ParameterError("the Dask executors need dask[distributed]: pip install 'optplan[dask]'") from None
    cluster = None
    if kind == "client":
        client, own_client = target, False
    elif kind == "dask-local":
        cluster = LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        client, own_client = Client(cluster), True
    else:
        try:
            client, own_client = Client(target, timeout=30), True
        except (OSError, TimeoutError) as exc:
            raise ParameterError(f"cannot reach the Dask scheduler at {target} ({exc}); start one with "
                                 f"'dask scheduler' and 'dask worker {target}', or use --executor local") from None
    try:
        try:
            client.run(warm_up, warm_modules(queue.items))
        except Exception as exc:  # typically: optplan is not installed where the workers run
            raise ParameterError(f"the Dask workers cannot run optplan ({type(exc).__name__}: {exc}); install the "
                                 f"same optplan version on every worker (pip install optplan[dask])") from None
        n_workers = max(1, len(client.scheduler_info().get("workers", {})) or (workers or 1))
        window = 4 * n_workers
        by_future = {}

        def submit():
            rec = queue.pop()
            if rec is None:
                return None
            fut = client.submit(execute_run, rec, key=f"optplan-run-{rec['key']}", pure=False)
            by_future[fut] = rec
            return fut

        initial = [f for f in (submit() for _ in range(min(window, len(queue)))) if f is not None]
        ac = as_completed(initial)
        try:
            for fut in ac:
                rec = by_future.pop(fut)
                try:
                    outcome = fut.result()
                except Exception as exc:  # a worker lost or the task could not be shipped
                    outcome = _failed(rec, f"dask: {type(exc).__name__}: {exc}")
                record(rec, outcome)
                fut.release()
                nxt = submit() if len(queue) else None
                if nxt is not None:
                    ac.add(nxt)
        except BaseException:
            client.cancel(list(by_future))
            raise
    finally:
        if own_client:
            client.close()
        if cluster is not None:
            cluster.close()
