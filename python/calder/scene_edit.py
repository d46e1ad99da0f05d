# SPDX-License-Identifier: MIT
"""A scene as editable data, and parameter paths into it.

A parameter path names one value of a scene file (docs/SCENES.md) by its
keys: ``world.dt``, ``seed``, ``bodies[0].mass.max``, ``fields[2].law.G``
(``[i]`` picks the i-th ``[[bodies]]`` or ``[[fields]]`` table, from 0).
``calder sweep --set`` reads the same paths.

`SceneEdit` holds a scene as the nested dicts and lists of its scene file
(``Scene.to_toml()`` read back), so that a path can be set, and gives a
`calder.Scene` back through calder's own scene reader: an unknown key or a
value out of range is refused there, with the reader's words (and its "did
you mean"), naming the path.
"""

from __future__ import annotations

import copy
import json
import math
import re
from typing import Any, Iterator, List, Tuple, Union

try:
    import tomllib  # Python 3.11+
except ImportError:  # pragma: no cover - Python 3.9, 3.10
    try:
        import tomli as tomllib  # type: ignore[no-redef]
    except ImportError:
        tomllib = None  # type: ignore[assignment]

from ._calder import Error, Scene

__all__ = ["SceneEdit", "parse_path"]

_NAME = r"[A-Za-z0-9_-]+"
_SEGMENT = re.compile(rf"({_NAME})((?:\[\d+\])*)")
_LOCATION = re.compile(r"^<[^>]*>:\d+:\d+: ")

Step = Union[str, int]


def parse_path(path: str) -> List[Step]:
    """The keys (str) and list positions (int) of a parameter path.

    >>> parse_path("fields[2].law.G")
    ['fields', 2, 'law', 'G']
    """
    if not isinstance(path, str) or not path:
        raise Error(f"parameter path must be a non-empty string like 'world.dt' (got {path!r})")
    steps: List[Step] = []
    for part in path.split("."):
        match = _SEGMENT.fullmatch(part)
        if not match:
            raise Error(f"parameter '{path}': '{part}' is not a key (letters, digits, _ and -) "
                        "optionally followed by [index], as in 'fields[0].law.G'")
        steps.append(match.group(1))
        steps.extend(int(i) for i in re.findall(r"\[(\d+)\]", match.group(2)))
    return steps


def _spelled(steps: List[Step]) -> str:
    text = ""
    for step in steps:
        text += f"[{step}]" if isinstance(step, int) else ("." if text else "") + step
    return text


def _key(name: str) -> str:
    return name if re.fullmatch(_NAME, name) else _string(name)


def _string(text: str) -> str:
    # JSON's escapes are TOML's, but for DEL, which TOML wants escaped too.
    return json.dumps(text, ensure_ascii=False).replace("\x7f", "\\u007f")


def _value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)  # the shortest text that reads back as the same double
    if isinstance(value, str):
        return _string(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{_key(k)} = {_value(v)}" for k, v in value.items()) + " }"
    if hasattr(value, "item") and not isinstance(value, (list, dict)):  # a numpy scalar
        return _value(value.item())
    raise Error(f"a scene value must be a number, a boolean, a string or a list of them "
                f"(got {type(value).__name__} {value!r})")


def to_toml(data: dict) -> str:
    """The scene file's text of nested dicts and lists (tables as [name],
    lists of tables as [[name]], deeper tables inline)."""
    lines: List[str] = []
    tables, arrays = [], []
    for key, value in data.items():
        if isinstance(value, dict):
            tables.append((key, value))
        elif isinstance(value, list) and value and all(isinstance(v, dict) for v in value):
            arrays.append((key, value))
        else:
            lines.append(f"{_key(key)} = {_value(value)}")
    for key, table in tables:
        lines += ["", f"[{_key(key)}]"] + [f"{_key(k)} = {_value(v)}" for k, v in table.items()]
    for key, items in arrays:
        for table in items:
            lines += ["", f"[[{_key(key)}]]"]
            lines += [f"{_key(k)} = {_value(v)}" for k, v in table.items()]
    return "\n".join(lines) + "\n"


class SceneEdit:
    """A copy of a scene as nested dicts and lists, set by parameter path.

        edit = SceneEdit(calder.Scene("exercise-2.16"))
        edit["fields[0].law.G"] = 2
        edit["world.dt"] = 0.5
        scene = edit.scene()        # calder's reader checks every value

    ``edit.data`` is the dict itself, for any other change.
    """

    def __init__(self, scene: Union[Scene, str, "SceneEdit"]):
        if isinstance(scene, SceneEdit):
            self.data = copy.deepcopy(scene.data)
            self.name = scene.name
            return
        if tomllib is None:  # pragma: no cover
            raise Error("editing a scene needs tomllib (Python 3.11) or tomli")
        if isinstance(scene, str):
            scene = Scene(scene)
        self.name = scene.name
        self.data = tomllib.loads(scene.to_toml())

    def _walk(self, path: str, create: bool) -> Tuple[Any, Step]:
        steps = parse_path(path)
        node: Any = self.data
        for depth, step in enumerate(steps[:-1]):
            node = self._child(node, steps, depth, create)
        last = steps[-1]
        self._check_container(node, steps, len(steps) - 1)
        return node, last

    def _check_container(self, node: Any, steps: List[Step], depth: int) -> None:
        step = steps[depth]
        where = _spelled(steps[:depth]) or "the scene"
        if isinstance(step, int):
            if not isinstance(node, list):
                raise Error(f"parameter '{_spelled(steps)}': '{where}' is not a list of tables, "
                            "so it takes no [index]")
            if step >= len(node):
                raise Error(f"parameter '{_spelled(steps)}': the scene has {len(node)} "
                            f"'{where}' (indices 0 to {len(node) - 1})" if node else
                            f"parameter '{_spelled(steps)}': the scene has no '{where}'")
        elif not isinstance(node, dict):
            raise Error(f"parameter '{_spelled(steps)}': '{where}' is a "
                        f"{'list' if isinstance(node, list) else 'value'}, not a table; "
                        f"{'pick one with [index]' if isinstance(node, list) else 'it has no keys'}")

    def _child(self, node: Any, steps: List[Step], depth: int, create: bool) -> Any:
        self._check_container(node, steps, depth)
        step = steps[depth]
        if isinstance(step, int):
            return node[step]
        if step not in node:
            following = steps[depth + 1]
            if isinstance(following, int) or not create:
                known = ", ".join(f"'{k}'" for k in node) or "none"
                raise Error(f"parameter '{_spelled(steps)}': the scene has no "
                            f"'{_spelled(steps[:depth + 1])}' (its keys here: {known})")
            node[step] = {}  # the scene reader judges the new key
        return node[step]

    def __setitem__(self, path: str, value: Any) -> None:
        node, last = self._walk(path, create=True)
        _value(value)  # refuses what a scene file can't hold, by type
        node[last] = value

    def set(self, path: str, value: Any) -> None:
        """edit.set(path, value): edit[path] = value, as an expression."""
        self[path] = value

    def __getitem__(self, path: str) -> Any:
        node, last = self._walk(path, create=False)
        if isinstance(last, str) and last not in node:
            raise KeyError(path)
        return node[last]

    def __contains__(self, path: str) -> bool:
        try:
            self[path]
        except (KeyError, Error):
            return False
        return True

    def paths(self) -> Iterator[str]:
        """Every value's parameter path, in the scene file's order."""
        def walk(node: Any, prefix: List[Step]) -> Iterator[str]:
            if isinstance(node, dict):
                for k, v in node.items():
                    yield from walk(v, prefix + [k])
            elif isinstance(node, list) and node and all(isinstance(v, dict) for v in node):
                for i, v in enumerate(node):
                    yield from walk(v, prefix + [i])
            else:
                yield _spelled(prefix)
        return walk(self.data, [])

    def to_toml(self) -> str:
        return to_toml(self.data)

    def scene(self, context: str = "") -> Scene:
        """The edited scene, read by calder's scene reader (which checks every
        key and value); an error names `context` (e.g. the parameters set)."""
        try:
            scene = Scene.parse(self.to_toml(), "<scene>")
            scene.validate()
        except Error as error:
            message = _LOCATION.sub("", str(error))
            raise Error(f"{context}: {message}" if context else message) from None
        return scene
