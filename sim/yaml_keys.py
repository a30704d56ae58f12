"""Mapping keys of a composed YAML document: the line of each, and a key given twice refused.

YAML's loaders keep the last of two equal keys without a word (a body or joint defined twice
would vanish), so every reader of a file the user writes (scenes, recording metadata, sensor
settings) composes the document first and walks it here before building the data.
"""

import yaml

#: a key's place in the document: mapping keys (str) and sequence indices (int), outermost first
KeyPath = tuple[str | int, ...]


class DuplicateKeyError(ValueError):
    """A mapping key given twice under one parent: its path and the 1-based lines of both."""

    def __init__(self, path: KeyPath, first_line: int, second_line: int) -> None:
        self.path, self.first_line, self.second_line = path, first_line, second_line
        super().__init__(f"key '{dotted(path)}' given twice (lines {first_line}, {second_line})")


def dotted(path: KeyPath) -> str:
    """A key path as the user writes it: ``bodies.crank``, ``points[0].x``."""
    text = ""
    for part in path:
        text += f"[{part}]" if isinstance(part, int) else (f".{part}" if text else part)
    return text


def key_lines(node: yaml.Node | None, prefix: KeyPath = ()) -> dict[KeyPath, int]:
    """1-based line of every mapping key under `node`, by key path, at any depth (through
    sequences too); DuplicateKeyError for the first key given twice under one parent."""
    lines: dict[KeyPath, int] = {}
    if isinstance(node, yaml.SequenceNode):
        for index, item in enumerate(node.value):
            lines.update(key_lines(item, (*prefix, index)))
    elif isinstance(node, yaml.MappingNode):
        for key_node, value_node in node.value:
            path = (*prefix, str(key_node.value))
            line = key_node.start_mark.line + 1
            if path in lines:
                raise DuplicateKeyError(path, lines[path], line)
            lines[path] = line
            lines.update(key_lines(value_node, path))
    return lines
