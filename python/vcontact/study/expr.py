"""User expressions over a run's outputs and parameters, evaluated safely (docs/STUDY.md,
"Expressions").

The text is parsed by Python's own parser (ast.parse, mode "eval") and the tree is walked here:
only numbers, names of outputs and parameters, arithmetic (+ - * / // % **), comparisons,
and/or/not, `a if c else b` and a fixed list of functions are accepted; anything else (an
attribute, a subscript, a string, a lambda, a call of another name) is refused when the study
is read, naming the expression and what it holds. Nothing of the user's text reaches eval().
Arithmetic is IEEE double (NumPy scalars): a division by zero is inf or nan, not an error.
Truth values are 1.0 and 0.0; nan is false.
"""

import ast
import math

import numpy as np

FUNCTIONS = {
    "abs": np.abs, "sqrt": np.sqrt, "exp": np.exp, "log": np.log, "log10": np.log10,
    "sin": np.sin, "cos": np.cos, "tan": np.tan, "atan2": np.arctan2, "hypot": np.hypot,
    "floor": np.floor, "ceil": np.ceil, "min": np.fmin, "max": np.fmax,
    "isnan": lambda x: np.float64(np.isnan(x)),
}
ARITY = {"atan2": 2, "hypot": 2, "min": 2, "max": 2}
CONSTANTS = {"pi": math.pi, "nan": math.nan, "inf": math.inf}

_BINARY = {ast.Add: np.add, ast.Sub: np.subtract, ast.Mult: np.multiply, ast.Div: np.divide,
           ast.FloorDiv: np.floor_divide, ast.Mod: np.fmod, ast.Pow: np.power}
_COMPARE = {ast.Lt: np.less, ast.LtE: np.less_equal, ast.Gt: np.greater,
            ast.GtE: np.greater_equal, ast.Eq: np.equal, ast.NotEq: np.not_equal}


class ExpressionError(ValueError):
    """An expression the evaluator does not accept; the message names it and the reason."""


class Expression:
    """A checked expression; `names` are the names it reads."""

    def __init__(self, text, known, where):
        self.text = text
        try:
            tree = ast.parse(text, mode="eval")
        except SyntaxError as e:
            raise ExpressionError(f"{where}: '{text}' is not an expression ({e.msg})") from None
        self.names = set()
        self._check(tree.body, known, where)
        self._tree = tree.body

    def _check(self, node, known, where):
        if isinstance(node, ast.Constant):
            if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
                raise ExpressionError(f"{where}: '{self.text}': only numbers may be written, "
                                      f"not {node.value!r}")
            return
        if isinstance(node, ast.Name):
            if node.id not in known and node.id not in CONSTANTS:
                raise ExpressionError(f"{where}: '{self.text}': no output or parameter named "
                                      f"'{node.id}' (known: {', '.join(sorted(known))})")
            if node.id not in CONSTANTS:
                self.names.add(node.id)
            return
        if isinstance(node, ast.Call):
            name = node.func.id if isinstance(node.func, ast.Name) else None
            if name not in FUNCTIONS or node.keywords:
                raise ExpressionError(f"{where}: '{self.text}': calls only "
                                      f"{', '.join(sorted(FUNCTIONS))} (by position)")
            if len(node.args) != ARITY.get(name, 1):
                raise ExpressionError(f"{where}: '{self.text}': {name} takes "
                                      f"{ARITY.get(name, 1)} argument(s)")
            for a in node.args:
                self._check(a, known, where)
            return
        children = self._children(node)
        if children is None:
            raise ExpressionError(f"{where}: '{self.text}': {type(node).__name__} is not allowed "
                                  "(numbers, names, arithmetic, comparisons, and/or/not, "
                                  "'a if c else b' and the listed functions are)")
        for c in children:
            self._check(c, known, where)

    @staticmethod
    def _children(node):
        if isinstance(node, ast.BinOp) and type(node.op) in _BINARY:
            return [node.left, node.right]
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd, ast.Not)):
            return [node.operand]
        if isinstance(node, ast.BoolOp):
            return node.values
        if isinstance(node, ast.Compare) and all(type(o) in _COMPARE for o in node.ops):
            return [node.left, *node.comparators]
        if isinstance(node, ast.IfExp):
            return [node.test, node.body, node.orelse]
        return None

    def __call__(self, env):
        with np.errstate(all="ignore"):
            return float(self._eval(self._tree, env))

    def _eval(self, node, env):
        if isinstance(node, ast.Constant):
            return np.float64(node.value)
        if isinstance(node, ast.Name):
            return np.float64(CONSTANTS[node.id] if node.id in CONSTANTS else env[node.id])
        if isinstance(node, ast.Call):
            return np.float64(FUNCTIONS[node.func.id](*(self._eval(a, env) for a in node.args)))
        if isinstance(node, ast.BinOp):
            return _BINARY[type(node.op)](self._eval(node.left, env), self._eval(node.right, env))
        if isinstance(node, ast.UnaryOp):
            v = self._eval(node.operand, env)
            if isinstance(node.op, ast.Not):
                return np.float64(not _truth(v))
            return -v if isinstance(node.op, ast.USub) else v
        if isinstance(node, ast.BoolOp):
            values = (_truth(self._eval(v, env)) for v in node.values)
            return np.float64(all(values) if isinstance(node.op, ast.And) else any(values))
        if isinstance(node, ast.Compare):
            left = self._eval(node.left, env)
            for op, right_node in zip(node.ops, node.comparators):
                right = self._eval(right_node, env)
                if not _COMPARE[type(op)](left, right):
                    return np.float64(0.0)
                left = right
            return np.float64(1.0)
        # IfExp, the only node left after _check
        return self._eval(node.body if _truth(self._eval(node.test, env)) else node.orelse, env)


def _truth(v):
    return bool(v == v and v != 0)
