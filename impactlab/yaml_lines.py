"""YAML to plain Python data, remembering the line of every node so errors can point at it."""

from __future__ import annotations

from typing import Any

import yaml

from .errors import StudyError

Path = tuple[Any, ...]


def format_path(path: Path) -> str:
    """('models', 2, 'name') -> 'models[2].name'."""
    text = ""
    for part in path:
        if isinstance(part, int):
            text += f"[{part}]"
        else:
            text += f".{part}" if text else str(part)
    return text


def parse_path(text: str) -> Path:
    """Inverse of :func:`format_path` for paths without dots inside keys."""
    parts: list[Any] = []
    for chunk in text.split("."):
        while "[" in chunk:
            head, _, rest = chunk.partition("[")
            if head:
                parts.append(head)
            index, _, chunk = rest.partition("]")
            parts.append(int(index))
        if chunk:
            parts.append(chunk)
    return tuple(parts)


def load_yaml(text: str, file: str | None = None) -> tuple[Any, dict[Path, int]]:
    """Parse YAML text into Python data and a map from node path to 1-based line number.

    Duplicate keys, which plain PyYAML silently overwrites, are refused.
    """
    loader = yaml.SafeLoader(text)
    try:
        node = loader.get_single_node()
        lines: dict[Path, int] = {}
        data = _convert(loader, node, (), lines, file) if node is not None else None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f"{file or '<study>'}:{mark.line + 1}" if mark else (file or "<study>")
        problem = getattr(exc, "problem", None) or str(exc)
        context, context_mark = getattr(exc, "context", None), getattr(exc, "context_mark", None)
        if context and context_mark:
            problem += f" ({context} on line {context_mark.line + 1})"
        raise StudyError(f"{where}: not valid YAML: {problem}") from None
    finally:
        loader.dispose()
    return data, lines


def _convert(loader, node, path: Path, lines: dict[Path, int], file):
    lines[path] = node.start_mark.line + 1
    if isinstance(node, yaml.MappingNode):
        loader.flatten_mapping(node)
        result = {}
        for key_node, value_node in node.value:
            key = loader.construct_object(key_node, deep=True)
            if key in result:
                raise StudyError(f"{file or '<study>'}:{key_node.start_mark.line + 1}: "
                                 f"{format_path(path + (key,))}: key given twice")
            result[key] = _convert(loader, value_node, path + (key,), lines, file)
        return result
    if isinstance(node, yaml.SequenceNode):
        return [_convert(loader, item, path + (index,), lines, file) for index, item in enumerate(node.value)]
    return loader.construct_object(node, deep=True)


def line_of(lines: dict[Path, int], path: Path) -> int | None:
    """Line of ``path`` or of its nearest ancestor that has one."""
    while True:
        if path in lines:
            return lines[path]
        if not path:
            return None
        path = path[:-1]
