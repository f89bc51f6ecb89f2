"""Type stubs of the extension module `netspec._netspec` (re-exported by `netspec`)."""

from os import PathLike
from typing import Any, Callable, Mapping, Sequence, final

_Path = str | PathLike[str]
_Point = Sequence[float] | Mapping[str, float]

class SpecError(ValueError):
    field: str | None
    path: str

class NetspecError(RuntimeError): ...

@final
class Progress:
    elapsed: float
    incumbent: float | None
    bound: float | None
    nodes: int

@final
class Drawn(dict[str, Any]):
    @property
    def svg(self) -> str: ...
    def _repr_svg_(self) -> str: ...

class Spec:
    @staticmethod
    def from_toml(text: str, base: _Path | None = None) -> Spec: ...
    @staticmethod
    def from_json(text: str, base: _Path | None = None) -> Spec: ...
    @staticmethod
    def from_dict(data: Mapping[str, Any], base: _Path | None = None) -> Spec: ...
    @staticmethod
    def read(path: _Path) -> Spec: ...
    @property
    def name(self) -> str: ...
    @property
    def description(self) -> str: ...
    @property
    def path(self) -> str | None: ...
    def to_dict(self) -> dict[str, Any]: ...
    def build(self, formulation: str | None = None, max_cells: int | None = None) -> Model: ...

@final
class Model:
    @property
    def name(self) -> str: ...
    @property
    def sense(self) -> str: ...
    @property
    def num_vars(self) -> int: ...
    @property
    def num_rows(self) -> int: ...
    @property
    def num_nonzeros(self) -> int: ...
    @property
    def num_integers(self) -> int: ...
    @property
    def compact(self) -> bool: ...
    def column_names(self) -> list[str]: ...
    def row_names(self) -> list[str]: ...
    def column(self, name: str) -> dict[str, Any]: ...
    def row(self, name: str) -> dict[str, Any]: ...
    def objective_value(self, values: _Point) -> float: ...
    def write(self, path: _Path) -> None: ...
    def solve(
        self,
        solver: str | None = None,
        time_limit: float | None = None,
        threads: int | None = None,
        gap: float | None = None,
        seed: int | None = None,
        start: _Point | None = None,
        on_progress: Callable[[Progress], object] | None = None,
    ) -> ModelResult: ...

@final
class ModelResult:
    @property
    def termination(self) -> str: ...
    @property
    def status(self) -> str: ...
    @property
    def objective(self) -> float | None: ...
    @property
    def bound(self) -> float | None: ...
    @property
    def gap(self) -> float | None: ...
    @property
    def time(self) -> float: ...
    @property
    def nodes(self) -> int | None: ...
    @property
    def solver(self) -> str: ...
    @property
    def valid(self) -> bool: ...
    @property
    def x(self) -> list[float] | None: ...
    def values(self) -> dict[str, float] | None: ...
    def to_dict(self) -> dict[str, Any]: ...
    def summary(self) -> str: ...

@final
class Design:
    edges: list[tuple[int, int]]
    points: list[tuple[float, float]]
    metrics: dict[str, Any]

@final
class Result:
    @property
    def status(self) -> str: ...
    @property
    def termination(self) -> str: ...
    @property
    def objective(self) -> float | None: ...
    @property
    def bound(self) -> float | None: ...
    @property
    def gap(self) -> float | None: ...
    @property
    def time(self) -> float: ...
    @property
    def solver_time(self) -> float | None: ...
    @property
    def nodes(self) -> int | None: ...
    @property
    def valid(self) -> bool: ...
    @property
    def design(self) -> Design | None: ...
    @property
    def explanation(self) -> dict[str, Any] | None: ...
    def to_dict(self) -> dict[str, Any]: ...
    def write(self, dir: _Path) -> str: ...
    def to_geojson(self) -> str | None: ...
    def svg(self) -> str | None: ...
    def _repr_svg_(self) -> str | None: ...

def read_spec(path: _Path) -> Spec: ...
def read_model(path: _Path) -> Model: ...
def check(model: Model, values: _Point) -> dict[str, Any]: ...
def solve(
    spec: Spec | _Path,
    solver: str | None = None,
    formulation: str | None = None,
    time_limit: float | None = None,
    threads: int | None = None,
    gap: float | None = None,
    seed: int | None = None,
    start: bool = True,
    explain: bool = False,
    on_progress: Callable[[Progress], object] | None = None,
) -> Result: ...
def compare(
    specs: _Path | Sequence[_Path],
    solvers: Sequence[str] | None = None,
    formulations: Sequence[str] | None = None,
    time_limit: float = 60.0,
    seeds: Sequence[int] | None = None,
    threads: int | None = None,
    start: bool = True,
    rows: Sequence[str] | None = None,
    out: _Path | None = None,
) -> list[dict[str, Any]]: ...
def csv_columns() -> list[str]: ...
def records_csv(records: list[dict[str, Any]]) -> str: ...
def solvers() -> list[dict[str, Any]]: ...
def level(
    spec: _Path,
    solver: str | None = None,
    method: str = "both",
    time_limit: float = 60.0,
    threads: int | None = None,
    seed: int = 1,
    count: int = 1,
    explain: bool = True,
    out: _Path | None = None,
) -> dict[str, Any]: ...
def city(
    spec: _Path,
    solver: str | None = None,
    time_limit: float | None = None,
    threads: int | None = None,
    threads_per_solve: int | None = None,
    gap: float | None = None,
    fresh: bool = False,
    out: _Path | None = None,
    on_progress: Callable[[Progress], object] | None = None,
) -> dict[str, Any]: ...
def site(
    extract: _Path,
    out: _Path,
    bbox: tuple[float, float, float, float] | Sequence[float] | None = None,
    polygon: _Path | None = None,
    holes: Sequence[str] | None = None,
    major: Sequence[str] | None = None,
    service: bool = False,
    grow: bool = False,
    city: bool = False,
    largest: bool = False,
    name: str | None = None,
    exclude: Sequence[int] | None = None,
) -> dict[str, Any]: ...
def stats(
    designs: Sequence[_Path],
    labels: Sequence[str] | None = None,
    region: _Path | None = None,
    reference: str | None = None,
    clean_int_tol: float = 10.0,
    metres_per_unit: float | None = None,
    window: tuple[float, float, float, float] | Sequence[float] | None = None,
    out: _Path | None = None,
) -> list[dict[str, Any]]: ...
def layout(
    region: _Path,
    out: _Path | None = None,
    seed: int | None = None,
    variations: int = 1,
    field: str = "distance",
    mode: str = "best",
    optimise: int = 0,
    from_layout: _Path | None = None,
    relayout: str | None = None,
    on_progress: Callable[[int, float], object] | None = None,
) -> list[Drawn]: ...
def field(
    region: _Path,
    out: _Path,
    method: str = "distance",
    h: float | None = None,
) -> dict[str, Any]: ...
def grow(
    context: _Path,
    out: _Path,
    seed: int | None = None,
    steps: int | None = None,
    every: int | None = None,
    all_streets: bool = False,
    gallery: int | None = None,
    window: tuple[float, float, float, float] | Sequence[float] | None = None,
    on_progress: Callable[[int, int], object] | None = None,
) -> dict[str, Any]: ...
def traffic(
    designs: Sequence[_Path],
    out: _Path = "out/traffic",
    labels: Sequence[str] | None = None,
    duration: float = 3600.0,
    through_rate: float = 300.0,
    local_rate: float = 600.0,
    seed: int = 1,
    metres_per_unit: float | None = None,
    level: int | None = None,
    window: tuple[float, float, float, float] | Sequence[float] | None = None,
    region: _Path | None = None,
    trade: _Path | None = None,
    trade_rate: float = 300.0,
    sumo_home: _Path | None = None,
    time_limit: float | None = None,
) -> dict[str, Any]: ...
def version() -> str: ...
