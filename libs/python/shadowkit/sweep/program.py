"""The `shadowkit` program a sweep's cells run: where it is, which options `eval` takes, and
the fingerprint that keys every result (program version, the executable's own hash, the data
it reads), so results of another build or other views are detected rather than mixed."""
import functools
import hashlib
import os
import re
import shutil
import subprocess


class ProgramError(RuntimeError):
    """A one-line description of why the program cannot be used."""


def find_program(explicit=None):
    """The shadowkit executable: `explicit`, else $SHADOWKIT, else `shadowkit` on PATH."""
    candidate = explicit or os.environ.get("SHADOWKIT") or shutil.which("shadowkit")
    if not candidate:
        raise ProgramError("shadowkit: not found (give --program, set SHADOWKIT or put shadowkit on PATH)")
    if not (os.path.isfile(candidate) and os.access(candidate, os.X_OK)):
        raise ProgramError(f"{candidate}: not an executable shadowkit program")
    return os.path.abspath(candidate)


def _sha256(path, digest=None):
    digest = digest or hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            digest.update(block)
    return digest


def data_directory():
    """views.json and the camera paths, as the program finds them: $SHADOWKIT_DATA_DIR, else the
    module's own answer (the source tree's data/ for a build, share/shadowkit once installed)."""
    if os.environ.get("SHADOWKIT_DATA_DIR"):
        return os.environ["SHADOWKIT_DATA_DIR"]
    from shadowkit import _native  # the compiled module knows where its build or install put the data

    return _native.data_directory()


@functools.lru_cache(maxsize=None)
def fingerprint(program, data_dir):
    """What a result depends on besides its options: {version, program (hash of the executable),
    data (hash of views.json and data/paths)}. Cached per process (a Dask worker hashes once)."""
    try:
        version = subprocess.run([program, "--version"], capture_output=True, text=True, check=True,
                                 timeout=60).stdout.strip()
    except (OSError, subprocess.SubprocessError) as e:
        raise ProgramError(f"{program}: does not run ({e})") from None
    data = hashlib.sha256()
    files = [os.path.join(data_dir, "views.json")]
    paths = os.path.join(data_dir, "paths")
    if os.path.isdir(paths):
        files += sorted(os.path.join(paths, f) for f in os.listdir(paths) if f.endswith(".json"))
    for f in files:
        if not os.path.isfile(f):
            raise ProgramError(f"{f}: missing (the data directory '{data_dir}' has no views)")
        data.update(os.path.relpath(f, data_dir).encode())
        _sha256(f, data)
    return {"version": version, "program": _sha256(program).hexdigest()[:16], "data": data.hexdigest()[:16]}


# CLI11's help: "  --name TYPE..." takes a value, "  --name   description" is a flag.
_OPTION = re.compile(r"^\s+(?:-\w,)?--([a-z][a-z0-9-]*)(\s+[A-Z]+\b|\s*$|\s{2,})")


@functools.lru_cache(maxsize=None)
def eval_options(program):
    """{name: takes_value} for every option of `shadowkit eval`, read from its --help."""
    try:
        help_text = subprocess.run([program, "eval", "--help"], capture_output=True, text=True, check=True,
                                   timeout=60).stdout
    except (OSError, subprocess.SubprocessError) as e:
        raise ProgramError(f"{program} eval --help: failed ({e})") from None
    options = {}
    for line in help_text.splitlines():
        m = _OPTION.match(line)
        if m:
            options[m.group(1)] = bool(m.group(2).strip()) and m.group(2).strip().isupper()
    options.pop("help", None)
    if "technique" not in options:
        raise ProgramError(f"{program} eval --help: no --technique in its options (not shadowkit?)")
    return options
