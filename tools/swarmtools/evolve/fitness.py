"""A fitness: one of a run's metrics, or an arithmetic expression over them.

The expression is parsed with :mod:`ast` and evaluated by walking the tree:
only numbers, metric names, ``+ - * / ** %``, unary ``-``/``+``, parentheses
and the functions ``min``, ``max``, ``abs``, ``sqrt``, ``log``, ``exp`` are
allowed; any other node (attributes, subscripts, comparisons, lambdas, other
calls, strings) is refused when the file is read.  Nothing is ever passed to
``eval``.

    trips_per_robot + 10 * success - merge_time_capped_s / 1000
"""

from __future__ import annotations

import ast
import math
from collections.abc import Callable, Mapping

_BINOPS: dict[type, Callable[[float, float], float]] = {
    ast.Add: lambda a, b: a + b,
    ast.Sub: lambda a, b: a - b,
    ast.Mult: lambda a, b: a * b,
    ast.Div: lambda a, b: a / b,
    ast.Pow: lambda a, b: a ** b,
    ast.Mod: lambda a, b: math.fmod(a, b),
}
_UNARY: dict[type, Callable[[float], float]] = {ast.USub: lambda a: -a, ast.UAdd: lambda a: a}
_FUNCS: dict[str, tuple[Callable[..., float], int, int]] = {   # name: (function, least, most arguments)
    "min": (min, 2, 16), "max": (max, 2, 16), "abs": (abs, 1, 1),
    "sqrt": (math.sqrt, 1, 1), "log": (math.log, 1, 1), "exp": (math.exp, 1, 1),
}
MAX_LENGTH = 1000
MAX_NODES = 200


class FitnessError(ValueError):
    """A fitness that cannot be parsed, or cannot be evaluated on a run."""


class Fitness:
    """A parsed fitness: `names` are the metrics it reads."""

    def __init__(self, text: str):
        if not isinstance(text, str) or not text.strip():
            raise FitnessError("expected a metric name or an arithmetic expression over metrics")
        if len(text) > MAX_LENGTH:
            raise FitnessError(f"longer than {MAX_LENGTH} characters")
        try:
            tree = ast.parse(text.strip(), mode="eval")
        except SyntaxError as e:
            raise FitnessError(f"not an expression: {e.msg} (at character {e.offset})") from None
        except (ValueError, RecursionError, MemoryError):
            raise FitnessError("not an expression") from None
        self.text = text.strip()
        self.names: list[str] = []
        count = 0
        for node in ast.walk(tree):
            count += 1
            if count > MAX_NODES:
                raise FitnessError(f"more than {MAX_NODES} parts: write a shorter expression")
            self._check(node)
        self._tree = tree.body

    def _check(self, node: ast.AST) -> None:
        if isinstance(node, (ast.Expression, ast.Load)) or type(node) in _BINOPS or type(node) in _UNARY:
            return
        if isinstance(node, ast.BinOp):
            if type(node.op) not in _BINOPS:
                raise FitnessError(f"operator '{ast.unparse(node)}' is not allowed (use + - * / ** %)")
            return
        if isinstance(node, ast.UnaryOp):
            if type(node.op) not in _UNARY:
                raise FitnessError(f"'{ast.unparse(node)}': only unary - and + are allowed")
            return
        if isinstance(node, ast.Constant):
            if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
                raise FitnessError(f"{node.value!r}: only numbers may appear as constants")
            return
        if isinstance(node, ast.Name):
            if node.id not in self.names and node.id not in _FUNCS:
                self.names.append(node.id)
            return
        if isinstance(node, ast.Call):
            if not isinstance(node.func, ast.Name) or node.func.id not in _FUNCS:
                raise FitnessError(f"'{ast.unparse(node.func)}' is not a function here (allowed: "
                                   f"{', '.join(_FUNCS)})")
            _, lo, hi = _FUNCS[node.func.id]
            if node.keywords or not lo <= len(node.args) <= hi:
                raise FitnessError(f"{node.func.id}() takes {lo if lo == hi else f'{lo} to {hi}'} "
                                   "arguments, no keywords")
            return
        raise FitnessError(f"'{ast.unparse(node)}' is not allowed in a fitness (numbers, metric names, "
                           f"+ - * / ** %, and {', '.join(_FUNCS)})")

    def __call__(self, metrics: Mapping[str, object]) -> float:
        """The fitness of one run; FitnessError naming a missing or null metric."""
        return float(self._eval(self._tree, metrics))

    def _eval(self, node: ast.AST, m: Mapping[str, object]) -> float:
        if isinstance(node, ast.Constant):
            return float(node.value)
        if isinstance(node, ast.Name):
            if node.id not in m:
                raise FitnessError(f"the runs report no metric '{node.id}' (they report: {', '.join(sorted(m))})")
            v = m[node.id]
            if v is None or isinstance(v, bool) or not isinstance(v, (int, float)) or math.isnan(v):
                raise FitnessError(f"metric '{node.id}' is {v!r} in a run (null: it did not happen; a fitness "
                                   "needs a number in every run, e.g. merge_time_capped_s, not merge_time_s)")
            return float(v)
        if isinstance(node, ast.BinOp):
            a, b = self._eval(node.left, m), self._eval(node.right, m)
            try:
                return _BINOPS[type(node.op)](a, b)
            except (ZeroDivisionError, OverflowError, ValueError) as e:
                raise FitnessError(f"'{ast.unparse(node)}': {e}") from None
        if isinstance(node, ast.UnaryOp):
            return _UNARY[type(node.op)](self._eval(node.operand, m))
        if isinstance(node, ast.Call):
            fn = _FUNCS[node.func.id][0]   # type: ignore[union-attr]
            try:
                return float(fn(*(self._eval(a, m) for a in node.args)))
            except (ValueError, OverflowError) as e:
                raise FitnessError(f"'{ast.unparse(node)}': {e}") from None
        raise FitnessError(f"cannot evaluate '{ast.unparse(node)}'")   # _check refused it already
