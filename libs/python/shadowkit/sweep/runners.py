"""Where cells are measured: one after another in this process's children (`serial`), or on a
Dask cluster (`dask`: a scheduler's address, or a local cluster of N worker processes), one
cell per task. Both hand each finished cell to the store as it arrives, so results stream
into the same resumable files; the scheduling, retries and a lost worker's re-run are Dask's.
"""
import logging
import shutil
import sys
import tempfile
import time

from .cells import run_cell


class Progress:
    """cells done / total, rate and time left, on one line of a terminal (a line per cell in a log).

    `expected` ({cell key: seconds}, cli.cell_seconds of the cells to run) weighs the time left:
    the time so far scaled by what the cells left should take against those done, so a sweep
    whose slow cells (leaves, the sun's disk, large images) come last is not told it is nearly
    done. Without it, every cell counts the same."""

    def __init__(self, total, already, stream=sys.stderr, expected=None):
        self.total, self.done, self.failed = total, already, 0
        self.first = already
        self.start = time.monotonic()
        self.stream = stream
        self.tty = stream.isatty()
        self.expected = dict(expected or {})
        self.expected_left, self.expected_done = sum(self.expected.values()), 0.0

    def step(self, record, stored):
        self.done += 1
        if "error" in record:
            self.failed += 1
            self._line(f"cell {record['key']} failed on {record['host']}: {record['error']}")
        elif not stored:
            self.done -= 1  # a duplicate: already counted
        if "error" in record or stored:
            seconds = self.expected.pop(record["key"], 0.0)
            self.expected_left -= seconds
            self.expected_done += seconds
        self._bar()

    def seconds_left(self, elapsed):
        """The time the cells not yet done should take, from `elapsed` seconds for those done."""
        now = self.done - self.first
        if self.expected_done > 0:
            return elapsed * max(self.expected_left, 0.0) / self.expected_done
        return (self.total - self.done) / (now / elapsed) if now and elapsed > 0 else float("nan")

    def _line(self, text):
        self.stream.write(("\r\033[K" if self.tty else "") + text + "\n")

    def _bar(self):
        elapsed = time.monotonic() - self.start
        now = self.done - self.first
        rate = now / elapsed * 60 if elapsed > 0 else 0.0
        left = self.seconds_left(elapsed)
        width = 30
        filled = int(width * self.done / self.total) if self.total else width
        text = (f"[{'#' * filled}{'.' * (width - filled)}] {self.done}/{self.total} cells · {rate:.1f}/min · "
                f"{_duration(left)} left" + (f" · {self.failed} failed" if self.failed else ""))
        if self.tty:
            self.stream.write("\r\033[K" + text)
        else:
            self.stream.write(text + "\n")
        self.stream.flush()

    def finish(self):
        if self.tty:
            self.stream.write("\n")
        self.stream.flush()


def _duration(seconds):
    if seconds != seconds:  # NaN: no cell finished yet
        return "?"
    if seconds < 90:
        return f"{seconds:.0f} s"
    if seconds < 5400:
        return f"{seconds / 60:.0f} min"
    return f"{seconds / 3600:.1f} h"


def run_serial(tasks, store, progress):
    for task in tasks:
        record = run_cell(task)
        progress.step(record, store.add(record))


def run_dask(tasks, store, progress, scheduler=None, local_workers=None):
    """On a Dask cluster: `scheduler` (tcp://HOST:8786) or a LocalCluster of `local_workers`
    single-threaded worker processes. Each cell is a task keyed by the cell's key."""
    try:
        from distributed import Client, LocalCluster, as_completed
    except ImportError:
        raise RuntimeError("--scheduler/--local-workers: Dask is not installed (Debian: python3-distributed)") from None
    cluster = None
    if scheduler:
        try:
            client = Client(scheduler, timeout="20s")
        except (OSError, TimeoutError) as e:
            raise RuntimeError(f"--scheduler {scheduler}: cannot connect ({e})") from None
    else:
        # One thread per worker: a cell's eval already uses the machine's cores (GL and the ray tracer).
        # Its own scratch directory: Dask purges (and logs) other clusters' stale ones in a shared one.
        scratch = tempfile.mkdtemp(prefix="shadowkit-dask-")
        cluster = LocalCluster(n_workers=local_workers, threads_per_worker=1, processes=True,
                               dashboard_address=None, silence_logs=logging.ERROR, local_directory=scratch)
        client = Client(cluster)
    try:
        futures = [client.submit(run_cell, task, key=f"shadowkit-cell-{task['key']}", pure=False) for task in tasks]
        for future in as_completed(futures):
            try:
                record = future.result()
            except Exception as e:  # a task Dask gave up on (KilledWorker after repeated losses)
                task = tasks[futures.index(future)]
                record = {"key": task["key"], "host": "dask", "options": task["options"], "labels": task["labels"],
                          "error": f"{type(e).__name__}: {e}"}
            progress.step(record, store.add(record))
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
            shutil.rmtree(scratch, ignore_errors=True)
