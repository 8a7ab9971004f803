"""A `shadowkit eval --serve` process kept by the process that measures cells (the sweep itself,
or each Dask worker, per thread): requests go in on its stdin as JSON arrays of arguments, and
the scene, GL context, BVHs and the truths it caches per camera, sun and size stay between
them while the cells' scene options are the same — the per-worker truth cache, without a
second implementation of eval's options."""
import atexit
import json
import os
import subprocess
import tempfile
import threading

SENTINEL = "shadowkit-serve: exit "


class ServerEnded(RuntimeError):
    """The serving process ended (crashed, killed) during a request."""


class EvalServer:
    def __init__(self, program, data_dir):
        handle, self.log = tempfile.mkstemp(prefix="shadowkit-serve-", suffix=".log")
        os.close(handle)
        with open(self.log, "ab") as log:  # the child appends; this process reads its own copy's offset
            self.process = subprocess.Popen([program, "eval", "--serve"], stdin=subprocess.PIPE,
                                            stdout=subprocess.PIPE, stderr=log, text=True, bufsize=1,
                                            env={**os.environ, "SHADOWKIT_DATA_DIR": data_dir})

    def evaluate(self, arguments):
        """(exit code, what the request printed on stderr)."""
        start = os.path.getsize(self.log)
        try:
            self.process.stdin.write(json.dumps(arguments) + "\n")
            self.process.stdin.flush()
        except (BrokenPipeError, OSError):
            raise ServerEnded(self._ended()) from None
        while True:
            line = self.process.stdout.readline()
            if not line:
                raise ServerEnded(self._ended())
            if line.startswith(SENTINEL):
                code = int(line[len(SENTINEL):])
                break
        with open(self.log, "rb") as f:
            f.seek(start)
            return code, f.read().decode(errors="replace")

    def _ended(self):
        code = self.process.wait()
        with open(self.log, "rb") as f:
            tail = f.read().decode(errors="replace").strip().splitlines()[-1:] or ["no message"]
        return f"eval --serve ended (exit {code}): {tail[0]}"

    def close(self):
        if self.process.poll() is None:
            self.process.stdin.close()
            try:
                self.process.wait(timeout=30)
            except subprocess.TimeoutExpired:
                self.process.kill()
        self.process.stdout.close()
        if os.path.exists(self.log):
            os.remove(self.log)


_servers = {}
_lock = threading.Lock()


def server(program, data_dir):
    """This thread's server for the program and data (started on first use)."""
    key = (program, data_dir, threading.get_ident())
    with _lock:
        if key not in _servers or _servers[key].process.poll() is not None:
            _servers[key] = EvalServer(program, data_dir)
        return _servers[key]


def drop(program, data_dir):
    """Forgets this thread's server (after it ended), so the next cell starts another."""
    with _lock:
        s = _servers.pop((program, data_dir, threading.get_ident()), None)
    if s is not None:
        s.close()


@atexit.register
def _close_all():
    with _lock:
        for s in _servers.values():
            s.close()
        _servers.clear()
