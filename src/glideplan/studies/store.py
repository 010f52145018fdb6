"""A resumable results store for studies: one SQLite file, one atomic commit per work unit.

The file holds the study's full configuration (canonical JSON, seed included) and, for every
finished work unit, its rows in a results table, written in the same transaction as the
unit's entry in `units`. A study killed at any instant (Ctrl-C, kill -9, power loss) leaves
only whole units behind (SQLite's journal rolls back a half-written transaction), so a
restart redoes exactly the missing units. Opening a file written with another configuration,
or a file that is not a readable results store, raises `ResultsFileError`; results of
different configurations are never mixed.
"""

from __future__ import annotations

import json
import pathlib
import sqlite3
from collections.abc import Iterable, Mapping, Sequence
from typing import Any

from glideplan.errors import ResultsFileError

__all__ = ["FORMAT", "ResultsStore", "canonical_json"]

FORMAT = "glideplan-study-1"


def canonical_json(data: Any) -> str:
    """Deterministic JSON (sorted keys, no whitespace) used to compare configurations."""
    return json.dumps(data, sort_keys=True, separators=(",", ":"), allow_nan=False)


def _differences(a: Mapping[str, Any], b: Mapping[str, Any]) -> list[str]:
    keys = sorted(set(a) | set(b))
    return [k for k in keys if canonical_json(a.get(k)) != canonical_json(b.get(k))]


class ResultsStore:
    """A study's results file (see module docstring).

    `columns` names the results table's columns (SQLite type affinities), `key` the columns
    that identify one row (a duplicate is an error, never silently overwritten).
    """

    def __init__(
        self,
        path: str | pathlib.Path,
        config: Mapping[str, Any],
        *,
        kind: str,
        columns: Sequence[tuple[str, str]],
        key: Sequence[str],
    ) -> None:
        self.path = pathlib.Path(path)
        self.config = dict(config)
        self.kind = kind
        self.columns = tuple(columns)
        self._conn = self._open(key)

    # ----- opening and validation -----------------------------------------------------------
    def _open(self, key: Sequence[str]) -> sqlite3.Connection:
        exists = self.path.exists()
        if exists and not self.path.is_file():
            raise ResultsFileError(f"results file {self.path} is not a regular file")
        try:
            conn = sqlite3.connect(self.path, timeout=60.0, isolation_level=None)
            conn.execute("PRAGMA journal_mode=WAL")
            conn.execute("PRAGMA synchronous=NORMAL")
            if exists:
                self._check(conn)
            else:
                self._create(conn, key)
        except sqlite3.DatabaseError as exc:
            raise ResultsFileError(
                f"results file {self.path} is not a readable glideplan study ({exc}); "
                "move it away or choose another output directory"
            ) from None
        return conn

    def _create(self, conn: sqlite3.Connection, key: Sequence[str]) -> None:
        cols = ", ".join(f"{name} {kind}" for name, kind in self.columns)
        conn.execute("BEGIN IMMEDIATE")
        conn.execute("CREATE TABLE meta (key TEXT PRIMARY KEY, value TEXT NOT NULL)")
        conn.execute(
            "CREATE TABLE units (unit INTEGER PRIMARY KEY, rows INTEGER NOT NULL, "
            "seconds REAL NOT NULL)"
        )
        conn.execute(f"CREATE TABLE results ({cols}, PRIMARY KEY ({', '.join(key)}))")
        conn.executemany(
            "INSERT INTO meta VALUES (?, ?)",
            [("format", FORMAT), ("kind", self.kind), ("config", canonical_json(self.config))],
        )
        conn.execute("COMMIT")

    def _check(self, conn: sqlite3.Connection) -> None:
        ok = conn.execute("PRAGMA quick_check").fetchone()
        if not ok or ok[0] != "ok":
            raise ResultsFileError(f"results file {self.path} is corrupt ({ok[0] if ok else ''})")
        try:
            meta = dict(conn.execute("SELECT key, value FROM meta").fetchall())
        except sqlite3.DatabaseError:
            raise ResultsFileError(f"{self.path} is not a glideplan results file") from None
        if meta.get("format") != FORMAT or meta.get("kind") != self.kind:
            raise ResultsFileError(
                f"{self.path} is not a {self.kind!r} results file of format {FORMAT}"
            )
        try:
            stored = json.loads(meta["config"])
        except (KeyError, ValueError):
            raise ResultsFileError(f"{self.path}: stored configuration is unreadable") from None
        if canonical_json(stored) != canonical_json(self.config):
            diff = ", ".join(_differences(stored, self.config)) or "?"
            raise ResultsFileError(
                f"{self.path} holds a study with a different configuration (differs in: {diff}); "
                "use another output directory or the same settings to resume it"
            )
        names = [r[1] for r in conn.execute("PRAGMA table_info(results)").fetchall()]
        if names != [c[0] for c in self.columns]:
            raise ResultsFileError(f"{self.path}: results table has unexpected columns {names}")
        bad = conn.execute(
            "SELECT COUNT(*) FROM units u WHERE u.rows != "
            "(SELECT COUNT(*) FROM results r WHERE r.unit = u.unit)"
        ).fetchone()[0]
        if bad:
            raise ResultsFileError(f"{self.path}: {bad} unit(s) have missing or extra rows")

    # ----- use ----------------------------------------------------------------------------
    def done_units(self) -> set[int]:
        """Indices of the work units already stored."""
        return {r[0] for r in self._conn.execute("SELECT unit FROM units")}

    def add_unit(self, unit: int, rows: Iterable[Sequence[Any]], seconds: float) -> None:
        """Store one unit's rows atomically (all or nothing); each row starts with `unit`."""
        rows = list(rows)
        marks = ", ".join("?" for _ in self.columns)
        conn = self._conn
        conn.execute("BEGIN IMMEDIATE")
        try:
            conn.execute("INSERT INTO units VALUES (?, ?, ?)", (int(unit), len(rows), seconds))
            conn.executemany(f"INSERT INTO results VALUES ({marks})", rows)
        except BaseException:
            conn.execute("ROLLBACK")
            raise
        conn.execute("COMMIT")

    def query(self, sql: str, params: Sequence[Any] = ()) -> list[tuple[Any, ...]]:
        """Run a read-only query on the store (tables: meta, units, results)."""
        return self._conn.execute(sql, params).fetchall()

    def close(self) -> None:
        self._conn.close()

    def __enter__(self) -> ResultsStore:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
