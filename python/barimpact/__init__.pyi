"""barimpact: bodies hitting each other along a line (Do, Raupp & Feijoo 1979)."""
import os
from pathlib import Path
from typing import Any, Callable, Iterable, Mapping, Sequence, Union

import numpy as np
import numpy.typing as npt

from ._core import Case as Case
from ._core import InputError as InputError
from ._core import MissingModuleError as MissingModuleError
from ._core import OutOfMemoryError as OutOfMemoryError
from ._core import OutputError as OutputError
from ._core import Result as Result

__all__ = ["Case", "Result", "InputError", "OutputError", "OutOfMemoryError", "MissingModuleError", "HealthWarning", "StrictError", "Table", "HopkinsonTable",
           "PdaTable", "MatchTable",
           "RunData", "run", "check", "exact", "converge", "sweep", "bearing", "drive", "inspector", "hammers", "hopkinson", "pda", "match", "plot", "load",
           "read_table", "exact_example1"]

_PathArg = Union[str, os.PathLike[str]]
_CaseLike = Union[Case, _PathArg, Mapping[str, Any]]
_Overrides = Union[Mapping[str, Any], Sequence[str], None]
_Progress = Callable[[dict[str, Any]], object]

class RunData:
    """A run directory read back for the figures (barimpact.plot.RunData): history columns, field
    snapshots, the case and summary as dicts."""

    history: dict[str, npt.NDArray[np.float64]]
    x: npt.NDArray[np.float64]
    field_t: npt.NDArray[np.float64]
    u: npt.NDArray[np.float64]
    sigma: npt.NDArray[np.float64]
    case: dict[str, Any]
    summary: dict[str, Any]
    body: npt.NDArray[Any] | None
    eps_p: npt.NDArray[np.float64] | None
    def __init__(self, history: dict[str, npt.NDArray[np.float64]], x: npt.NDArray[np.float64],
                 field_t: npt.NDArray[np.float64], u: npt.NDArray[np.float64], sigma: npt.NDArray[np.float64],
                 case: dict[str, Any], summary: dict[str, Any], body: npt.NDArray[Any] | None = None,
                 eps_p: npt.NDArray[np.float64] | None = None, case_source: Any = None) -> None: ...
    @property
    def columns(self) -> tuple[str, ...]: ...
    def __getitem__(self, column: str) -> npt.NDArray[np.float64]: ...
    def __contains__(self, column: object) -> bool: ...
    def __getattr__(self, name: str) -> npt.NDArray[np.float64]: ...
    def to_pandas(self) -> Any: ...

class HealthWarning(UserWarning):
    """A run's health checks warned; the results are kept."""

class StrictError(RuntimeError):
    """strict=True and the health checks warned (the command's exit 4); the results are written."""

    result: Any
    warnings: list[str]
    def __init__(self, message: str, result: Any, warnings: Iterable[str]) -> None: ...

class Table(dict[str, npt.NDArray[Any]]):
    """A results table: columns by name as numpy arrays, in the CSV's order."""

    summary: dict[str, Any] | None
    def __init__(self, columns: Mapping[str, npt.NDArray[Any]] | Iterable[tuple[str, npt.NDArray[Any]]] = ...,
                 summary: dict[str, Any] | None = None) -> None: ...
    def __getattr__(self, name: str) -> npt.NDArray[Any]: ...
    @property
    def columns(self) -> tuple[str, ...]: ...
    @property
    def rows(self) -> int: ...
    def row(self, i: int) -> dict[str, Any]: ...
    def to_pandas(self) -> Any:
        """A pandas.DataFrame of the same columns."""

class HopkinsonTable(Table):
    """hopkinson.csv's columns, with summary.json as `summary`."""

class PdaTable(Table):
    """pda.csv's columns, with summary.json as `summary`."""

class MatchTable(Table):
    """match.csv's columns, with summary.json as `summary`, soil.csv as `soil` and static.csv as `static`."""

    soil: Table | None
    static: Table | None
    def __init__(self, columns: Mapping[str, npt.NDArray[Any]] | Iterable[tuple[str, npt.NDArray[Any]]] = ...,
                 summary: dict[str, Any] | None = None, soil: Table | None = None,
                 static: Table | None = None) -> None: ...

def run(case: _CaseLike, progress: _Progress | None = None, *, out: _PathArg | None = None, set: _Overrides = None,
        force: bool = False, strict: bool = False) -> Result:
    """barimpact run CASE [--out DIR] [--set ...] [--force] [--strict]."""

def check(case: _CaseLike, *, set: _Overrides = None) -> dict[str, Any]:
    """barimpact check CASE [--set ...]: steps, stable step, penalty time constants, a time estimate."""

def exact(case: _CaseLike, *, out: _PathArg | None = None, set: _Overrides = None, force: bool = False,
          strict: bool = False) -> Result:
    """barimpact exact CASE [--out DIR] [--set ...] [--force] [--strict]."""

def converge(case: _CaseLike, out: _PathArg | None = None, *, set: _Overrides = None, levels: int = 4, ratio: int = 2,
             refine: str | None = None, vary: str | tuple[str, str | Sequence[Any]] | None = None,
             schemes: str | Sequence[str] | None = None, reference: str = "auto", jobs: int | None = None,
             no_plot: bool = False, force: bool = False, strict: bool = False) -> Table:
    """barimpact converge CASE --out DIR [--levels N] [--ratio R] [--refine ...] [--vary ...] [--schemes ...]
    [--reference ...] [--jobs N] [--set ...] [--force] [--strict]: convergence.csv's table."""

def sweep(sweep_file: _PathArg | Mapping[str, Any], out: _PathArg, *, jobs: int | None = None, no_batch: bool = False,
          force: bool = False, strict: bool = False) -> Table:
    """barimpact sweep SWEEP --out DIR [--jobs N] [--no-batch] [--force] [--strict]: sweep.csv's table."""

def bearing(case: _PathArg, out: _PathArg, capacity: str | tuple[float, float, int], toe_share: float | None = None,
            jobs: int | None = None, plot: bool = True, force: bool = False, *, no_plot: bool = False,
            strict: bool = False, set: _Overrides = None) -> Table:
    """barimpact bearing CASE --out DIR --capacity FROM:TO:COUNT [--toe-share S] [--set K=V] [--jobs N] [--no-plot]
    [--force] [--strict]: bearing.csv's table."""

def drive(case: _PathArg, out: _PathArg, jobs: int | None = None, *, no_plot: bool = False, force: bool = False,
          strict: bool = False, set: _Overrides = None) -> Table:
    """barimpact drive CASE --out DIR [--set K=V] [--jobs N] [--no-plot] [--force] [--strict]: drive.csv's table."""

def inspector(case: _PathArg, out: _PathArg, stroke: str | tuple[float, float, int], depth: float | None = None,
              jobs: int | None = None, *, no_plot: bool = False, force: bool = False, strict: bool = False,
              set: _Overrides = None) -> Table:
    """barimpact inspector CASE --out DIR --stroke FROM:TO:COUNT [--depth D]: inspector.csv's table."""

def hammers() -> Table:
    """barimpact hammers: the shipped hammer table."""

def hopkinson(setup: _PathArg | Mapping[str, Any], out: _PathArg | None = None, *, no_plot: bool = False,
              force: bool = False, strict: bool = False) -> HopkinsonTable:
    """barimpact hopkinson SETUP [--out DIR] [--no-plot] [--force] [--strict]: hopkinson.csv's table."""

def pda(record: _PathArg | Mapping[str, Any], out: _PathArg | None = None, *, no_plot: bool = False,
        force: bool = False) -> PdaTable:
    """barimpact pda RECORD [--out DIR] [--no-plot] [--force]: pda.csv's table."""

def match(record: _PathArg | Mapping[str, Any], out: _PathArg | None = None, *, no_plot: bool = False,
          force: bool = False, jobs: int | None = 0, strict: bool = False) -> MatchTable:
    """barimpact match RECORD [--out DIR] [--no-plot] [--jobs N] [--force] [--strict]: match.csv's table, soil.csv and
    static.csv."""

def plot(dir: _PathArg | Result | RunData, out: _PathArg | None = None, *, force: bool = False,
         formats: Sequence[str] = ("png", "svg")) -> list[Path]:
    """barimpact plot DIR [--out FIGURES] [--force], or the figures of a Result into `out`."""

def load(run_dir: _PathArg, with_fields: bool = True) -> RunData:
    """A directory written by `barimpact run`, read back for the figures:
    history.csv and fields.csv, or results.h5 (`[output] format = "hdf5"`,
    read with h5py), the same RunData; with_fields=False leaves the fields unread."""

def read_table(path: _PathArg) -> Table:
    """convergence.csv, sweep.csv, bearing.csv or hopkinson.csv (a file, or the directory holding it)."""

def exact_example1(x: npt.ArrayLike, t: npt.ArrayLike, length: float = 1.0, stiffness: float = 1.0,
                   density: float = 1.0, v0: float = -1.0) -> dict[str, npt.NDArray[np.float64]]:
    """The paper's Example 1 with a rigid obstacle (exact): arrays u, v, strain, R broadcast over x and t."""
