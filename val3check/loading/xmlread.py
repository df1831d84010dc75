"""Read one XML file safely into a small element tree with file positions.

Security: expat is configured as defusedxml configures it (defusedxml.expatreader /
defusedxml.common): parameter entities are never parsed, any entity declaration (internal,
external or unparsed) stops the parse, external entity references and external DTD subsets
are refused and never fetched, and a reference to an entity that is not one of the five
predefined ones is an error. Nothing outside the file is ever read.

Positions: expat counts lines (after CRLF / CR normalisation) and columns in code points,
0-based; every position stored here is 1-based. The text of `<Code>` / `<code>` elements is
kept with a SourceMap that maps every character back to the file, whether it came from
CDATA or from escaped text (`&gt;` is one character of code but four columns of file).
"""

from __future__ import annotations

from xml.parsers import expat

from defusedxml.common import (
    DTDForbidden,
    EntitiesForbidden,
    ExternalReferenceForbidden,
)

from .. import confine
from ..confine import Roots
from ..diagnostics import Diagnostic
from ..light_dataclass import dataclass, field
from ..positions import Position, SourceMap, line_starts
from ..rules import codes

XSI_NS = "http://www.w3.org/2001/XMLSchema-instance"
_SEP = " "  # namespace separator given to expat: "uri local"
_CODE_TAGS = frozenset({"code"})  # elements whose text is kept with a SourceMap
_TEXT_TAGS = frozenset({"description"})  # elements whose plain text is kept


@dataclass(slots=True, eq=False)
class Node:
    tag: str  # local name, as written
    ns: str  # namespace URI, "" when none
    attrs: dict[str, str]  # local attribute names; xsi:* attributes keyed "xsi:type" etc.
    line: int  # 1-based position of the "<" of the start tag
    col: int
    children: list["Node"] = field(default_factory=list)
    text: str = ""  # only for code and description elements
    smap: SourceMap | None = None  # only for code elements

    @property
    def ltag(self) -> str:
        return self.tag.lower()

    def find(self, *names: str) -> "Node | None":
        """First child whose local name is one of `names` (case-insensitive)."""
        for c in self.children:
            if c.tag.lower() in names:
                return c
        return None

    def findall(self, *names: str) -> list["Node"]:
        return [c for c in self.children if c.tag.lower() in names]

    def get(self, name: str, default: str | None = None) -> str | None:
        """Attribute by name, case-insensitive fallback (files from old tools vary)."""
        v = self.attrs.get(name)
        if v is not None:
            return v
        low = name.lower()
        for k, val in self.attrs.items():
            if k.lower() == low:
                return val
        return default


class _Forbidden(Exception):
    def __init__(self, message: str, line: int, col: int) -> None:
        super().__init__(message)
        self.message = message
        self.line = line
        self.col = col


# Plain-words versions of expat's messages (F004).
_PLAIN: dict[int, str] = {}


def _init_plain() -> None:
    c = expat.errors.codes
    plain = {
        "XML_ERROR_SYNTAX": "syntax error",
        "XML_ERROR_INVALID_TOKEN": (
            "a character here is not allowed in XML (a bare '<' or '&' in text must be written"
            " &lt; or &amp;, or the text put in a CDATA section)"
        ),
        "XML_ERROR_UNCLOSED_TOKEN": "the file ends in the middle of a tag (is it truncated?)",
        "XML_ERROR_PARTIAL_CHAR": "the file ends in the middle of a character (is it truncated?)",
        "XML_ERROR_DUPLICATE_ATTRIBUTE": "an attribute is written twice on this element",
        "XML_ERROR_JUNK_AFTER_DOC_ELEMENT": "there is text or another element after the end of the root element",
        "XML_ERROR_UNCLOSED_CDATA_SECTION": "a CDATA section is not closed (missing ']]>'; is the file truncated?)",
        "XML_ERROR_UNBOUND_PREFIX": (
            "a namespace prefix is used without being declared (for example xsi: needs"
            ' xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" on the root element)'
        ),
        "XML_ERROR_MISPLACED_XML_PI": "the XML declaration '<?xml ...?>' must be at the very start of the file",
        "XML_ERROR_INCORRECT_ENCODING": "the encoding declared in the XML declaration does not match the file",
        "XML_ERROR_BAD_CHAR_REF": "a character reference (&#...;) names a character that XML does not allow",
        "XML_ERROR_INVALID_ARGUMENT": "invalid document",
    }
    for name, text in plain.items():
        err = getattr(expat.errors, name, None)
        if err is not None and err in c:
            _PLAIN[c[err]] = text


_init_plain()
_CODE_NO_ELEMENTS = expat.errors.codes[expat.errors.XML_ERROR_NO_ELEMENTS]
_CODE_INVALID_TOKEN = expat.errors.codes[expat.errors.XML_ERROR_INVALID_TOKEN]
_CODE_TAG_MISMATCH = expat.errors.codes[expat.errors.XML_ERROR_TAG_MISMATCH]
_CODE_UNCLOSED_CDATA = expat.errors.codes[expat.errors.XML_ERROR_UNCLOSED_CDATA_SECTION]
_CODE_UNDEFINED_ENTITY = expat.errors.codes[expat.errors.XML_ERROR_UNDEFINED_ENTITY]
_CODE_ASYNC_ENTITY = expat.errors.codes.get(getattr(expat.errors, "XML_ERROR_ASYNC_ENTITY", ""), -1)
_CODE_RECURSIVE = expat.errors.codes[expat.errors.XML_ERROR_RECURSIVE_ENTITY_REF]
_CODE_AMPLIFICATION = expat.errors.codes.get(getattr(expat.errors, "XML_ERROR_AMPLIFICATION_LIMIT_BREACH", ""), -1)


class _CodeCollector:
    """Builds the text of a code element and its SourceMap from expat's character chunks."""

    __slots__ = (
        "parts",
        "starts",
        "col_maps",
        "cur_line",
        "cur_start_col",
        "cur_len",
        "next_col",
        "cur_cols",
        "pending_cr",
    )

    def __init__(self, line: int, col: int) -> None:
        self.parts: list[str] = []
        self.starts: list[Position] = []
        self.col_maps: dict[int, list[int]] = {}
        self.cur_line = line  # file line of the current code line
        self.cur_start_col = col  # file column of its first character
        self.cur_len = 0  # characters in the current code line so far
        self.next_col = col  # file column where the next contiguous character would be
        self.cur_cols: list[int] | None = None  # explicit columns once they stop being contiguous
        self.pending_cr = False

    def _newline(self, line: int, col: int) -> None:
        self.parts.append("\n")
        self._close_line()
        self.cur_line, self.cur_start_col, self.next_col = line, col, col
        self.cur_len = 0
        self.cur_cols = None

    def _close_line(self) -> None:
        self.starts.append(Position(self.cur_line, self.cur_start_col))
        if self.cur_cols is not None:
            self.col_maps[len(self.starts) - 1] = self.cur_cols

    def _chars(self, text: str, line: int, col: int, width: int) -> None:
        """`text` (no newline) starts at file (line, col); each character is `width` columns
        wide in the file when `width` > 0 (1 for literal text); for a reference, `width` is
        the width of the whole reference and `text` is its one replacement character."""
        if not text:
            return
        if self.cur_len == 0 and self.cur_cols is None:
            self.cur_line, self.cur_start_col, self.next_col = line, col, col
        if self.cur_cols is None and col == self.next_col and line == self.cur_line and width == 1:
            self.cur_len += len(text)
            self.next_col += len(text)
        else:
            if self.cur_cols is None:
                self.cur_cols = [self.cur_start_col + i for i in range(self.cur_len)]
            if width == 1:
                self.cur_cols.extend(range(col, col + len(text)))
                self.next_col = col + len(text)
            else:
                self.cur_cols.extend([col] * len(text))
                self.next_col = col + width
            self.cur_len += len(text)
        self.parts.append(text)

    def literal(self, text: str, line: int, col: int) -> None:
        if self.pending_cr:
            self.pending_cr = False
        if "\n" not in text:
            self._chars(text, line, col, 1)
            return
        pieces = text.split("\n")
        self._chars(pieces[0], line, col, 1)
        for k, piece in enumerate(pieces[1:], 1):
            self._newline(line + k, 1)
            self._chars(piece, line + k, 1, 1)

    def verbatim(self, text: str, line: int, col: int) -> None:
        """A whole CDATA section's text, starting at file (line, col): verbatim, so every line
        after the first starts at column 1. Same result as `literal`, without the per-line
        work (a third of the loading time of a large application)."""
        self.pending_cr = False
        nl = text.count("\n")
        if not nl:
            self._chars(text, line, col, 1)
            return
        first = text.find("\n")
        self._chars(text[:first], line, col, 1)
        self._close_line()
        self.starts.extend(line_starts(line + 1, line + nl))
        last = text[text.rindex("\n") + 1:]
        self.parts.append(text[first:])
        self.cur_line, self.cur_start_col = line + nl, 1
        self.cur_len, self.next_col, self.cur_cols = len(last), 1 + len(last), None

    def reference(self, text: str, line: int, col: int, width: int) -> None:
        """A character or entity reference (`&gt;`, `&#10;`), `width` columns in the file."""
        if text == "\n" and self.pending_cr:  # &#13;&#10: one line end
            self.pending_cr = False
            return
        self.pending_cr = False
        if text in ("\n", "\r"):
            self.pending_cr = text == "\r"
            self._newline(line, col + width)
            return
        self._chars(text, line, col, width)

    def finish(self) -> tuple[str, SourceMap]:
        self._close_line()
        return "".join(self.parts), SourceMap(self.starts, self.col_maps)


@dataclass(slots=True)
class XmlResult:
    root: Node | None
    diagnostics: list[Diagnostic]
    size: int = 0  # bytes read
    lines: int = 0  # lines in the file


def _count_lines(data: bytes) -> int:
    if not data:
        return 0
    n = data.count(b"\n") + data.count(b"\r") - data.count(b"\r\n")
    if not data.endswith((b"\n", b"\r")):
        n += 1
    return n


def _line_col_of_offset(prefix: str) -> tuple[int, int]:
    """1-based line and column of the character that follows `prefix`."""
    line = 1 + prefix.count("\n") + prefix.count("\r") - prefix.count("\r\n")
    last = max(prefix.rfind("\n"), prefix.rfind("\r"))
    return line, len(prefix) - last  # last == -1 -> len + 1


def read_bytes(path: str, max_size: int, roots: Roots,
               overlay: dict[str, bytes] | None = None) -> tuple[bytes | None, list[Diagnostic]]:
    """The file's bytes (or its unsaved text from `overlay`), or None with F001 (cannot read),
    F002 (too large) or F014 (outside the allowed roots): `val3check.confine.read_bytes` decides."""
    try:
        return confine.read_bytes(path, roots, max_size, overlay), []
    except confine.Refused as exc:
        return None, [Diagnostic(exc.code, exc.reason, path)]


def decode(data: bytes, path: str) -> tuple[bytes | None, list[Diagnostic]]:
    """UTF-8 bytes without BOM ready for expat, or None with F003 at the first bad byte.

    A UTF-16 byte-order mark is accepted (re-encoded to UTF-8): be liberal in what we read.
    """
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]
    elif data.startswith((b"\xff\xfe\x00\x00", b"\x00\x00\xfe\xff")):  # before UTF-16: same first bytes
        try:
            return data.decode("utf-32").encode("utf-8"), []
        except UnicodeDecodeError:
            return None, [
                Diagnostic(
                    codes.INVALID_UTF8, "the file starts with a UTF-32 byte-order mark but is not valid UTF-32", path
                )
            ]
    elif data.startswith((b"\xff\xfe", b"\xfe\xff")):
        try:
            return data.decode("utf-16").encode("utf-8"), []
        except UnicodeDecodeError:
            return None, [
                Diagnostic(
                    codes.INVALID_UTF8, "the file starts with a UTF-16 byte-order mark but is not valid UTF-16", path
                )
            ]
    try:
        data.decode("utf-8")
    except UnicodeDecodeError as exc:
        prefix = data[: exc.start].decode("utf-8")
        line, col = _line_col_of_offset(prefix)
        bad = data[exc.start : exc.start + 1].hex().upper()
        return None, [
            Diagnostic(
                codes.INVALID_UTF8,
                f"invalid UTF-8 (byte 0x{bad}); VAL 3 files are UTF-8: re-save the file as UTF-8",
                path,
                line,
                col,
            )
        ]
    return data, []


def parse(data: bytes, path: str) -> tuple[Node | None, list[Diagnostic]]:
    """Parse UTF-8 bytes (no BOM) into a Node tree; never raises for bad input."""
    parser = expat.ParserCreate(encoding="UTF-8", namespace_separator=_SEP)
    # defusedxml.expatreader / defusedxml.common: never parse parameter entities, forbid entity
    # declarations, refuse external references (nothing is fetched or read).
    parser.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)
    parser.buffer_text = False
    parser.ordered_attributes = False

    root_holder: list[Node] = []
    stack: list[Node] = []
    state = {"cdata": False}
    cdata: list = []  # [line, col, chunks...] of the CDATA section being read in a code element
    cdata_at = [0, 0]  # where the text of the CDATA section being read starts
    collectors: list[_CodeCollector | None] = []
    texts: list[list[str] | None] = []

    def where(back_to: bytes | None = None) -> tuple[int, int]:
        """The current position, or that of the last `back_to` before it (the start of the
        declaration expat has just read, rather than its end)."""
        if back_to is not None:
            bi = parser.CurrentByteIndex
            start = data.rfind(back_to, 0, max(bi, 0) + len(back_to))
            if start >= 0:
                return _line_col_of_offset(data[:start].decode("utf-8", "replace"))
        return parser.CurrentLineNumber, parser.CurrentColumnNumber + 1

    def start(name: str, attrs: dict[str, str]) -> None:
        ns, _, local = name.rpartition(_SEP)
        if attrs:
            a: dict[str, str] = {}
            for k, v in attrs.items():
                if _SEP in k:
                    kns, _, kl = k.rpartition(_SEP)
                    a[("xsi:" + kl) if kns == XSI_NS else kl] = v
                else:
                    a[k] = v
        else:
            a = {}
        line, col = parser.CurrentLineNumber, parser.CurrentColumnNumber + 1
        node = Node(local, ns, a, line, col)
        if stack:
            stack[-1].children.append(node)
        else:
            root_holder.append(node)
        stack.append(node)
        low = local.lower()
        if low in _CODE_TAGS:
            collectors.append(_CodeCollector(line, col))
            texts.append(None)
        elif low in _TEXT_TAGS:
            collectors.append(None)
            texts.append([])
        else:
            collectors.append(None)
            texts.append(None)

    def flush_cdata() -> None:
        if cdata and collectors and collectors[-1] is not None:
            collectors[-1].verbatim("".join(cdata[2:]), cdata[0], cdata[1])
        cdata.clear()

    def end(name: str) -> None:
        if cdata:
            flush_cdata()
        node = stack.pop()
        coll = collectors.pop()
        txt = texts.pop()
        if coll is not None:
            node.text, node.smap = coll.finish()
        elif txt is not None:
            node.text = "".join(txt)

    def chars(text: str) -> None:
        if not collectors:
            return
        coll = collectors[-1]
        if coll is not None:
            if state["cdata"]:  # gathered, handled in one piece at the end of the section
                if not cdata:
                    cdata.extend(cdata_at)
                cdata.append(text)
                return
            line = parser.CurrentLineNumber
            col = parser.CurrentColumnNumber + 1
            bi = parser.CurrentByteIndex
            if 0 <= bi < len(data) and data[bi] == 0x26:  # "&": a reference
                semi = data.find(b";", bi, bi + 40)
                width = (semi - bi + 1) if semi > 0 else 1
                coll.reference(text, line, col, width)
                return
            coll.literal(text, line, col)
            return
        txt = texts[-1]
        if txt is not None:
            txt.append(text)

    def cdata_start() -> None:
        state["cdata"] = True
        # The section's text starts after `<![CDATA[` (9 columns, no line end). expat buffers
        # it into a few callbacks rather than one a line (the callbacks were a third of the
        # reading); a buffered callback comes late, with the position of the next event, so
        # the position is taken here.
        cdata_at[:] = (parser.CurrentLineNumber, parser.CurrentColumnNumber + 10)
        parser.buffer_text = True

    def cdata_end() -> None:
        parser.buffer_text = False  # expat has delivered the buffered text before this call
        flush_cdata()
        state["cdata"] = False

    def entity_decl(name, is_param, value, base, sysid, pubid, notation):  # noqa: ANN001
        line, col = where(b"<!DOCTYPE")
        kind = "parameter entity" if is_param else "entity"
        raise _Forbidden(
            f"the document declares the {kind} '{name}'; entity declarations are not allowed in"
            " VAL 3 files and are never expanded: the file was not read",
            line,
            col,
        )

    def unparsed_decl(name, base, sysid, pubid, notation):  # noqa: ANN001
        line, col = where(b"<!DOCTYPE")
        raise _Forbidden(
            f"the document declares the unparsed entity '{name}'; entity declarations are not"
            " allowed in VAL 3 files: the file was not read",
            line,
            col,
        )

    def external_ref(context, base, sysid, pubid):  # noqa: ANN001
        line, col = where()
        raise _Forbidden(
            "the document refers to an external entity; external entities are never fetched or"
            " read: the file was not read",
            line,
            col,
        )

    def doctype(name, sysid, pubid, has_internal):  # noqa: ANN001
        if sysid or pubid:
            line, col = where(b"<!DOCTYPE")
            raise _Forbidden(
                "the document type declaration refers to an external DTD; external DTDs are never"
                " fetched or read: the file was not read",
                line,
                col,
            )

    def skipped(name, is_param):  # noqa: ANN001
        line, col = where()
        raise _Forbidden(
            f"reference to the undeclared entity '&{name};': only &lt; &gt; &amp; &quot; &apos;"
            " and character references (&#...;) are allowed",
            line,
            col,
        )

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    parser.CharacterDataHandler = chars
    parser.StartCdataSectionHandler = cdata_start
    parser.EndCdataSectionHandler = cdata_end
    parser.EntityDeclHandler = entity_decl
    parser.UnparsedEntityDeclHandler = unparsed_decl
    parser.ExternalEntityRefHandler = external_ref
    parser.StartDoctypeDeclHandler = doctype
    parser.SkippedEntityHandler = skipped

    try:
        parser.Parse(data, True)
    except _Forbidden as exc:
        return None, [Diagnostic(codes.FORBIDDEN_ENTITY, exc.message, path, exc.line, exc.col)]
    except (EntitiesForbidden, ExternalReferenceForbidden, DTDForbidden) as exc:  # pragma: no cover
        return None, [Diagnostic(codes.FORBIDDEN_ENTITY, str(exc), path, 0, 0)]
    except expat.ExpatError as exc:
        return None, [_expat_diagnostic(exc, parser, data, path, stack)]
    except RecursionError:  # pragma: no cover - expat does not recurse in Python
        return None, [Diagnostic(codes.MALFORMED_XML, "malformed XML: elements nested too deeply", path)]
    if not root_holder:  # pragma: no cover - expat reports "no element found" first
        return None, [Diagnostic(codes.MALFORMED_XML, "malformed XML: no root element", path)]
    return root_holder[0], []


def _expat_diagnostic(exc: expat.ExpatError, parser, data: bytes, path: str, stack: list[Node]) -> Diagnostic:  # noqa: ANN001
    code = exc.code
    line, col = exc.lineno, exc.offset + 1
    if code in (_CODE_UNDEFINED_ENTITY, _CODE_ASYNC_ENTITY, _CODE_RECURSIVE, _CODE_AMPLIFICATION):
        bi = parser.ErrorByteIndex
        name = ""
        if 0 <= bi < len(data) and data[bi] == 0x26:
            semi = data.find(b";", bi, bi + 64)
            if semi > 0:
                name = data[bi + 1 : semi].decode("utf-8", "replace")
        what = f"'&{name};'" if name else "an entity"
        return Diagnostic(
            codes.FORBIDDEN_ENTITY,
            f"reference to {what}, which is not one of the predefined entities: only &lt; &gt;"
            " &amp; &quot; &apos; and character references (&#...;) are allowed",
            path,
            line,
            col,
        )
    if code == _CODE_UNCLOSED_CDATA:
        start = data.rfind(b"<![CDATA[", 0, max(parser.ErrorByteIndex, 0) + 1)
        if start >= 0:
            line, col = _line_col_of_offset(data[:start].decode("utf-8", "replace"))
        return Diagnostic(codes.MALFORMED_XML, "malformed XML: " + _PLAIN[code], path, line, col)
    if code == _CODE_INVALID_TOKEN:
        better = _invalid_token(parser.ErrorByteIndex, data, path)
        if better is not None:
            return better
    if code == _CODE_NO_ELEMENTS:
        if not data.strip():
            return Diagnostic(codes.MALFORMED_XML, "malformed XML: the file is empty", path, 0, 0)
        if stack:
            msg = (
                f"the file ends before the element <{stack[-1].tag}> opened on line"
                f" {stack[-1].line} is closed (is it truncated?)"
            )
        else:
            msg = "the file contains no XML element"
        return Diagnostic(codes.MALFORMED_XML, f"malformed XML: {msg}", path, line, col)
    if code == _CODE_TAG_MISMATCH and stack:
        open_el = stack[-1]
        msg = f"this closing tag does not match the open element <{open_el.tag}> (opened on line {open_el.line})"
        return Diagnostic(codes.MALFORMED_XML, f"malformed XML: {msg}", path, line, col)
    msg = _PLAIN.get(code) or expat.ErrorString(code)
    return Diagnostic(codes.MALFORMED_XML, f"malformed XML: {msg}", path, line, col)


def _invalid_token(bi: int, data: bytes, path: str) -> Diagnostic | None:
    """Say what the 'invalid token' really is: a control character, or the `]]>` that ended a
    CDATA section early (a string of code holding "]]>") rather than the one expat stops at."""
    if not 0 <= bi < len(data):
        return None
    byte = data[bi]
    if byte < 0x20 and byte not in (0x09, 0x0A, 0x0D):
        line, col = _line_col_of_offset(data[:bi].decode("utf-8", "replace"))
        return Diagnostic(
            codes.MALFORMED_XML,
            f"malformed XML: the control character U+{byte:04X} is not allowed in an XML file, even in a CDATA"
            " section; remove it (in a string, build it with chr())",
            path,
            line,
            col,
        )
    here = data.find(b"]]>", max(0, bi - 2), bi + 3)  # expat points at one of its characters
    if here >= 0:
        bi = here
        start = data.rfind(b"<![CDATA[", 0, bi)
        early = data.find(b"]]>", start + 9, bi) if start >= 0 else -1
        if early >= 0:
            line, col = _line_col_of_offset(data[:early].decode("utf-8", "replace"))
            return Diagnostic(
                codes.MALFORMED_XML,
                "malformed XML: this ']]>' ends the CDATA section of the code early (a string holding ']]>'?),"
                ' so the code after it is read as XML; write the string as "]]" + ">"',
                path,
                line,
                col,
            )
    return None


def read_xml(path: str, max_size: int, roots: Roots, overlay: dict[str, bytes] | None = None) -> XmlResult:
    """Read, decode and parse one file: F001/F002/F003/F004/F005/F014 diagnostics, never raises.
    `overlay`: absolute path -> unsaved text read instead of the file (confine.read_bytes)."""
    data, diags = read_bytes(path, max_size, roots, overlay)
    if data is None:
        return XmlResult(None, diags)
    size = len(data)
    utf8, diags = decode(data, path)
    if utf8 is None:
        return XmlResult(None, diags, size)
    root, diags = parse(utf8, path)
    return XmlResult(root, diags, size, _count_lines(utf8))
