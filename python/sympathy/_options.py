"""Functions built from the one option table (cases/app/option_table.hpp).

Each command's options reach Python as keyword-only arguments with real signatures (what
``inspect.signature``, ``help()``, an IDE and the type stubs show), their types checked here by
the option's kind before the engine is called: a wrong type raises ``TypeError`` naming the
keyword and the type expected; a bad value raises ``sympathy.InputError`` (a ``ValueError``) from
the engine's own checks, naming the keyword. The values go to the engine as values (an int, a
float, a list of floats, a dict), not as command-line text.
"""

from __future__ import annotations

import difflib
import inspect
import math
import operator
import os
from collections.abc import Callable, Mapping, Sequence
from typing import Any, Literal, Optional, Union

from . import _core

# The Python type each kind of option takes (for signatures and stubs), and how it is written in
# the stubs.
_ANNOTATION = {
    "flag": bool,
    "integer": int,
    "number": float,
    "numbers": Sequence[float],
    "text": str,
    "path": Union[str, os.PathLike],
    "names": Union[str, Sequence[str]],
    "texts": Union[str, Sequence[str]],
    "assignments": Mapping[str, float],
}
_STUB_TYPE = {
    "flag": "bool",
    "integer": "int",
    "number": "float",
    "numbers": "Sequence[float]",
    "text": "str",
    "path": "str | os.PathLike[str]",
    "names": "str | Sequence[str]",
    "texts": "str | Sequence[str]",
    "assignments": "Mapping[str, float]",
}
_EXPECTED = {
    "flag": "True or False",
    "integer": "an int",
    "number": "a float or an int",
    "numbers": "a sequence of floats",
    "text": "a str",
    "path": "a str or a path",
    "names": "a str or a sequence of str",
    "texts": "a str or a sequence of str",
    "assignments": "a mapping of str to float",
    "choice": "a str",
}


# Text options that name a file or a directory also take a path object.
_PATHS = ("FILE", "FILE.csv", "FITTED.toml", "DIR")


def python_kind(option: dict) -> str:
    """The option's kind, a text naming a file or directory as "path", a repeatable text (given
    once or more: basins' grid) as "texts"."""
    if option["kind"] == "text" and option["placeholder"] in _PATHS:
        return "path"
    if option["kind"] == "text" and option["repeatable"]:
        return "texts"
    return option["kind"]


def _annotation(option: dict) -> Any:
    if option["kind"] == "choice":
        return Literal[tuple(option["choices"])]  # type: ignore[misc]
    return _ANNOTATION[python_kind(option)]


def stub_type(option: dict) -> str:
    """The option's type as the stubs write it."""
    if option["kind"] == "choice":
        return "Literal[" + ", ".join(repr(c) for c in option["choices"]) + "]"
    return _STUB_TYPE[python_kind(option)]


def _is_number(v: Any) -> bool:
    if isinstance(v, (bool, str, bytes)):
        return False
    try:
        float(v)
    except OverflowError:
        return True  # a number, too large: a bad value, not a wrong type
    except (TypeError, ValueError):
        return False
    return True


def checked(function: str, option: dict, value: Any) -> Any:
    """The value as the engine takes it for the option's kind; TypeError naming the keyword
    for a value of another type."""
    keyword = option["keyword"]
    kind = python_kind(option) if "placeholder" in option else option["kind"]

    def wrong() -> TypeError:
        return TypeError(
            f"{function}(): {keyword} must be {_EXPECTED[kind]}, not {type(value).__name__}"
            f" ({value!r})")

    if kind == "flag":
        if not isinstance(value, bool):
            raise wrong()
        return value
    if kind == "integer":
        if isinstance(value, bool):
            raise wrong()
        try:
            n = operator.index(value)
        except TypeError:
            raise wrong() from None
        if not -2**31 <= n < 2**31:  # the engine's int
            raise _core.InputError(f"{keyword} {n}: expected an integer of at most 10 digits")
        return n
    if kind == "number":
        if not _is_number(value):
            raise wrong()
        try:
            return float(value)
        except OverflowError:
            raise _core.InputError(f"{keyword} {value}: expected a finite number") from None
    if kind == "numbers":
        if _is_number(value):
            return [float(value)]
        if isinstance(value, (str, bytes, Mapping)) or not hasattr(value, "__iter__"):
            raise wrong()
        items = list(value)
        if not all(_is_number(x) for x in items):
            raise wrong()
        try:
            return [float(x) for x in items]
        except OverflowError:
            raise _core.InputError(f"{keyword}: expected finite numbers") from None
    if kind in ("text", "path", "choice"):
        if kind == "path" and isinstance(value, os.PathLike):
            return os.fspath(value)
        if not isinstance(value, str):
            raise wrong()
        return value
    if kind == "texts":  # each item its own value of the repeatable option
        if isinstance(value, str):
            return [value]
        if isinstance(value, (bytes, Mapping)) or not hasattr(value, "__iter__"):
            raise wrong()
        items = list(value)
        if not all(isinstance(x, str) for x in items):
            raise wrong()
        return items
    if kind == "names":
        if isinstance(value, str):
            return value
        if isinstance(value, (bytes, Mapping)) or not hasattr(value, "__iter__"):
            raise wrong()
        items = list(value)
        if not all(isinstance(x, str) for x in items):
            raise wrong()
        return ",".join(items)
    if kind == "assignments":
        if not isinstance(value, Mapping):
            raise wrong()
        out = {}
        for k, v in value.items():
            if not isinstance(k, str) or not _is_number(v):
                raise TypeError(f"{function}(): {keyword} must be {_EXPECTED[kind]}; "
                                f"got {k!r}: {v!r}")
            try:
                out[k] = float(v)
            except OverflowError:
                raise _core.InputError(f"{keyword} {k}={v}: expected a finite number") from None
        return out
    raise AssertionError(kind)


def finite(function: str, keyword: str, value: Any) -> None:
    """A value the engine would refuse anyway, refused here naming the keyword (NaN, inf)."""
    values = value.values() if isinstance(value, dict) else value if isinstance(value, list) \
        else [value]
    for x in values:
        if isinstance(x, float) and not math.isfinite(x):
            raise _core.InputError(f"{keyword} {x}: expected a finite number")


# What a progress callable is called with: each point as it is found (a branch, equilibria, a
# curve), or the count of jobs done and their total (a study's branches, a map's orbits, basins'
# runs, a sweep's tasks).
POINT_PROGRESS = "bool | Callable[[Any], None] | None"
JOBS_PROGRESS = "bool | Callable[[int, int], None] | None"


def signature(command: str, first: list[inspect.Parameter], progress: bool,
              returns: Any, jobs: bool = False) -> inspect.Signature:
    """The signature of a function of `command`: `first`, then every option as a keyword-only
    argument (required ones without a default), then progress where the command has one (`jobs`:
    called with the jobs done and their total)."""
    params = list(first)
    for o in _core.command_options(command):
        default = inspect.Parameter.empty if o["required"] else None
        annotation = _annotation(o) if o["required"] else Optional[_annotation(o)]
        params.append(inspect.Parameter(o["keyword"], inspect.Parameter.KEYWORD_ONLY,
                                        default=default, annotation=annotation))
    if progress:
        callback = Callable[[int, int], None] if jobs else Callable[[Any], None]
        params.append(inspect.Parameter(
            "progress", inspect.Parameter.KEYWORD_ONLY, default=None,
            annotation=Union[bool, callback, None]))
    return inspect.Signature(params, return_annotation=returns)


def docstring(command: str, summary: str, progress: bool, jobs: bool = False) -> str:
    """The summary, then each keyword with its help (the program's --help text)."""
    lines = [summary, "", "Keyword arguments (the options of ``sympathy " + command + "``):", ""]
    for o in _core.command_options(command):
        extra = []
        if o["required"]:
            extra.append("required")
        if o["repeatable"] and o["kind"] not in ("assignments", "names"):
            extra.append("repeatable")
        tail = f" ({', '.join(extra)})" if extra else ""
        lines.append(f"- ``{o['keyword']}`` ({stub_type(o)}): {o['help']}{tail}")
    if progress and jobs:
        lines.append("- ``progress`` (callable or bool): called with (done, total) as jobs "
                     "finish (True: a tqdm bar, when tqdm is installed)")
    elif progress:
        lines.append("- ``progress`` (callable or bool): called with each point as it is found "
                     "(True: a tqdm bar, when tqdm is installed)")
    lines += ["", "None (the default) leaves an option to the command's default."]
    return "\n".join(lines)


def keywords(function: str, sig: inspect.Signature, args: tuple,
             kwargs: dict) -> inspect.BoundArguments:
    """The call's arguments bound to `sig` (TypeError as Python raises it for an unknown or
    missing keyword, with the nearest known one), each option's value checked by its kind."""
    try:
        bound = sig.bind(*args, **kwargs)
    except TypeError as e:
        known = [p for p in sig.parameters if sig.parameters[p].kind ==
                 inspect.Parameter.KEYWORD_ONLY]
        unknown = [k for k in kwargs if k not in sig.parameters]
        near = difflib.get_close_matches(unknown[0], known, n=1) if unknown else []
        hint = (f"; did you mean '{near[0]}'?" if near
                else "; expected one of: " + ", ".join(known) if unknown else "")
        raise TypeError(f"{function}() {e}{hint}") from None
    return bound


def engine_keywords(function: str, command: str, bound: inspect.BoundArguments) -> dict:
    """The options given (not None), checked by kind, as the engine takes them."""
    out = {}
    for o in _core.command_options(command):
        k = o["keyword"]
        if k in bound.arguments and bound.arguments[k] is not None:
            value = checked(function, o, bound.arguments[k])
            finite(function, k, value)
            out[k] = value
    return out


def stub_text(functions: dict) -> str:
    """The package's type stubs (python/sympathy/__init__.pyi), from the option table:
    `functions` maps each function's name to (command, summary, progress)."""

    def keywords(command: str, progress: str) -> list[str]:
        out = []
        for o in _core.command_options(command):
            t = stub_type(o)
            out.append(f"{o['keyword']}: {t}" if o["required"]
                       else f"{o['keyword']}: {t} | None = ...")
        if progress:
            out.append(f"progress: {progress} = ...")
        return out

    def define(name: str, first: str, command: str, progress: str, indent: str) -> list[str]:
        lines = [f"{indent}def {name}(", f"{indent}    {first},", f"{indent}    /,",
                 f"{indent}    *,"]
        lines += [f"{indent}    {k}," for k in keywords(command, progress)]
        lines.append(f"{indent}) -> Result: ...")
        return lines

    lines = [
        "# Generated from the option table by scripts/python_stubs: do not edit (a test holds it",
        "# to the table).",
        "import os",
        "from collections.abc import Callable, Mapping, Sequence",
        "from typing import Any, Literal",
        "",
        "CaseSource = str | os.PathLike[str] | Mapping[str, Any]",
        "",
        "# The functions' commands, summaries and whether they report progress (for tests).",
        "_FUNCTIONS: dict[str, tuple[str, str, bool]]",
        "",
        "class InputError(ValueError): ...",
        "class OutputError(OSError): ...",
        "",
        "class Result:",
        "    def __init__(self, **fields: Any) -> None: ...",
        "    def __getattr__(self, name: str) -> Any: ...",
        "    def to_dict(self) -> dict[str, Any]: ...",
        "    def to_dataframe(self) -> Any: ...",
        "    def plot(self, ax: Any = ..., out: Any = ..., **options: Any) -> Any: ...",
        "",
        "class Points(Result):",
        "    def columns(self) -> dict[str, Any]: ...",
        "",
        "class Case:",
        "    def __init__(",
        "        self,",
        "        source: CaseSource,",
        "        params: str | None = ...,",
        "        set: Mapping[str, float] | None = ...,",
        "    ) -> None: ...",
        "    @property",
        "    def path(self) -> str: ...",
        "    @property",
        "    def params(self) -> str: ...",
        "    @property",
        "    def parameters(self) -> dict[str, float]: ...",
        "    @property",
        "    def state_names(self) -> list[str]: ...",
        "    def with_values(self, **values: float) -> Case: ...",
    ]
    for name, (command, _, progress) in functions.items():
        lines += define(name, "self", command, POINT_PROGRESS if progress else "", "    ")
    lines.append("")
    for name, (command, _, progress) in functions.items():
        lines += define(name, "case: Case | CaseSource", command,
                        POINT_PROGRESS if progress else "", "")
    for command in ("study", "map", "basins", "sweep"):
        lines += define(command, "path: str | os.PathLike[str]", command, JOBS_PROGRESS, "")
    lines += ["def load(path: str | os.PathLike[str]) -> Result: ..."]
    return "\n".join(lines) + "\n"
