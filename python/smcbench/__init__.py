"""smcbench from Python: solve box-MLCPs, nonlinear MCPs and affine variational inequalities (AVIs) with smcbench's
backends, read and write AVI files, judge an answer against a certified reference, benchmark a suite of one's own
problems or MCPs, simulate the sliding-mode scenes of Acary & Brogliato (2009), read and write .smcps problem sets,
load `smcbench bench` results, report on them and compare two runs as `smcbench report` and `smcbench compare` do.
`python -m smcbench ARGS` runs the command-line program shipped in the package (__main__.py).

numpy in, numpy out. The C++ core is the extension `smcbench._smcbench`; this file turns Python's conventions
(None bounds, scalars, scipy.sparse, keyword options) into its arguments and its dicts into result objects.
Invalid input raises `smcbench.InvalidInputError`, a `ValueError` carrying the C++ library's message.
See docs/python.md.
"""

from __future__ import annotations

import contextlib
import json
import os
import shutil
import tempfile
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, Iterable, Iterator, List, NamedTuple, Optional, Union

import numpy as np

from . import _smcbench
from ._smcbench import AffineVI, InvalidInputError, scenes, scenes_directory

__all__ = [
    "InvalidInputError", "SolveResult", "Simulation", "Problem", "McpProblem", "solvers", "solve", "solve_mcp",
    "judge_mcp", "bench_mcp", "simulate", "scenes", "scenes_directory", "read_problem_set", "write_problem_set",
    "load_bench_results", "bench", "AffineVI", "AviResult", "AviFile", "AviProblem", "solve_avi", "read_avi",
    "write_avi", "judge", "report", "report_tables", "compare", "Comparison",
]


@dataclass
class SolveResult:
    """What one solve returned (the fields of the C++ SolveResult).

    status: the status name ("solved", "iteration_limit", "infeasible", ...); solved: status == "solved".
    z, w: the returned point and F(z) (M z + q for a box-MLCP). residual_*: the merit function at z
    (docs/verdict.md). time_seconds: wall time of the C++ Solve call. details: backend-specific numbers, and codes
    by name (lemke's "free_row_mode": "schur"; auto's "chosen": "enum"; an external adapter's "in_process": "worker").
    solver: the backend that was asked; chosen: for "auto", the backend whose answer this is (else None).
    verdict, forward_error, reference: with solve(..., reference=...), the bench's verdict on the answer, ‖z − z*‖∞
    against the certified reference (NaN when z* is not certified the only solution) and that reference (judge()'s
    "reference" dict); None otherwise.
    """

    status: str
    solved: bool
    z: np.ndarray
    w: np.ndarray
    iterations: int
    residual_abs: float
    residual_rel: float
    residual_scaled: float
    time_seconds: float
    details: Dict[str, Union[float, str]]
    solver: str
    chosen: Optional[str]
    message: str
    verdict: Optional[str] = None
    forward_error: Optional[float] = None
    reference: Optional[Dict[str, Any]] = None


def _result(raw: dict) -> SolveResult:
    return SolveResult(solved=raw["status"] == "solved", **raw)


def solvers() -> List[dict]:
    """The registered backends: dicts with name, algorithm, reference, dense, sparse, symmetric_only, exact, mcp,
    default_size_limit and options (the help text of their backend options)."""
    return _smcbench.solvers()


def _is_sparse(matrix: Any) -> bool:
    try:
        import scipy.sparse
    except ImportError:  # no scipy: nothing can be a scipy matrix
        return False
    return scipy.sparse.issparse(matrix)


def _csc_tuple(matrix: Any, what: str) -> tuple:
    """A scipy.sparse matrix as (rows, cols, indptr, indices, data) of its CSC form, int32 indices."""
    csc = matrix.tocsc()
    if csc.nnz > np.iinfo(np.int32).max:
        raise InvalidInputError(f"{what}: {csc.nnz} stored entries exceed the int32 indices of the C++ core")
    return (csc.shape[0], csc.shape[1], np.asarray(csc.indptr, dtype=np.int32),
            np.asarray(csc.indices, dtype=np.int32), np.asarray(csc.data, dtype=np.float64))


def _bound(value: Any, default: float, size: int, what: str) -> np.ndarray:
    """A bound vector: None → default everywhere, a scalar → that value everywhere, else the array itself."""
    if value is None:
        return np.full(size, default)
    array = np.asarray(value, dtype=np.float64)
    if array.ndim == 0:
        return np.full(size, float(array))
    return array  # its size is checked by the C++ core (message names l or u)


def _size_of(q: Any) -> int:
    return int(np.asarray(q).reshape(-1).shape[0]) if np.ndim(q) == 1 else -1


def solve(M, q, l=None, u=None, solver: str = "auto", tol: float = 1e-10, time_limit: Optional[float] = None, *,
          z0=None, max_iterations: Optional[int] = None, polish: bool = True, reference=None,
          **backend_options) -> SolveResult:
    """Solve the box-MLCP  M z + q = w − v,  l ≤ z ≤ u,  w, v ≥ 0,  (z − l)ᵀw = 0,  (u − z)ᵀv = 0.

    M: a dense array (any float dtype or contiguity; copied) or a scipy.sparse matrix (as CSC; backends that
    take sparse M natively: see solvers(), e.g. newton; dense-only ones solve a dense copy up to 4096 rows).
    q: the vector q. l, u: bounds; None means l = 0 and u = +inf (the standard LCP), a scalar is used on every
    row (l=-1, u=1: the relay problem), np.inf / -np.inf are allowed (l = -inf, u = inf: a free row).
    solver: a name from solvers(); "auto" picks per problem (docs/auto.md). tol: the relative and scaled merit
    tolerance of "solved". time_limit: seconds (None: no limit). z0: warm start. max_iterations: None = the
    backend's default. polish: the exact polish of the answer (on by default, as in the CLI).
    backend_options: the backend's typed options by name (solvers()[i]["options"]; `--set` in the CLI), e.g.
    solve(M, q, solver="psor", omega=1.2). reference: None (the default) leaves the answer unjudged; True judges
    it as judge() does against the library's certified reference; an array z* is certified and judged against:
    the result's verdict, forward_error and reference are then set.

    Raises InvalidInputError (a ValueError) for NaN/inf in M or q, NaN bounds, l > u, size mismatches, an
    unknown solver or option, or an invalid option value.
    """
    matrix, q_vec, l_vec, u_vec = _box_arrays(M, q, l, u)
    result = _result(_smcbench._solve(matrix, q_vec, l_vec, u_vec, solver, float(tol), time_limit, z0,
                                      max_iterations, polish, backend_options))
    if reference is not None and reference is not False:
        judged = _smcbench._judge(matrix, q_vec, l_vec, u_vec, result.z, result.status, float(tol),
                                  None if reference is True else reference, "unknown")
        result.verdict, result.forward_error = judged["verdict"], judged["forward_error"]
        result.reference = judged["reference"]
    return result


def _box_arrays(M, q, l, u):
    """M, q, l, u as the C++ core takes a box-MLCP: sparse M as its CSC tuple, bounds as vectors (_bound)."""
    m = _size_of(q)
    matrix = _csc_tuple(M, "M") if _is_sparse(M) else M
    return matrix, q, _bound(l, 0.0, max(m, 0), "l"), _bound(u, np.inf, max(m, 0), "u")


def judge(M, q, l, u, z, status: str = "solved", tol: float = 1e-10, reference=None,
          expected: str = "unknown") -> dict:
    """The verdict `smcbench bench` gives the answer z with status (a SolveResult.status name) to the box-MLCP
    (M, q, l, u as in solve(): None bounds are l = 0, u = +inf; scalars are used on every row): the library's Judge
    (docs/verdict.md). Residuals are recomputed from z; "solved" needs them ≤ tol and, where the reference is
    certified the only solution, ‖z − z*‖∞ within the allowance 10·max(1, μ)·tol·(1 + ‖z*‖∞).

    reference: a known solution z*, certified here in extended precision (Certify); None: the library's certified
    reference, from z itself and the answers of lemke, enum and newton (problems of up to 64 rows; larger ones get
    none). expected: "unknown", "solvable" or "infeasible" (a refusal of a solvable problem is WRONGLY REFUSED).
    Returns the dict of judge_mcp (verdict, wrong, residual_abs/rel/scaled, forward_error, forward_error_rel,
    forward_allowance; NaN where no unique reference defines them) and "reference": the reference used
    (certificate, z, condition, proved_radius, proved_unique). Bad input raises InvalidInputError naming the field."""
    matrix, q_vec, l_vec, u_vec = _box_arrays(M, q, l, u)
    return _smcbench._judge(matrix, q_vec, l_vec, u_vec, z, str(status), float(tol), reference, str(expected))


def _default_mcp_solver() -> str:
    """"auto" when the registry says auto solves MCPs (SolverInfo::mcp), else "newton"; asked at every call."""
    backends = {b["name"]: b for b in solvers()}
    return "auto" if backends.get("auto", {}).get("mcp") else "newton"


def _mcp_arrays(F, J, l, u, where: str):
    """The checked callables and bound vectors of an MCP (scalar bounds broadcast to the other bound's size).
    J may be None (differences of F, _DifferenceJacobian)."""
    for name, value in (("F", F), ("J", J)):
        if value is None and name == "J":
            continue
        if not callable(value):
            raise InvalidInputError(f"{where}: {name} must be callable (z -> array) or None (differences of F), "
                                    f"got {type(value).__name__}" if name == "J" else
                                    f"{where}: {name} must be callable (z -> array), got {type(value).__name__}")
    l_vec = np.asarray(l, dtype=np.float64)
    u_vec = np.asarray(u, dtype=np.float64)
    for name, value in (("l", l_vec), ("u", u_vec)):
        if value.ndim > 1:
            raise InvalidInputError(f"{where}: {name}: expected a 1-D array or a scalar, got shape {value.shape}")
    if l_vec.ndim == 0 and u_vec.ndim == 0:
        raise InvalidInputError(f"{where}: l and u are both scalars: give at least one bound vector (size n)")
    n = l_vec.shape[0] if l_vec.ndim == 1 else u_vec.shape[0]
    return _bound(l_vec, 0.0, n, "l"), _bound(u_vec, 0.0, n, "u")


_DERIVATIVE_METHODS = ("auto", "complex-step", "central")


class _DifferenceJacobian:
    """The Jacobian of F without a hand-written J, a dense (n, n) array per call.

    "central": central differences, column j from F(z ± h_j e_j) with h_j = ε^(1/3)·max(1, |z_j|); where a point
    would leave [l_j, u_j], one-sided inward with h_j = ε^(1/2)·max(1, |z_j|) (F is then only called in the box),
    as CentralDifferenceJacobian in C++ (solvers/core/mcp_derivatives.h). 2n calls of F per Jacobian.
    "complex-step": J[:, j] = Im F(z + i·h e_j) / h, h = 1e-20: exact to rounding, for an F written with
    complex-safe operations (numpy arithmetic, np.exp, np.sin, ...; not abs, max, comparisons). n calls of F.
    "auto": at the first call, complex step if F returns complex values for a complex z and its Jacobian there
    agrees with central differences (relative 1e-5), else central; the choice is kept (method_used)."""

    def __init__(self, F: Callable, l_vec: np.ndarray, u_vec: np.ndarray, method: str, where: str):
        if method not in _DERIVATIVE_METHODS:
            raise InvalidInputError(f"{where}: derivatives must be one of {', '.join(_DERIVATIVE_METHODS)}, "
                                    f"got {method!r}")
        self.F, self.l, self.u, self.where = F, l_vec, u_vec, where
        self.method_used = None if method == "auto" else method

    def _value(self, z: np.ndarray) -> np.ndarray:
        return np.asarray(self.F(z)).reshape(-1)

    def central(self, z: np.ndarray) -> np.ndarray:
        eps = np.finfo(np.float64).eps
        z = np.asarray(z, dtype=np.float64)
        n = z.shape[0]
        columns = []
        for j in range(n):
            scale = max(1.0, abs(z[j]))
            h, h1 = np.cbrt(eps) * scale, np.sqrt(eps) * scale
            plus, minus = z[j] + h, z[j] - h
            if minus < self.l[j] and z[j] + h1 <= self.u[j]:
                plus, minus = z[j] + h1, z[j]
            elif plus > self.u[j] and z[j] - h1 >= self.l[j]:
                plus, minus = z[j], z[j] - h1
            zp, zm = z.copy(), z.copy()
            zp[j], zm[j] = plus, minus
            columns.append((self._value(zp).astype(np.float64) - self._value(zm).astype(np.float64)) /
                           (zp[j] - zm[j]))
        return np.column_stack(columns) if columns else np.zeros((0, 0))

    def complex_step(self, z: np.ndarray) -> np.ndarray:
        z = np.asarray(z, dtype=np.float64)
        n = z.shape[0]
        h = 1e-20
        columns = []
        for j in range(n):
            zc = z.astype(np.complex128)
            zc[j] += 1j * h
            value = self._value(zc)
            if not np.iscomplexobj(value):
                raise TypeError("F returned real values for a complex z")
            columns.append(value.imag / h)
        return np.column_stack(columns) if columns else np.zeros((0, 0))

    def _choose(self, z: np.ndarray) -> None:
        """auto: complex step when F takes complex input and agrees with central differences at z."""
        import warnings

        central = self.central(z)
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("error")  # numpy's ComplexWarning: F dropped the imaginary part
                by_complex = self.complex_step(z)
        except Exception:  # F does not take complex input: any error means central differences
            self.method_used = "central"
            return
        agree = np.all(np.abs(by_complex - central) <= 1e-5 * np.maximum(1.0, np.abs(central)))
        self.method_used = "complex-step" if agree else "central"

    def __call__(self, z: np.ndarray) -> np.ndarray:
        if self.method_used is None:
            self._choose(z)
        return self.complex_step(z) if self.method_used == "complex-step" else self.central(z)


def _jacobian_for_core(J: Optional[Callable], where: str, F: Optional[Callable] = None, l_vec=None, u_vec=None,
                       derivatives: str = "auto") -> Callable:
    """J as the C++ core takes it: a scipy.sparse value becomes its CSC tuple, a dense one passes unchanged; J None
    is the differences of F (_DifferenceJacobian)."""
    if J is None:
        return _DifferenceJacobian(F, l_vec, u_vec, derivatives, where)
    if derivatives != "auto":
        raise InvalidInputError(f"{where}: derivatives={derivatives!r} applies when J is None (J was given)")

    def jacobian(z: np.ndarray):
        value = J(z)
        return _csc_tuple(value, f"{where}: J(z)") if _is_sparse(value) else value

    return jacobian


def _optional_vector(value) -> Optional[np.ndarray]:
    return None if value is None else np.asarray(value, dtype=np.float64)


def solve_mcp(F: Callable, J: Optional[Callable], l, u, z0=None, solver: Optional[str] = None, tol: float = 1e-10,
              time_limit: Optional[float] = None, *, max_iterations: Optional[int] = None, variable_scale=None,
              derivatives: str = "auto", derivative_test: bool = False, derivative_test_tol: float = 1e-4,
              **backend_options) -> SolveResult:
    """Solve the nonlinear MCP: z in [l, u] with −F(z) in the normal cone of [l, u] at z, i.e. per row
    F_i(z) ≥ 0 at z_i = l_i, F_i(z) ≤ 0 at z_i = u_i, F_i(z) = 0 strictly inside.

    F(z) -> array of shape (n,); J(z) -> the Jacobian dF/dz, a dense (n, n) array or a scipy.sparse matrix.
    Both are called with a float64 array z of shape (n,) while the backend runs (it releases the GIL and takes it
    back for each call). l, u: bound vectors (scalars are used on every row; ±np.inf allowed); z0: the start
    point (default: the projection of 0 onto the box); a z0 outside [l, u] is projected onto the box and the
    result's details start_projected / start_projection_distance say how far (every backend). solver: any backend
    with mcp=True in solvers(); None (the
    default) is "auto" when the registry says auto solves MCPs, else "newton". variable_scale: the units c_i > 0
    of the variables (default 1), so that residual_scaled, the scale-free MCP residual, does not change with them.
    An exception raised by F or J stops the solve and is raised from solve_mcp; a result of the wrong shape, a
    non-callable F or J, bad bounds or sizes, an unknown backend or one that does not solve MCPs raise
    InvalidInputError naming the field.
    The Jacobian's kind (dense or sparse) is taken from J's value at the (projected) start: a sparse J is handed to
    the backends' sparse paths.
    J=None: no hand-written Jacobian; derivatives says how it is computed from F: "auto" (the default: complex step
    when F accepts a complex z and agrees with central differences at the first point, else central differences),
    "complex-step" or "central" (per-component steps, inside the box). details["jacobian"] names the method used.
    derivative_test=True (Ipopt's derivative_test): before the solve, J at the start point is compared with central
    differences; an entry off by more than derivative_test_tol·max(1, |difference|) makes the result's message start
    with "derivative check: J[i, j] = ... but central differences give ..." and raises a RuntimeWarning;
    details["derivative_check_error"] is the largest relative difference.
    """
    l_vec, u_vec = _mcp_arrays(F, J, l, u, "solve_mcp")
    name = _default_mcp_solver() if solver is None else solver
    jacobian = _jacobian_for_core(J, "solve_mcp", F, l_vec, u_vec, derivatives)
    result = _result(_smcbench._solve_mcp(F, jacobian, l_vec, u_vec, z0, _optional_vector(variable_scale), name,
                                          float(tol), time_limit, max_iterations, backend_options,
                                          bool(derivative_test), float(derivative_test_tol)))
    if isinstance(jacobian, _DifferenceJacobian) and jacobian.method_used is not None:
        result.details["jacobian"] = jacobian.method_used
    if derivative_test and result.details.get("derivative_check_error", 0.0) > derivative_test_tol:
        import warnings

        warnings.warn(f"solve_mcp: {result.message.split('; ')[0]}", RuntimeWarning, stacklevel=2)
    return result


def _references(references, solution, where: str) -> List[dict]:
    """References as the core takes them: dicts {"z", "certificate", "condition"}. A bare array is a verified
    solution not known to be the only one ("isolated"); `solution` is the problem's one solution ("unique")."""
    out = []
    if solution is not None:
        out.append({"z": np.asarray(solution, dtype=np.float64), "certificate": "unique", "condition": 0.0})
    for k, r in enumerate(references or []):
        if isinstance(r, dict):
            unknown = sorted(set(r) - {"z", "certificate", "condition"})
            if unknown or "z" not in r:
                raise InvalidInputError(f"{where}: references[{k}]: a dict with 'z' and optionally 'certificate', "
                                        f"'condition' (got keys {sorted(r)})")
            out.append({"z": np.asarray(r["z"], dtype=np.float64),
                        "certificate": str(r.get("certificate", "isolated")),
                        "condition": float(r.get("condition", 0.0))})
        else:
            out.append({"z": np.asarray(r, dtype=np.float64), "certificate": "isolated", "condition": 0.0})
    return out


def judge_mcp(F: Callable, J: Callable, l, u, z, status: str = "solved", tol: float = 1e-10, references=None,
              references_complete: bool = False, expected: str = "unknown", *, variable_scale=None) -> dict:
    """The verdict `smcbench bench` gives an answer z with status (a SolveResult.status name) to the MCP (F, J, l,
    u): JudgeMCP (docs/verdict.md). The residuals are recomputed from z (the scale-free one with J at z); "solved"
    requires residual_scaled ≤ tol and, where a reference defines it, a forward error within its allowance.
    references: known solutions, each an array (a verified solution, certificate "isolated") or a dict {"z",
    "certificate" ("unique", "degenerate", "isolated", "non-unique"), "condition" (μ of docs/verdict.md, default
    0)}; references_complete: they are every solution (the nearest one is then used); expected: "unknown",
    "solvable" or "infeasible". Returns a dict: verdict ("solved", "failed", "WRONGLY CLAIMED", "INACCURATE", ...),
    wrong (a wrong answer: wrongly claimed, inaccurate or wrongly refused), residual_abs, residual_rel,
    residual_scaled, forward_error, forward_error_rel, forward_allowance (NaN where no reference defines them)."""
    l_vec, u_vec = _mcp_arrays(F, J, l, u, "judge_mcp")
    problem = {"F": F, "J": _jacobian_for_core(J, "judge_mcp", F, l_vec, u_vec), "l": l_vec, "u": u_vec,
               "variable_scale": _optional_vector(variable_scale),
               "references": _references(references, None, "judge_mcp"),
               "references_complete": bool(references_complete), "expected": str(expected)}
    return _smcbench._judge_mcp(problem, z, str(status), float(tol))


@dataclass
class McpProblem:
    """A nonlinear MCP of a user's suite for bench_mcp: z in [l, u] with −F(z) in the normal cone at z.

    id: unique in the suite. F, J, l, u as in solve_mcp (J None: differences of F, derivatives="auto"; their
    calls are then part of the timed solves). starts: the starting points (each one is a job; None: the
    projection of 0 onto the box, labelled "cold"; an entry None: that projection too); start_labels: their names
    (None: "start1", "start2", ...).
    solution: the problem's unique solution, if known (judged by forward error, certificate "unique"); references:
    more known solutions as in judge_mcp; references_complete: the references (and solution) are every solution.
    expected: "solvable" (default), "infeasible" or "unknown". variable_scale: the variables' units (solve_mcp)."""

    id: str
    F: Callable
    J: Optional[Callable]
    l: Any
    u: Any
    starts: Optional[List[Any]] = None
    start_labels: Optional[List[str]] = None
    solution: Optional[Any] = None
    references: Optional[List[Any]] = None
    references_complete: bool = False
    expected: str = "solvable"
    variable_scale: Optional[Any] = None
    source: str = "python"
    tags: List[str] = field(default_factory=list)

    def solve(self, start: int = 0, solver: Optional[str] = None, **kwargs) -> SolveResult:
        """solve_mcp on this problem from starts[start] (None: from the projection of 0)."""
        z0 = None if self.starts is None else self.starts[start]
        return solve_mcp(self.F, self.J, self.l, self.u, z0=z0, solver=solver, variable_scale=self.variable_scale,
                         **kwargs)

    def _starts(self, l_vec: np.ndarray, u_vec: np.ndarray):
        if self.starts is None:
            if l_vec.shape != u_vec.shape:  # the core's message names l and u
                return [np.zeros(0)], ["cold"]
            return [np.clip(0.0, l_vec, u_vec)], ["cold"]
        cold = np.clip(0.0, l_vec, u_vec) if l_vec.shape == u_vec.shape else np.zeros(0)
        starts = [cold if s is None else np.asarray(s, dtype=np.float64) for s in self.starts]
        labels = list(self.start_labels) if self.start_labels is not None else [f"start{k + 1}" for k in
                                                                                 range(len(starts))]
        return starts, labels

    def _core(self, index: int) -> dict:
        """This problem as the C++ core takes it (bench_mcp)."""
        where = f"bench_mcp: problems[{index}] ('{self.id}')"
        l_vec, u_vec = _mcp_arrays(self.F, self.J, self.l, self.u, where)
        starts, labels = self._starts(l_vec, u_vec)
        return {"id": str(self.id), "F": self.F, "J": _jacobian_for_core(self.J, where, self.F, l_vec, u_vec),
                "l": l_vec, "u": u_vec,
                "variable_scale": _optional_vector(self.variable_scale), "starts": starts,
                "start_labels": [str(label) for label in labels],
                "references": _references(self.references, self.solution, where),
                "references_complete": bool(self.references_complete), "expected": str(self.expected),
                "source": str(self.source), "tags": [str(t) for t in self.tags]}


_BENCH_MCP_COLUMNS = ["problem", "start", "solver", "size", "expected", "status", "verdict", "wrong", "iterations",
                      "residual_abs", "residual_rel", "residual_scaled", "tolerance", "forward_error",
                      "forward_error_rel", "forward_allowance", "time_median", "time_min", "time_max", "samples",
                      "solves_per_sample", "certificate", "tags", "message"]


def bench_mcp(problems: Iterable[McpProblem], solvers: Optional[List[str]] = None, tol: float = 1e-10,
              repetitions: int = 5, time_limit: float = 10.0, *, out=None):
    """Benchmark a suite of McpProblem on MCP backends as `smcbench bench` does: a pandas DataFrame with one row per
    problem × start × backend (columns: problem, start, solver, size, expected, status, verdict, wrong, iterations,
    residual_abs/rel/scaled, tolerance, forward_error, forward_error_rel, forward_allowance, time_median/min/max,
    samples, solves_per_sample, certificate, tags, message), in suite, start, backend order. The records are written
    as `smcbench bench --out` writes them (results.json, results.csv; suite "python") to the folder out (None: a
    temporary one), so report(out) or report(df) makes their report.

    solvers: a backend name or a list of them (None: every registered backend with mcp=True). Each problem × start × backend is solved
    once untimed, then `repetitions` timed samples (a sample repeats the solve until it lasts 0.2 ms; at most 2 s per
    row); times are per solve, in seconds, and include the calls into F and J. The timing loop runs in C++ without
    the GIL. The last answer is judged by JudgeMCP, the verdict of judge_mcp and of `smcbench bench`. time_limit:
    seconds per solve. An exception raised by F or J ends the benchmark and is raised here; bad input (duplicate
    ids, starts of the wrong size, NaN bounds, an unknown backend or one that does not solve MCPs) raises
    InvalidInputError naming the problem and the field."""
    import pandas as pd  # imported here: the rest of the module does not need pandas

    suite = []
    for index, p in enumerate(problems):
        if not isinstance(p, McpProblem):
            raise InvalidInputError(f"bench_mcp: problems[{index}] is a {type(p).__name__}, expected McpProblem")
        suite.append(p._core(index))
    names = [solvers] if isinstance(solvers, str) else list(solvers or [])
    with _results_output(out) as folder:
        rows = _smcbench._bench_mcp(suite, names, float(tol), int(repetitions), float(time_limit), "python", folder)
        return _with_results(pd.DataFrame.from_records(rows, columns=_BENCH_MCP_COLUMNS), folder, out)


@dataclass
class PlantRows:
    """A ZOH run's plant between samples (plant_substeps = S > 1): S·steps + 1 rows, the samples and the plant's
    exact state at S − 1 points between each two, as `smcbench simulate --out` writes them. t (rows,), x (rows, n);
    s, y, u (rows, m): between samples s is the multiplier of the held input and u the input held."""

    t: np.ndarray
    x: np.ndarray
    s: np.ndarray
    y: np.ndarray
    u: np.ndarray


@dataclass
class Simulation:
    """A recorded run of a scene. Rows are steps k = 0 .. steps: t (steps+1,), x (steps+1, n), s and y
    (steps+1, m); row 0 is the initial state (s_0 = 0). u (steps+1, m): the control input applied over
    [t_k, t_k+1) (the u columns of `smcbench simulate --out`; the last row NaN), None when the run has no input.
    iterations, residual and status describe the one-step problem that produced row k (row 0: none). summary:
    the JSON summary of `smcbench simulate --summary` (steps, x_final, reaching_step, s_error_max / y_error_max
    against a certified reference run, ...). plant: the plant between samples (PlantRows) for a ZOH run with
    plant_substeps > 1, else None. notes: overrides that had no effect (the CLI's "note:" lines)."""

    scene: str
    description: str
    solver: Optional[str]
    t: np.ndarray
    x: np.ndarray
    s: np.ndarray
    y: np.ndarray
    iterations: np.ndarray
    residual: np.ndarray
    status: List[str]
    summary: dict
    wall_seconds: float
    u: Optional[np.ndarray] = None
    plant: Optional[PlantRows] = None
    notes: List[str] = field(default_factory=list)


_SIMULATE_OVERRIDES = ("method", "h", "T", "theta", "gamma", "x0", "parameters", "solver", "tol", "max_iterations",
                       "warm_start", "polish", "on_failure", "algorithm", "newton_tol", "newton_max_iterations",
                       "reach_tol", "plant_substeps", "reference")


def simulate(scene, *, backend_options: Optional[dict] = None, **overrides) -> Simulation:
    """Run a scene with implicit (or explicit / ZOH) Euler, as `smcbench simulate` does.

    scene: a registered name (smcbench.scenes()), the path of a scene file, or a dict in the scene JSON format
    (problems/scenes/README.md). overrides (each default: the scene's own value): method ("implicit",
    "explicit", "zoh", "zoh-explicit"), h, T, theta, gamma, x0, parameters (dict name → value), solver (default:
    the scene's, else "auto"), tol (1e-10), max_iterations, warm_start (True), polish (True), on_failure
    ("stop" | "continue"), algorithm ("newton-mlcp" | "mcp", nonlinear scenes), newton_tol,
    newton_max_iterations, reach_tol (10·tol), plant_substeps (ZOH methods: S > 1 fills Simulation.plant with
    the plant's state at S − 1 points between samples; default: the scene's), reference (True: run the certified
    reference run for the summary's s_error_max / y_error_max; False skips that second run). backend_options: the
    backend's typed options (the CLI's --set). The rules and messages are `smcbench simulate`'s. An unknown
    override raises TypeError; a bad value InvalidInputError.
    """
    unknown = sorted(set(overrides) - set(_SIMULATE_OVERRIDES))
    if unknown:
        raise TypeError(f"simulate: unknown override(s) {', '.join(unknown)} (known: {', '.join(_SIMULATE_OVERRIDES)})")
    settings = _smcbench._SimulateOverrides()
    for name, value in overrides.items():
        if name == "parameters":
            value = {str(k): float(v) for k, v in value.items()}
        elif name in ("h", "T", "theta", "gamma", "tol", "newton_tol", "reach_tol"):
            value = float(value)
        elif name == "x0":
            value = np.asarray(value, dtype=np.float64)
        setattr(settings, name, value)
    if isinstance(scene, dict):
        raw = _smcbench._simulate(json.dumps(scene), True, settings, backend_options or {})
    elif isinstance(scene, (str, os.PathLike)):
        raw = _smcbench._simulate(os.fspath(scene), False, settings, backend_options or {})
    else:
        raise TypeError(f"simulate: scene must be a name, a path or a dict, got {type(scene).__name__}")
    raw["summary"] = json.loads(raw.pop("summary_json"))
    if raw["plant"] is not None:
        raw["plant"] = PlantRows(**raw["plant"])
    return Simulation(**raw)


@dataclass
class Problem:
    """One problem of a .smcps set: the box-MLCP (M dense ndarray or scipy.sparse.csc_matrix; q, l, u) with the
    library's metadata: id (unique in the set), source, tags, seed, expected ("unknown", "solvable",
    "infeasible"), solution (a known z, or None), metadata (str → str), matrix (symmetric / positive_definite /
    p_matrix: "yes", "no", "unknown") and reference (certificate, z, condition of the certified reference;
    proved_radius and proved_unique, its interval proof, computed on reading and never written)."""

    id: str
    M: Any
    q: np.ndarray
    l: np.ndarray
    u: np.ndarray
    source: str = "python"
    tags: List[str] = field(default_factory=list)
    seed: Optional[int] = None
    expected: str = "unknown"
    solution: Optional[np.ndarray] = None
    metadata: Dict[str, str] = field(default_factory=dict)
    matrix: Dict[str, str] = field(default_factory=dict)
    reference: Dict[str, Any] = field(default_factory=dict)

    def solve(self, solver: str = "auto", **kwargs) -> SolveResult:
        """smcbench.solve on this problem."""
        return solve(self.M, self.q, self.l, self.u, solver=solver, **kwargs)


def read_problem_set(path) -> List[Union[Problem, "AviProblem"]]:
    """The problems of a .smcps file (problems/library/README.md), in file order: a list of Problem for a set of
    box-MLCPs, a list of AviProblem for a set of AVIs (format version 4; `smcbench library --write-suite avi
    FILE.smcps` writes one). One file holds one kind, so the list does too; its attribute .kind says which ("box"
    or "avi"), and .name, .description, .version are the set's name, description and format version."""
    path = os.fspath(path)
    if _smcbench._problem_set_kind(path) == "avi":
        raw = _smcbench._read_avi_problem_set(path)
        problems = _ProblemList(AviProblem(**d) for d in raw["problems"])
        problems.kind = "avi"
    else:
        raw = _smcbench._read_problem_set(path)
        problems = _ProblemList(_problem_from_dict(d) for d in raw["problems"])
    problems.name, problems.description, problems.version = raw["name"], raw["description"], raw["version"]
    return problems


class _ProblemList(list):
    """A list of Problem (kind "box") or of AviProblem (kind "avi") with the set's name, description and version."""

    kind: str = "box"
    name: str = ""
    description: str = ""
    version: int = 0


def _problem_from_dict(d: dict) -> Problem:
    if isinstance(d["M"], tuple):
        import scipy.sparse
        rows, cols, indptr, indices, data = d["M"]
        d["M"] = scipy.sparse.csc_matrix((data, indices, indptr), shape=(rows, cols))
    return Problem(**d)


def write_problem_set(path, problems: Iterable, name: str = "python", description: str = "") -> None:
    """Write problems as a .smcps file: box-MLCPs (Problem objects, or dicts with at least id, M, q, l, u; bounds
    may be None, l = 0, u = +inf, or scalars as in solve()), or AVIs (AviProblem objects, or AffineVI objects, whose
    name is then the id), written as a set of AVIs (format version 4). A file holds one kind: mixing them is an
    error. Raises InvalidInputError for an invalid problem or a duplicate or empty id; the file is written under a
    temporary name and renamed, so a failed write leaves no partial file.

    AVIs keep the reference they carry (read_problem_set's, as read); `smcbench library FILE --certify OUT` certifies
    the AVIs that have none."""
    items = list(problems)
    avis = [isinstance(p, (AviProblem, AffineVI)) for p in items]
    if any(avis):
        if not all(avis):
            raise InvalidInputError("write_problem_set: a .smcps set holds box problems or AVIs, not both: "
                                    f"problems[{avis.index(False)}] is not an AviProblem or AffineVI")
        dicts = []
        for p in items:
            entry = AviProblem(id=p.name, avi=p) if isinstance(p, AffineVI) else p
            d = dict(entry.__dict__)
            if not d["reference"]:
                del d["reference"]
            dicts.append(d)
        _smcbench._write_avi_problem_set(os.fspath(path), dicts, name, description)
        return
    dicts = []
    for p in items:
        d = dict(p.__dict__) if isinstance(p, Problem) else dict(p)
        m = _size_of(d.get("q"))
        d["l"] = _bound(d.get("l"), 0.0, max(m, 0), "l")
        d["u"] = _bound(d.get("u"), np.inf, max(m, 0), "u")
        if _is_sparse(d.get("M")):
            d["M"] = _csc_tuple(d["M"], "M")
        for key in ("reference", "matrix"):
            if key in d and not d[key]:
                del d[key]
        dicts.append(d)
    _smcbench._write_problem_set(os.fspath(path), dicts, name, description)


def bench(suites, solvers=None, tol: float = 1e-10, repetitions: int = 7, time_limit: float = 10.0, *,
          settings: Optional[List[str]] = None, quick: bool = False, polish: bool = True, warm: bool = True,
          backend_budget: float = 60.0, job_budget: float = 1.0, sequence_budget: float = 1.0, siconos_dir=None,
          problems: Optional[List[str]] = None, out=None):
    """Run a benchmark as `smcbench bench` does, through the same engine: a pandas DataFrame with the columns of
    results.csv, one row per record (problem × backend, then the tolerance sweep's rows, mode "sweep", then the warm
    track's rows, mode "warm": one per sequence × backend, seconds per step; warm=False skips them, as --no-warm).

    suites: a suite name ("tiny", "paper", "families", "hard", "siconos", "scale", "mcp", "avi", "all"), the path of
    a .smcps file, a list of those, or a list of Problem or of AviProblem (read_problem_set's list, or your own),
    run as one suite named "python". solvers: a backend name or a list (None: every registered backend). settings: typed backend options
    "BACKEND.OPTION=VALUE". quick, polish, backend_budget (seconds per backend and suite, 0: no limit),
    job_budget (seconds per cold job), sequence_budget (seconds per warm sequence × backend; 0: no limit, as
    `bench --full` sets all three) and siconos_dir (None: bench's default) as the flags of `smcbench bench`; no time-stepper studies. problems: globs
    over problem ids, as `smcbench bench --problem` (a str or a list; None: every problem), e.g.
    problems=["mcp/classic/*"]: only the problems whose id matches one run; a glob that matches none raises
    InvalidInputError. out: a folder to
    keep results.json and results.csv in (None: a temporary one). Bad input (an unknown suite or backend, a
    rejected setting, tol <= 0, repetitions < 1, ...) raises InvalidInputError naming it, before anything runs."""
    import pandas as pd  # imported here: the rest of the module does not need pandas

    items = [suites] if isinstance(suites, (str, os.PathLike, Problem, AviProblem)) else list(suites)
    globs = [problems] if isinstance(problems, str) else list(problems or [])
    given = [item for item in items if isinstance(item, (Problem, AviProblem))]
    names = [solvers] if isinstance(solvers, str) else list(solvers or [])
    with tempfile.TemporaryDirectory(prefix="smcbench-bench-") as scratch:
        if given:
            if len(given) != len(items):
                raise InvalidInputError("bench: suites: give suite names and files, or a list of Problem (or of "
                                        "AviProblem), not both")
            path = os.path.join(scratch, "python.smcps")
            write_problem_set(path, given, name="python", description="problems given to smcbench.bench")
            paths = [path]
        else:
            paths = [os.fspath(item) for item in items]
        folder = os.fspath(out) if out is not None else os.path.join(scratch, "results")
        _smcbench._bench(paths, names, list(settings or []), float(tol), int(repetitions), float(time_limit),
                         float(backend_budget), float(job_budget), float(sequence_budget), bool(quick), bool(polish), bool(warm),
                         "" if siconos_dir is None else os.fspath(siconos_dir), globs, folder)
        return _with_results(_with_text_columns(pd.read_csv(os.path.join(folder, "results.csv")), folder), folder,
                             out)


def _with_text_columns(frame, folder: str):
    """results.csv's frame with the record fields results.csv leaves out, tags and message, from results.json (the
    same records in the same order, _record_rows), as the last columns; "" where a record has none."""
    with open(os.path.join(folder, "results.json"), encoding="utf-8") as f:
        rows = _record_rows(json.load(f), sweep=True, warm=True)
    if len(rows) != len(frame):
        raise RuntimeError(f"bench: results.json holds {len(rows)} records but results.csv {len(frame)} rows")
    for column in ("tags", "message"):
        frame[column] = [str(r.get(column, "")) for r in rows]
    return frame


@contextlib.contextmanager
def _results_output(out):
    """The folder a run writes its results to: out, or a temporary one removed afterwards."""
    if out is not None:
        yield os.fspath(out)
        return
    with tempfile.TemporaryDirectory(prefix="smcbench-results-") as scratch:
        yield os.path.join(scratch, "results")


def _with_results(frame, folder: str, out):
    """frame with what report() and compare() need to find the run again: attrs "results_json" (the text of
    results.json, kept when the folder was temporary) and "results_dir" (out, or None)."""
    with open(os.path.join(folder, "results.json"), encoding="utf-8") as f:
        frame.attrs["results_json"] = f.read()
    frame.attrs["results_dir"] = None if out is None else os.fspath(out)
    return frame


def _record_rows(document: dict, sweep: bool, warm: bool) -> List[dict]:
    """The records of a results.json document in results.csv's order: per suite the cold records, then (sweep) the
    tolerance sweep's, then (warm) the warm track's."""
    rows = []
    for suite in document.get("suites", []):
        rows.extend(suite.get("records", []))
        if sweep:
            rows.extend(suite.get("sweep", []))
        if warm:
            rows.extend(suite.get("warm", []))
    return rows


def load_bench_results(path, include_sweep: bool = True):
    """A pandas DataFrame of a `smcbench bench` results.json (format smcbench-bench/1): one row per problem ×
    backend record, with the columns of results.csv (suite, problem, solver, mode, size, sparse, expected, status,
    verdict, iterations, residual_abs/rel/scaled, tolerance, time_median/min/max/mad, samples, solves_per_sample,
    forward_error, forward_error_rel, forward_allowance, certificate, reference_radius, reference_proved_unique,
    tags, message). include_sweep adds the
    tolerance-sweep records (mode "sweep"). The run's command, environment and format are in df.attrs.
    path: the results.json file or the folder holding it."""
    import pandas as pd  # imported here: the rest of the module does not need pandas

    path = os.fspath(path)
    if os.path.isdir(path):
        path = os.path.join(path, "results.json")
    with open(path, encoding="utf-8") as f:
        text = f.read()
    document = json.loads(text)
    if not str(document.get("format", "")).startswith("smcbench-bench/"):
        raise InvalidInputError(f"'{path}': not a smcbench bench results file (format {document.get('format')!r}, "
                                "expected smcbench-bench/1)")
    frame = pd.DataFrame.from_records(_record_rows(document, include_sweep, warm=False))
    frame.attrs.update({key: document.get(key) for key in ("format", "command", "environment", "polish")})
    frame.attrs.update({"results_json": text, "results_dir": os.path.dirname(path) or "."})
    return frame


class _ResultsFolder(NamedTuple):
    """Where results.json of a run is (folder) and how the report and compare.md name it (name: the folder as the
    user gave it, or where bench() kept it; "(results in memory)" for a DataFrame whose folder was temporary)."""

    folder: str
    name: str


def _results_folder(results, what: str, scratch: str) -> _ResultsFolder:
    """The folder holding results.json of `results`: a `smcbench bench --out` folder, its results.json, or a
    DataFrame of bench(), bench_mcp() or load_bench_results() (its attrs "results_json", written to a folder in
    scratch). InvalidInputError naming `what` otherwise."""
    if isinstance(results, (str, os.PathLike)):
        path = os.fspath(results)
        folder = os.path.dirname(path) or "." if os.path.isfile(path) else path
        if not os.path.isfile(os.path.join(folder, "results.json")):
            raise InvalidInputError(f"{what}: '{path}' is not a results folder (no results.json in it): give a "
                                    "`smcbench bench --out` folder, its results.json, or what bench() returned")
        return _ResultsFolder(folder, folder)
    attrs = getattr(results, "attrs", None)
    text = attrs.get("results_json") if isinstance(attrs, dict) else None
    if not text:
        raise InvalidInputError(f"{what}: expected a results folder, its results.json, or the DataFrame of bench(), "
                                f"bench_mcp() or load_bench_results(); got {type(results).__name__}")
    folder = tempfile.mkdtemp(prefix=what + "-", dir=scratch)
    with open(os.path.join(folder, "results.json"), "w", encoding="utf-8") as f:
        f.write(text)
    return _ResultsFolder(folder, attrs.get("results_dir") or "(results in memory)")


def report(results, out=None, *, plots: bool = False) -> str:
    """The report `smcbench report DIR` writes (report.md: verdict counts, timing, tolerance ladder, ... per suite),
    made by the same C++ code (WriteBenchReport) and returned as markdown text.

    results: a `smcbench bench --out` folder, its results.json, or the DataFrame bench(), bench_mcp() or
    load_bench_results() returned. out: a folder to write report.md (and, with plots, its PNG figures) to; None
    writes nothing (the results folder is never touched unless it is out). plots: draw the figures (needs gnuplot,
    as the command without --no-plots). InvalidInputError for anything else, or for plots without gnuplot."""
    with tempfile.TemporaryDirectory(prefix="smcbench-report-") as scratch:
        source = _results_folder(results, "report", scratch)
        work = os.path.join(scratch, "report")  # made here, so that the results folder is left as it is
        os.mkdir(work)
        shutil.copyfile(os.path.join(source.folder, "results.json"), os.path.join(work, "results.json"))
        # The report names the folder it was made in: the results' own, as `smcbench report DIR` would.
        markdown = _smcbench._report(work, bool(plots)).replace(work, source.name)
        if out is not None:
            os.makedirs(os.fspath(out), exist_ok=True)
            with open(os.path.join(os.fspath(out), "report.md"), "w", encoding="utf-8") as f:
                f.write(markdown)
            for name in os.listdir(work):
                if name not in ("results.json", "report.md"):
                    shutil.copyfile(os.path.join(work, name), os.path.join(os.fspath(out), name))
        return markdown


# Columns of report_tables() that hold measurements (kept float even when every value is a whole number).
_MEASURED = ("time", "ratio", "error", "residual", "tolerance", "success", "/ floor", "min", "max")


def report_tables(results) -> Dict[str, Any]:
    """The tables report.md is rendered from, as pandas DataFrames: one per table, columns named as the report's
    markdown names them, computed by the same C++ functions (bench/analysis/report_tables.h). Keys, in order:
    "summary" (per problem class), "failures" (per backend), then with a column "suite": "backends", "statuses",
    "audit", "bands", "ladder", "sweep", "peers", "profiles". Counts are ints; times in seconds, ratios and errors
    are floats (NaN where the report leaves a blank or a "–").

    results: as for report(): a `smcbench bench --out` folder, its results.json, or a DataFrame of bench(),
    bench_mcp() or load_bench_results(). InvalidInputError for anything else."""
    import pandas as pd

    with tempfile.TemporaryDirectory(prefix="smcbench-report-tables-") as scratch:
        source = _results_folder(results, "report_tables", scratch)
        raw = _smcbench._report_tables(source.folder)
    frames = {}
    for name, columns, rows in raw:
        frame = pd.DataFrame(rows, columns=columns)
        for column in columns:
            values = frame[column]
            if values.dtype.kind == "f" and not any(word in column for word in _MEASURED) and values.notna().all() \
                    and (values == values.round()).all():
                frame[column] = values.astype("int64")
        frames[name] = frame
    return frames


@dataclass
class Comparison:
    """What `smcbench compare A B` found (bench/compare/compare_runs.h). summary: the table the command prints;
    markdown: its compare.md (linking the figure when one was drawn); regressed: what its exit status 1 means (a verdict regression or
    a group flagged slower); regressions, slower_groups: their counts; matched_records: records both runs hold;
    verdict_changes: dicts (kind "regression" / "improvement" / "changed", suite, problem, start, solver, mode,
    tolerance, verdict_a/b, status_a/b, message_b); groups: per suite × backend × size band the time ratio B/A
    (sgm_a, sgm_b, ratio, low, high: the bootstrap interval, flag "SLOWER" / "faster" / ""); only_in_a, only_in_b:
    records one run lacks ("suite|problem|backend|mode"). data: compare.json as a dict (format "smcbench-compare/1":
    the runs' settings, build and machine side by side with their differences, the noise floor, the machine drift,
    the groups with raw and drift-divided ratios and median iterations; docs/cli.md, "compare")."""

    summary: str
    markdown: str
    data: dict
    regressed: bool
    regressions: int
    slower_groups: int
    matched_records: int
    verdict_changes: List[dict]
    groups: List[dict]
    only_in_a: List[str]
    only_in_b: List[str]


def compare(a, b, out=None, *, threshold: float = 0.05, resamples: int = 2000, confidence: float = 0.95,
            keep_drift: bool = False, plots: bool = False) -> Comparison:
    """Compare two bench runs of the same suites as `smcbench compare A B` does (CompareRunFolders: what differed
    between the runs, verdict changes, then the time ratio B/A per suite, backend and size band with a bootstrap
    interval, flagged only beyond both runs' noise floor and 1 + threshold, after dividing out a machine drift).

    a, b: results folders, their results.json, or DataFrames of bench() / bench_mcp() / load_bench_results().
    out: a folder to write compare.md and compare.json to, and with plots the ratio figure
    compare-ratios.{png,svg,dat,gp}, by the same C++ code as the command's --out (None: nothing written).
    threshold, resamples, confidence, keep_drift: the command's flags. plots: draw the figure (needs gnuplot, as the
    command without --no-plots; with plots but no out, InvalidInputError). Runs of other suites, or options out of
    range, raise InvalidInputError (the command's exit status 2); so does a figure gnuplot could not draw, after
    compare.md and compare.json were written."""
    if plots and out is None:
        raise InvalidInputError("compare: plots=True needs out=, the folder the figure is written to")
    with tempfile.TemporaryDirectory(prefix="smcbench-compare-") as scratch:
        runs = [_results_folder(x, "compare", scratch) for x in (a, b)]
        raw = _smcbench._compare(runs[0].folder, runs[1].folder, runs[0].name, runs[1].name, float(threshold),
                                 int(resamples), float(confidence), bool(keep_drift),
                                 "" if out is None else os.fspath(out), bool(plots))
    figure_error = raw.pop("figure_error")
    if figure_error:
        raise InvalidInputError(f"compare: no figure: {figure_error}")
    raw["data"] = json.loads(raw["data"])
    return Comparison(**raw)


AffineVI.__doc__ = """An affine variational inequality over a polytope (docs/avi.md): find λ in
P = {λ : H λ ≥ K, E λ = f} with 0 ∈ M λ + q + N_P(λ), i.e. (x − λ)ᵀ(M λ + q) ≥ 0 for every x in P.

AffineVI(M, q, H=None, K=None, E=None, f=None, name=""): M n×n, q of size n, H m×n and K of size m (None or
empty: no inequality), E p×n and f of size p (both or neither). Numpy arrays in (any float dtype; copied),
numpy arrays out: the properties M, q, H, K, E (p×n, 0×n without equalities), f, and name, n, m, p,
feasible_point (the point of P the validation found), boundedness ("bounded", "unbounded", "not decided"),
expected ("solvable" on a bounded P, else "unknown").

Raises InvalidInputError (a ValueError with the C++ message naming the field) for sizes that disagree, NaN or
inf, a zero row of H or E, or an empty P."""


@dataclass
class AviResult:
    """What solve_avi returned.

    status: the status name; solved: status == "solved" (SolveAvi downgrades a backend's "solved" that fails the
    AVI rule to "inaccurate"). verdict: the AVI verdict of JudgeAvi ("solved", "failed", "correctly refused",
    "WRONGLY CLAIMED", ...; docs/avi.md, "The verdict"), never the backend's own flag; expected: the outcome the
    verdict assumed ("solvable" on a bounded P, else "unknown"). lambda_: λ (trailing underscore: `lambda` is a
    Python keyword); mu (≥ 0, one per row of H) and nu (one per row of E): the multipliers, with
    M λ + q − Hᵀ mu − Eᵀ nu = 0. residual_rel, residual_scaled: the natural residual of the normalized reduction;
    primal_infeasibility, complementarity: the rule's parts in units of λ (relative to 1 + ‖λ‖∞).
    forward_error: ‖λ − λ*‖∞ when a reference was given and λ* is provably unique, else None;
    reference_certificate: the reference's certificate, or None. reduced: the backend's own SolveResult on the
    reduced box-MLCP (its status, z = (λ, μ̃, ν̃), details).
    """

    status: str
    solved: bool
    verdict: str
    expected: str
    lambda_: np.ndarray
    mu: np.ndarray
    nu: np.ndarray
    iterations: int
    time_seconds: float
    residual_rel: float
    residual_scaled: float
    primal_infeasibility: float
    complementarity: float
    forward_error: Optional[float]
    reference_certificate: Optional[str]
    solver: str
    message: str
    reduced: SolveResult


def solve_avi(avi: AffineVI, solver: str = "lemke", tol: float = 1e-10, time_limit: Optional[float] = None, *,
              start=None, max_iterations: Optional[int] = None, polish: bool = True, reference=None,
              expected: Optional[str] = None, **backend_options) -> AviResult:
    """Solve the AVI with a box backend through the exact reduction to a box-MLCP (SolveAvi, docs/avi.md).

    solver: a backend that solves box-MLCPs (solvers()); the default lemke pivots exactly and solves every
    monotone AVI (M + Mᵀ positive semidefinite). tol: the tolerance of the AVI rule. time_limit: seconds (None: no
    limit). start: a warm start, λ alone (size n) or (λ, μ, ν) (size n + m + p). max_iterations: None = the
    backend's default. polish: the exact polish of the reduction's answer. reference: a known λ* (size n): it is
    certified (CertifyAvi) and λ is judged by its forward error where λ* is provably unique. expected: what a
    correct backend must answer ("solvable", "infeasible", "unknown"; None: avi.expected), for the verdict.
    backend_options: the backend's typed options by name, as in solve().

    Raises InvalidInputError (a ValueError) for an unknown solver or option, a backend that does not solve
    box-MLCPs, an invalid option value, or a start or reference of the wrong size.
    """
    raw = _smcbench._solve_avi(avi, solver, float(tol), time_limit, start, max_iterations, polish, reference,
                               expected, backend_options)
    raw["reduced"] = _result(raw["reduced"])
    return AviResult(solved=raw["status"] == "solved", **raw)


@dataclass
class AviProblem:
    """One AVI of a .smcps set of AVIs: the AffineVI with the library's metadata. id (unique in the set), source,
    tags, expected ("solvable", "infeasible", "unknown"; None: avi.expected, what write_problem_set stores),
    metadata (str → str), and reference: the certified reference as stored ({} when none): certificate,
    condition, z (z* of the normalized reduction, what the file stores), lambda_ (λ*, the head of z), mu, nu (μ*,
    ν*: M λ* + q − Hᵀ mu − Eᵀ nu = 0), lambda_unique (whether the forward error of λ is judged) and
    strictly_monotone. Written back unchanged, it reads back bit for bit."""

    id: str
    avi: AffineVI
    source: str = "python"
    tags: List[str] = field(default_factory=list)
    expected: Optional[str] = None
    metadata: Dict[str, str] = field(default_factory=dict)
    reference: Dict[str, Any] = field(default_factory=dict)

    def solve(self, solver: str = "lemke", **kwargs) -> "AviResult":
        """solve_avi on this AVI, judged by its expected outcome and, where its reference verified a λ* (certificate
        "unique" or "verified"), against that λ* (certified again by solve_avi)."""
        kwargs.setdefault("expected", self.expected)
        if self.reference.get("lambda_") is not None:
            kwargs.setdefault("reference", self.reference["lambda_"])
        return solve_avi(self.avi, solver, **kwargs)


class AviFile(NamedTuple):
    """What an AVI file holds: avi (an AffineVI), solution (the file's reference λ*, checked when read, or None),
    expected (the file's expected outcome, else avi.expected). Unpacks as `avi, solution, expected`."""

    avi: AffineVI
    solution: Optional[np.ndarray]
    expected: str


def read_avi(path) -> AviFile:
    """Read an AVI file (.avi.json, docs/formats.md). Raises InvalidInputError naming the file and the field of
    any defect. solve_avi(f.avi, expected=f.expected) judges an answer as `smcbench solve FILE` does."""
    return AviFile(*_smcbench._read_avi(os.fspath(path)))


def write_avi(avi: AffineVI, path, solution=None, expected: Optional[str] = None) -> None:
    """Write avi (with a reference λ*, size n, and an expected outcome "solvable" / "infeasible" / "unknown", if
    given) as an AVI file that reads back bit for bit (docs/formats.md). Raises InvalidInputError when the file
    cannot be written, or the solution or expected is malformed."""
    _smcbench._write_avi(avi, os.fspath(path), solution, expected)
