"""What reading a field file says instead of failing obscurely: cfgrib's skipped variables
as one warning (its log captured, no traceback on stderr), and a file with no finite current
refused by its name (`glideplan.fields.io` calls both)."""

from __future__ import annotations

import contextlib
import re
from collections.abc import Iterator
from typing import Any

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.fields.field import NODATA_FLOOR

__all__ = ["SKIPPED_ATTR", "quiet_cfgrib", "refuse_all_nan"]


#: Dataset attribute carrying the notes of what a reader skipped (popped by `open_field`).
SKIPPED_ATTR = "glideplan_skipped"


@contextlib.contextmanager
def quiet_cfgrib() -> Iterator[list[str]]:
    """Capture cfgrib's log records (its "skipping variable: ..." with a traceback, which
    Python's last-resort handler would print on stderr) and the readers' Python warnings;
    yield the list the skipped variables' names are added to ("t2m (paramId 167)")."""
    import logging
    import warnings

    skipped: list[str] = []

    class _Capture(logging.Handler):
        def emit(self, record: logging.LogRecord) -> None:
            m = re.search(r"skipping variable: paramId==(\d+) shortName='([^']*)'",
                          record.getMessage())
            if m:
                skipped.append(f"{m.group(2)} (paramId {m.group(1)})")

    log = logging.getLogger("cfgrib")
    handler, propagate = _Capture(), log.propagate
    log.addHandler(handler)
    log.propagate = False
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            yield skipped
    finally:
        log.removeHandler(handler)
        log.propagate = propagate


def refuse_all_nan(u: np.ndarray, v: np.ndarray, source: str, nodata: Any) -> None:
    """A file with no finite current at all is refused by its name (it is not "land"): the
    depth range's fault when it reaches below the sea floor at every wet node."""
    if np.isfinite(u).any() and np.isfinite(v).any():
        return
    if nodata is not None and np.any(nodata == NODATA_FLOOR):
        raise InvalidParameterError("depth_range", source, "reaches below the sea floor at "
                                    "every node with water: no current over that layer "
                                    "anywhere; give a shallower depth range")
    raise InvalidParameterError("field", source, "every current value in the file is NaN "
                                "(no data: fill values only)")
