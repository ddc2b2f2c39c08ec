"""Short TypeErrors for the extension's functions.

pybind11 answers a call it cannot match (an unknown keyword, a missing argument, a value of
the wrong type) with "incompatible function arguments ... Invoked with: " and the repr of
every argument: whole vertex arrays. short_type_errors() wraps a function so that such a
call raises a TypeError of one line that names the argument instead. The signature comes
from the first lines of the function's docstring (each starts with its own signature).
"""
import functools
import inspect
import numbers
import re

_MARK = "incompatible function arguments"


def _signature_text(doc):
    """The "name(...)" at the start of a docstring, through its closing parenthesis."""
    if not doc or "(" not in doc.split("\n", 1)[0]:
        return None
    depth = 0
    for i, c in enumerate(doc):
        if c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
            if depth == 0:
                return doc[:i + 1]
    return None


def _signature(f):
    text = _signature_text(getattr(f, "__doc__", None))
    if text is None:
        return None
    params = text[text.index("(") + 1:-1]
    scope = {}
    try:
        exec("def _f(" + " ".join(params.split()) + "): pass", {}, scope)
        return inspect.signature(scope["_f"])
    except Exception:  # a docstring this parser does not read: no signature
        return None


def _declared_types(message):
    """name -> type from pybind11's "(vertices: object, ..., threads: int = 0) -> X"."""
    m = re.search(r"1\. \((.*)\) ->", message)
    if not m:
        return {}
    out, depth, part = {}, 0, ""
    for c in m.group(1) + ",":
        if c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
        if c == "," and depth == 0:
            name, _, rest = part.strip().partition(":")
            out[name.strip()] = rest.split("=")[0].strip()
            part = ""
        else:
            part += c
    return out


def _short_value(value):
    """A scalar's repr when it is short; never an array's."""
    if isinstance(value, (bool, int, float, str)) and len(repr(value)) <= 40:
        return " " + repr(value)
    return ""


def _mismatch(name, declared, value):
    """Why `value` is not a `declared`, or None when it looks like one. (Integers are taken
    by the module itself, out of range as ValueError: a C++ int argument is never left.)"""
    got = type(value).__name__
    if getattr(value, "shape", ()) != ():  # an array where a scalar belongs
        if declared in ("float", "int", "bool", "str"):
            return f"{name} must be a single value ({declared}), got {got}"
        return None
    if declared == "float":
        if isinstance(value, str) or not isinstance(value, numbers.Real) and not hasattr(value, "__float__"):
            return f"{name} must be a number, got {got}{_short_value(value)}"
    elif declared == "int":
        if isinstance(value, bool) or not hasattr(value, "__index__"):
            return f"{name} must be an integer, got {got}{_short_value(value)}"
    elif declared == "bool":
        if not isinstance(value, bool) and got != "bool_":
            return f"{name} must be True or False, got {got}{_short_value(value)}"
    elif declared == "str":
        if not isinstance(value, str):
            return f"{name} must be a str, got {got}{_short_value(value)}"
    return None


def _explain(f, sig, args, kwargs, message):
    name = f.__name__
    if sig is not None:
        try:
            bound = sig.bind(*args, **kwargs)
        except TypeError as e:  # unknown keyword, missing or extra argument
            return f"{name}(): {e}"
        declared = _declared_types(message)
        for arg, value in bound.arguments.items():
            if arg in declared:
                why = _mismatch(arg, declared[arg], value)
                if why:
                    return f"{name}(): {why}"
    types = ", ".join([type(a).__name__ for a in args] + [f"{k}={type(v).__name__}" for k, v in kwargs.items()])
    return f"{name}(): incompatible arguments ({types}); see help(meshsal.{name})"


def short_type_errors(f):
    """f, raising a short TypeError where pybind11 would print its arguments."""
    sig = _signature(f)

    @functools.wraps(f)
    def call(*args, **kwargs):
        try:
            return f(*args, **kwargs)
        except TypeError as e:
            message = str(e)
            if _MARK not in message:
                raise
            raise TypeError(_explain(f, sig, args, kwargs, message)) from None

    if sig is not None:
        call.__signature__ = sig
    else:
        del call.__wrapped__  # inspect.signature would fail on the extension function
    return call
