"""The small expression language of a sweep's `derive` and `where` entries.

A specification comes from outside, so its expressions are never handed to Python's eval:
they are parsed with `ast` and only arithmetic, comparisons, boolean logic, conditional
expressions, membership in literal lists and a few pure functions (min, max, abs, round,
int, float, sqrt, log2) are evaluated. Names are the cell's options with hyphens written as
underscores (`map_size`, `cascades`) and its bundle axes' labels.
"""
import ast
import math
import operator

_BINARY = {
    ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul, ast.Div: operator.truediv,
    ast.FloorDiv: operator.floordiv, ast.Mod: operator.mod, ast.Pow: operator.pow,
}
_COMPARE = {
    ast.Eq: operator.eq, ast.NotEq: operator.ne, ast.Lt: operator.lt, ast.LtE: operator.le, ast.Gt: operator.gt,
    ast.GtE: operator.ge, ast.In: lambda a, b: a in b, ast.NotIn: lambda a, b: a not in b,
}
_FUNCTIONS = {
    "min": min, "max": max, "abs": abs, "round": round, "int": int, "float": float, "sqrt": math.sqrt,
    "log2": math.log2,
}


class ExpressionError(ValueError):
    """A one-line description of what is wrong with an expression."""


class Expression:
    """A parsed expression; `names` are those it reads."""

    def __init__(self, text):
        if not isinstance(text, str) or not text.strip():
            raise ExpressionError("expected an expression as a non-empty string")
        if len(text) > 1000:
            raise ExpressionError("an expression of more than 1000 characters")
        self.text = text
        try:
            self._tree = ast.parse(text.strip(), mode="eval").body
            self.names = set()
            self._check(self._tree)
        except SyntaxError as e:
            raise ExpressionError(f"'{text}' is not an expression ({e.msg})") from None
        except (RecursionError, MemoryError):
            raise ExpressionError(f"'{text[:40]}...' is nested too deeply") from None

    def _check(self, node):
        allowed = (ast.Constant, ast.Name, ast.BinOp, ast.UnaryOp, ast.BoolOp, ast.Compare, ast.IfExp, ast.Call,
                   ast.List, ast.Tuple, ast.Load, ast.operator, ast.unaryop, ast.boolop, ast.cmpop)
        if not isinstance(node, allowed):
            raise ExpressionError(f"'{self.text}': {type(node).__name__} is not allowed (arithmetic, comparisons, "
                                  f"and/or/not, x if c else y, lists and {', '.join(sorted(_FUNCTIONS))})")
        if isinstance(node, ast.BinOp) and type(node.op) not in _BINARY:
            raise ExpressionError(f"'{self.text}': the operator {type(node.op).__name__} is not allowed")
        if isinstance(node, ast.Call):
            if not isinstance(node.func, ast.Name) or node.func.id not in _FUNCTIONS or node.keywords:
                raise ExpressionError(f"'{self.text}': only {', '.join(sorted(_FUNCTIONS))} may be called")
            for a in node.args:
                self._check(a)
            return
        if isinstance(node, ast.Name):
            self.names.add(node.id)
        for child in ast.iter_child_nodes(node):
            self._check(child)

    def evaluate(self, names):
        """The value with `names` (a dict) bound; ExpressionError for an unknown name or a failed operation."""
        try:
            return self._eval(self._tree, names)
        except ExpressionError:
            raise
        except (ArithmeticError, TypeError, ValueError) as e:
            raise ExpressionError(f"'{self.text}': {e}") from None
        except RecursionError:
            raise ExpressionError(f"'{self.text[:40]}...' is nested too deeply") from None

    def _eval(self, node, names):
        if isinstance(node, ast.Constant):
            return node.value
        if isinstance(node, ast.Name):
            if node.id not in names:
                raise ExpressionError(f"'{self.text}': unknown name '{node.id}' (known: {', '.join(sorted(names))})")
            return names[node.id]
        if isinstance(node, (ast.List, ast.Tuple)):
            return [self._eval(e, names) for e in node.elts]
        if isinstance(node, ast.BinOp):
            left, right = self._eval(node.left, names), self._eval(node.right, names)
            if isinstance(node.op, ast.Pow) and isinstance(right, (int, float)) and abs(right) > 64:
                raise ExpressionError(f"'{self.text}': exponent {right} is too large")
            if isinstance(node.op, ast.Mult) and any(isinstance(v, (str, list)) for v in (left, right)):
                raise ExpressionError(f"'{self.text}': only numbers multiply")
            return _BINARY[type(node.op)](left, right)
        if isinstance(node, ast.UnaryOp):
            value = self._eval(node.operand, names)
            if isinstance(node.op, ast.Not):
                return not value
            return -value if isinstance(node.op, ast.USub) else +value
        if isinstance(node, ast.BoolOp):
            values = (self._eval(v, names) for v in node.values)
            return all(values) if isinstance(node.op, ast.And) else any(values)
        if isinstance(node, ast.Compare):
            left = self._eval(node.left, names)
            for op, comparator in zip(node.ops, node.comparators):
                right = self._eval(comparator, names)
                if not _COMPARE[type(op)](left, right):
                    return False
                left = right
            return True
        if isinstance(node, ast.IfExp):
            return self._eval(node.body if self._eval(node.test, names) else node.orelse, names)
        if isinstance(node, ast.Call):
            return _FUNCTIONS[node.func.id](*(self._eval(a, names) for a in node.args))
        raise ExpressionError(f"'{self.text}': cannot evaluate {type(node).__name__}")
