"""The one exception raised for a recording that does not follow the documented format."""


class RecordingError(ValueError):
    """A recording or its metadata breaks the format of ``data/experiment/README.md``.

    The message starts with the file name and, where the problem sits on a line, the line
    number (1-based, the CSV header being line 1), so that it can be fixed in an editor.
    """

    def __init__(
        self,
        source: str,
        message: str,
        line: int | None = None,
        last_line: int | None = None,
    ) -> None:
        self.source = source
        self.line = line
        self.last_line = last_line
        if line is None:
            where = source
        elif last_line is None or last_line == line:
            where = f"{source}, line {line}"
        else:
            where = f"{source}, lines {line}-{last_line}"
        super().__init__(f"{where}: {message}")
