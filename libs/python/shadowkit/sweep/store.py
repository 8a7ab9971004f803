"""A sweep's results on disk, resumable.

OUT/cells.jsonl is the record: one line per measured cell ({key, options, labels, fingerprint,
seconds, host, rows}), appended and flushed as each cell finishes, so an interrupted sweep
loses at most the cells in flight (a line cut short by a kill is ignored on the next run).
A re-run skips the keys it holds. Cells measured by another program or other data (their
fingerprint differs) are reported, never mixed into the tables. OUT/results.csv and
OUT/results.jsonl (one row per cell and view, or per frame of a path) are written from the
record, in the specification's order. OUT/failures.jsonl keeps the cells that failed, with
their error; they are tried again on the next run.
"""
import csv
import json
import os


class StoreError(RuntimeError):
    """A one-line description of why the output directory cannot be used."""


def describe(fingerprint):
    """'shadowkit 0.1.0, program 5ef836be, data 668a3cd7': a fingerprint in a message."""
    return (f"{fingerprint.get('version', '?')}, program {str(fingerprint.get('program', '?'))[:8]}, "
            f"data {str(fingerprint.get('data', '?'))[:8]}")


class Store:
    def __init__(self, directory, fingerprint):
        self.directory = directory
        self.fingerprint = fingerprint
        try:
            os.makedirs(directory, exist_ok=True)
        except OSError as e:
            raise StoreError(f"--out {directory}: cannot create ({e.strerror})") from None
        self.path = os.path.join(directory, "cells.jsonl")
        self.done = {}  # key -> record, this fingerprint's
        self.stale = []  # records of another program or data
        self.cut_short = 0  # lines an interrupted run left incomplete
        if os.path.exists(self.path):
            with open(self.path) as f:
                for line in f:
                    try:
                        record = json.loads(line)
                        record["key"], record["rows"]
                    except (ValueError, KeyError, TypeError):
                        self.cut_short += 1
                        continue
                    if record.get("fingerprint") != fingerprint:
                        self.stale.append(record)
                    else:
                        self.done[record["key"]] = record
        self._file = None
        if self.cut_short:
            self._rewrite()  # the next cell's line must not continue a cut one

    def refuse_stale(self, discard):
        """StoreError when the directory holds another program's results, unless `discard`: then
        they are moved to cells.stale.jsonl and the sweep starts afresh beside them."""
        if not self.stale:
            return
        theirs = describe(self.stale[0].get("fingerprint") or {})
        if not discard:
            raise StoreError(f"--out {self.directory}: {len(self.stale)} cells were measured by another shadowkit or "
                             f"data ({theirs}; this is {describe(self.fingerprint)}): give another --out, or "
                             f"--discard-stale")
        with open(os.path.join(self.directory, "cells.stale.jsonl"), "a") as f:
            for record in self.stale:
                f.write(json.dumps(record, sort_keys=True) + "\n")
        self.stale = []
        self._rewrite()

    def _rewrite(self):
        temporary = self.path + ".tmp"
        with open(temporary, "w") as f:
            for record in [*self.stale, *self.done.values()]:
                f.write(json.dumps(record, sort_keys=True) + "\n")
        os.replace(temporary, self.path)

    def add(self, record):
        """Appends a measured cell; False (and nothing written) when its key is already held, so a
        cell that reaches the client twice (a worker lost after finishing) gives one row."""
        if "error" in record:
            with open(os.path.join(self.directory, "failures.jsonl"), "a") as f:
                f.write(json.dumps(record, sort_keys=True) + "\n")
            return False
        if record["key"] in self.done:
            return False
        if self._file is None:
            self._file = open(self.path, "a")
        self._file.write(json.dumps(record, sort_keys=True) + "\n")
        self._file.flush()
        os.fsync(self._file.fileno())
        self.done[record["key"]] = record
        return True

    def close(self):
        if self._file is not None:
            self._file.close()
            self._file = None

    def rows(self, keys):
        """Rows of the cells `keys` (in that order) that are measured: the cell's key, its bundle
        labels, its options (hyphens as underscores) and every figure of its report. Where the report
        states an option's value (technique, map_size, filter) the column holds what eval used, and
        a given value that differs (technique=auto) stays as NAME_given."""
        out = []
        for key in keys:
            record = self.done.get(key)
            if record is None:
                continue
            for figures in record["rows"]:
                row = {"cell": key, **record["labels"]}
                row.update({name.replace("-", "_"): value for name, value in record["options"].items()})
                for name, value in figures.items():
                    if name in row and name != "cell" and str(row[name]) != str(value):
                        row[name + "_given"] = row[name]
                    row[name] = value
                out.append(row)
        return out

    def write_tables(self, keys):
        """results.csv and results.jsonl from the record (atomically: a reader never sees half)."""
        rows = self.rows(keys)
        columns = []
        seen = set()
        for row in rows:
            for name in row:
                if name not in seen:
                    seen.add(name)
                    columns.append(name)
        csv_path = os.path.join(self.directory, "results.csv")
        with open(csv_path + ".tmp", "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=columns, restval="")
            writer.writeheader()
            for row in rows:
                writer.writerow({k: json.dumps(v) if isinstance(v, (list, dict)) else v for k, v in row.items()})
        os.replace(csv_path + ".tmp", csv_path)
        jsonl_path = os.path.join(self.directory, "results.jsonl")
        with open(jsonl_path + ".tmp", "w") as f:
            for row in rows:
                f.write(json.dumps(row) + "\n")
        os.replace(jsonl_path + ".tmp", jsonl_path)
        return rows
