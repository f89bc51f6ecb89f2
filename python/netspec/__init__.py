"""netspec: network design from functional specifications by integer programming, on
interchangeable MILP backends (HiGHS, CBC, SCIP, microlp).

The library's own API: read a spec, build its MILP, solve it on any compiled backend, check
the answer independently, compare backends; and the urban methods (levels, cities, real sites,
layouts, fields, grown networks, traffic, street statistics). See docs/python.md.
"""

from __future__ import annotations

from typing import Any, Iterable, Mapping, Sequence

from ._netspec import (
    Design,
    Drawn,
    Model,
    ModelResult,
    NetspecError,
    Progress,
    Result,
    Spec,
    SpecError,
    check,
    city,
    compare,
    csv_columns,
    field,
    grow,
    layout,
    level,
    read_model,
    read_spec,
    records_csv,
    site,
    solve,
    solvers,
    stats,
    traffic,
    version,
)

__all__ = [
    "Design",
    "Drawn",
    "Model",
    "ModelResult",
    "NetspecError",
    "Progress",
    "Result",
    "Spec",
    "SpecError",
    "check",
    "city",
    "compare",
    "csv_columns",
    "field",
    "grow",
    "layout",
    "level",
    "read_model",
    "read_spec",
    "records_csv",
    "records_frame",
    "site",
    "solve",
    "solvers",
    "stats",
    "stats_frame",
    "traffic",
    "version",
]

__version__: str = version()


def records_frame(records: Iterable[Mapping[str, Any]]) -> Any:
    """The records of `compare` as a pandas DataFrame with the columns of `results.csv`, in
    its order (pandas is an optional dependency: `pip install netspec[pandas]`)."""
    try:
        import pandas as pd
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError("records_frame needs pandas: pip install pandas") from e
    columns: Sequence[str] = csv_columns()
    rows = [{c: r.get(c) for c in columns} for r in records]
    return pd.DataFrame(rows, columns=list(columns))


def stats_frame(designs: Iterable[Mapping[str, Any]]) -> Any:
    """The designs of `stats` as a pandas DataFrame, one row per design: its label and kind,
    every street statistic, and its mean distance to the reference (pandas is an optional
    dependency)."""
    try:
        import pandas as pd
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError("stats_frame needs pandas: pip install pandas") from e
    rows = []
    for d in designs:
        distance = d.get("distance") or {}
        rows.append({"label": d["label"], "kind": d["kind"], **d["stats"], "distance": distance.get("mean")})
    return pd.DataFrame(rows)

