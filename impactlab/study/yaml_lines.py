"""YAML to plain Python data, remembering the line of every node so errors can point at it."""

from __future__ import annotations

import stat
from pathlib import Path as FilePath
from typing import Any

import yaml

from impactlab.errors import ResourceLimitError, StudyError
from impactlab.foreign import MAX_INPUT_BYTES, MAX_NESTING, nesting_message, shown
from impactlab.study.limits import max_yaml_nodes

#: the one size limit of an input file (impactlab.foreign.MAX_INPUT_BYTES, 64 MiB), refused by its size before a byte
#: is read
MAX_TEXT_BYTES = MAX_INPUT_BYTES
_BOMS = {b"\xff\xfe\x00\x00": "UTF-32", b"\x00\x00\xfe\xff": "UTF-32", b"\xff\xfe": "UTF-16",
         b"\xfe\xff": "UTF-16"}


def checked_bytes(path: FilePath, what: str, limit: int, missing: str = "", folder: str = "") -> bytes:
    """The bytes of a regular file of at most ``limit`` bytes, or a StudyError that says what the file is instead.

    ``what`` names the file in messages (``study file``, ``shot table``); ``missing`` and ``folder`` add advice to
    the messages of a path that does not exist or is a folder.
    """
    try:
        info = path.stat()
    except FileNotFoundError:
        raise StudyError(f"{path}: no such {what}{missing}") from None
    except OSError as exc:
        raise StudyError(f"{path}: cannot read this {what}: {exc.strerror}") from None
    if stat.S_ISDIR(info.st_mode):
        raise StudyError(f"{path}: is a folder, not a {what}{folder}")
    if not stat.S_ISREG(info.st_mode):
        raise StudyError(f"{path}: is not a regular file (a device or pipe); give a {what}")
    if info.st_size > limit:
        raise StudyError(f"{shown(path)}: {info.st_size:,} bytes ({info.st_size / 2**20:.0f} MiB) is too large for a "
                         f"{what} (at most {limit:,} bytes, {limit / 2**20:.0f} MiB, impactlab's one limit on input "
                         "files; split the file)")
    return path.read_bytes()


def read_text_file(path: FilePath, what: str = "study file") -> str:
    """The UTF-8 text of a regular file, or a StudyError that says what the file is instead."""
    data = checked_bytes(path, what, MAX_TEXT_BYTES,
                         folder=f"; give the .yaml file(s) inside it (e.g. {path}/*.yaml)")
    for bom, encoding in _BOMS.items():
        if data.startswith(bom):
            raise StudyError(f"{path}: is {encoding} text; save the {what} as UTF-8")
    if b"\0" in data:
        raise StudyError(f"{path}: " + (f"is UTF-16 text without a byte-order mark; save the {what} as UTF-8"
                                        if _utf16_without_mark(data) else
                                        f"is a binary file (it holds NUL bytes), not a YAML {what}"))
    return utf8_text(data, path, what)


def _utf16_without_mark(data: bytes) -> bool:
    """Text saved as UTF-16 without its mark (Windows tools do): every other byte NUL, the rest decode to text."""
    sample = data[:4096]
    for zeros, encoding in ((sample[1::2], "utf-16-le"), (sample[0::2], "utf-16-be")):
        if len(sample) >= 4 and zeros.count(0) >= 0.9 * len(zeros):
            try:
                text = sample[:len(sample) // 2 * 2].decode(encoding)
            except UnicodeDecodeError:
                return False
            # text, not a binary file whose header is mostly zeros (HDF5): printable characters and line breaks
            return sum(char.isprintable() or char in "\r\n\t" for char in text) >= 0.98 * len(text)
    return False


def utf8_text(data: bytes, path: FilePath, what: str) -> str:
    """``data`` decoded as UTF-8 (a byte-order mark dropped), or a StudyError at the line of the first bad byte."""
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = data[:exc.start].count(b"\n") + 1
        raise StudyError(f"{path}:{line}: is not UTF-8 text (byte 0x{data[exc.start]:02x}); save the {what} as "
                         "UTF-8") from None

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


#: deepest nesting (block levels + flow brackets) a study, table or data file may have; a study nests about 6
#: deep. PyYAML's C composer recurses once per level in C, so a document nested ~50,000 deep (100 KB of
#: ``[[[[...``) overflows the C stack and kills the process with a segmentation fault before Python can catch
#: anything: :func:`nesting_depth` measures the depth from the text, before the parser sees it.
MAX_YAML_DEPTH = MAX_NESTING  # the one bound of every structured input (impactlab.foreign)


def nesting_depth(text: str, limit: int = MAX_YAML_DEPTH) -> tuple[int, int]:
    """An upper estimate of how deep a YAML text nests, and the line where it first exceeds ``limit``.

    One pass over the text, no recursion: block levels are counted as an indentation stack (each deeper
    level starts at a larger column; the compact ``- - -`` and ``? `` indicators each open one), flow levels
    as open ``[`` and ``{`` outside quotes and comments. The estimate is never below the depth the YAML
    composer will reach (a block scalar's more-indented lines may count a few levels too many, which a limit
    of :data:`MAX_YAML_DEPTH` levels leaves harmless).

    Parameters
    ----------
    text : str
        The YAML text.
    limit : int
        Depth at which to stop and report the line.

    Returns
    -------
    (depth, line) : (int, int)
        The deepest level seen (``limit + 1`` when the scan stopped early) and the 1-based line where the
        limit was passed (0 if it was not).
    """
    stack: list[int] = []
    flow = 0
    deepest = 0
    quote = ""
    for number, line in enumerate(text.splitlines(), start=1):
        position, length = 0, len(line)
        if flow == 0 and not quote:
            while position < length and line[position] in " \t":
                position += 1
            if position == length or line[position] == "#":
                continue
            if line.startswith(("---", "..."), position) and position == 0:
                stack.clear()
                continue
            column = position
            while True:
                while stack and stack[-1] >= column:
                    stack.pop()
                stack.append(column)
                if line[position:position + 2] in ("- ", "? ") or line[position:] in ("-", "?"):
                    position += 2
                    while position < length and line[position] == " ":
                        position += 1
                    column = position
                    if len(stack) > limit:
                        return len(stack), number
                    if position >= length:
                        break
                    continue
                break
        previous, plain = " ", False
        for char in line[position:]:
            if quote:
                if char == quote:
                    quote, plain = "", False
                previous = char
                continue
            if char == "#" and previous in " \t":
                break
            elif plain and not (char == ":" or (flow and char in ",]}")):
                pass  # inside plain text ("x[1]", "it's"): brackets and quotes are text
            elif char in "\"'":
                quote = char
            elif char in "[{":
                flow += 1
                deepest = max(deepest, len(stack) + flow)
                if deepest > limit:
                    return deepest, number
            elif char in "]}":
                flow = max(flow - 1, 0)
            plain = (plain and char != ":" and not (flow and char in ",]}")) or char not in " \t,:-?[]{}\"'"
            previous = char
        if not flow:
            quote = ""  # a quoted scalar of a block value that runs on is read as more lines: over, never under
        depth = len(stack) + flow
        if depth > deepest:
            deepest = depth
            if deepest > limit:
                return deepest, number
    return deepest, 0


#: what splits lines for str.splitlines (nesting_depth's lines), "\r\n" counted twice
_LINE_BREAKS = ("\n", "\r", "\v", "\f", "\x1c", "\x1d", "\x1e", "\x85", "\u2028", "\u2029")


def nesting_bound(text: str) -> int:
    """A bound :func:`nesting_depth` never exceeds, counted at C speed: a short text needs no scan.

    The scan's depth is its block levels plus its open flow brackets. A block level is opened at most once per
    line and once per compact ``-`` or ``?`` indicator, a flow level once per ``[`` or ``{``; so the depth is at most
    the lines (here every line break, counted generously) plus those characters, wherever they stand.
    """
    return (sum(text.count(mark) for mark in _LINE_BREAKS) + 1 + text.count("-") + text.count("?")
            + text.count("[") + text.count("{"))


#: libyaml's parser where PyYAML was built with it (10x faster than the pure-Python one, the same nodes and marks)
_LOADER = getattr(yaml, "CSafeLoader", yaml.SafeLoader)


def load_yaml(text: str, file: str | None = None) -> tuple[Any, dict[Path, int]]:
    """Parse YAML text into Python data and a map from node path to 1-based line number.

    Duplicate keys, which plain PyYAML silently overwrites, are refused. Aliases are expanded into
    plain data (a study is a tree), so a recursive alias is refused and the expansion is bounded by
    :func:`impactlab.study.limits.max_yaml_nodes` nodes: ten nested aliases of ten items each would
    otherwise make 10^10 nodes.
    """
    if len(text) > MAX_TEXT_BYTES:
        raise StudyError(f"{file or '<study>'}: {len(text):,} characters is too large for a YAML document (at most "
                         f"{MAX_TEXT_BYTES:,})")
    depth, line = nesting_depth(text) if nesting_bound(text) > MAX_YAML_DEPTH else (0, 0)
    if line:
        raise StudyError(f"{shown(file or '<study>')}:{line}: {nesting_message('YAML', MAX_YAML_DEPTH)}")
    loader = _LOADER(text)
    try:
        node = loader.get_single_node()
        lines: dict[Path, int] = {}
        budget = _Budget(max_yaml_nodes(), file)
        data = _convert(loader, node, (), lines, file, budget) if node is not None else None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f"{file or '<study>'}:{mark.line + 1}" if mark else (file or "<study>")
        problem = getattr(exc, "problem", None) or " ".join(str(exc).split())  # one line (a ReaderError has two)
        context, context_mark = getattr(exc, "context", None), getattr(exc, "context_mark", None)
        if context and context_mark:
            problem += f" ({context} on line {context_mark.line + 1})"
        raise StudyError(f"{where}: not valid YAML: {problem}") from None
    except RecursionError:  # nesting thousands deep, or a merge key (<<) that merges its own mapping
        raise StudyError(f"{file or '<study>'}: the YAML nests too deeply or merges a mapping into itself") from None
    finally:
        loader.dispose()
    return data, lines


class _Budget:
    """Nodes left to expand, and the collection nodes on the way down (an alias to one of them is a cycle)."""

    def __init__(self, nodes: int, file):
        self.left, self.limit, self.file = nodes, nodes, file or "<study>"
        self.open: set[int] = set()

    def enter(self, node, path: Path) -> None:
        if id(node) in self.open:
            raise StudyError(f"{self.file}:{node.start_mark.line + 1}: {format_path(path) or '<top>'}: a recursive "
                             "alias (a node that contains itself); write the data out instead")
        self.left -= 1
        if self.left < 0:
            raise ResourceLimitError(f"{self.file}: the YAML expands (through its aliases) to more than "
                                     f"{self.limit:,} nodes; write the data out, or raise IMPACTLAB_MAX_YAML_NODES")


def _convert(loader, node, path: Path, lines: dict[Path, int], file, budget: _Budget):
    budget.enter(node, path)
    lines[path] = node.start_mark.line + 1
    if isinstance(node, yaml.MappingNode):
        budget.open.add(id(node))
        loader.flatten_mapping(node)
        result = {}
        for key_node, value_node in node.value:
            if not isinstance(key_node, yaml.ScalarNode):  # a list or mapping as a key: never a study's
                raise StudyError(f"{file or '<study>'}:{key_node.start_mark.line + 1}: {format_path(path) or '<top>'}: "
                                 "a key must be a plain name, not a list or mapping")
            key = loader.construct_object(key_node, deep=True)
            if key in result:
                raise StudyError(f"{file or '<study>'}:{key_node.start_mark.line + 1}: "
                                 f"{format_path(path + (key,))}: key given twice")
            result[key] = _convert(loader, value_node, path + (key,), lines, file, budget)
        budget.open.discard(id(node))
        return result
    if isinstance(node, yaml.SequenceNode):
        budget.open.add(id(node))
        items = [_convert(loader, item, path + (index,), lines, file, budget) for index, item in enumerate(node.value)]
        budget.open.discard(id(node))
        return items
    return loader.construct_object(node, deep=True)


def line_of(lines: dict[Path, int], path: Path) -> int | None:
    """Line of ``path`` or of its nearest ancestor that has one."""
    while True:
        if path in lines:
            return lines[path]
        if not path:
            return None
        path = path[:-1]
