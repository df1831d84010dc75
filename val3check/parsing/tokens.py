"""The tokens of VAL 3 code: reserved words, terminal names and their spellings, `Tok`."""

from __future__ import annotations

from operator import itemgetter

TYPE_CHECKING = False  # not typing's: importing typing costs 3 ms at lint's start-up
if TYPE_CHECKING:
    from typing import Any


MAX_BLOCK_DEPTH = 64  # nested if/while/do/for/switch blocks (deeper: F104)

# Reserved words (manual 2.2.5, 3.1), any case -> terminal name. `to` and `step` are not here:
# they are keywords only inside `for` (see the grammar).
KEYWORDS = {
    "begin": "BEGIN", "end": "END",
    "if": "IF", "elseif": "ELSEIF", "else": "ELSE", "endif": "ENDIF",
    "while": "WHILE", "endwhile": "ENDWHILE",
    "do": "DO", "until": "UNTIL",
    "for": "FOR", "endfor": "ENDFOR",
    "switch": "SWITCH", "case": "CASE", "default": "DEFAULT", "endswitch": "ENDSWITCH",
    "break": "BREAK", "return": "RETURN", "call": "CALL",
    "true": "TRUE", "false": "FALSE",
    "and": "AND", "or": "OR", "xor": "XOR",
    # task creation (5.10) has its own syntax: the program is written as a call
    "taskcreate": "TASKCREATE", "taskcreatesync": "TASKCREATESYNC",
}
CONTEXT_KEYWORDS = {"to": "TO", "step": "STEP"}

# The spelling the manual and the SRS editor use, for messages.
SPELLING = {
    "BEGIN": "begin", "END": "end", "IF": "if", "ELSEIF": "elseIf", "ELSE": "else",
    "ENDIF": "endIf", "WHILE": "while", "ENDWHILE": "endWhile", "DO": "do", "UNTIL": "until",
    "FOR": "for", "ENDFOR": "endFor", "SWITCH": "switch", "CASE": "case", "DEFAULT": "default",
    "ENDSWITCH": "endSwitch", "BREAK": "break", "RETURN": "return", "CALL": "call",
    "TRUE": "true", "FALSE": "false", "AND": "and", "OR": "or", "XOR": "xor",
    "TO": "to", "STEP": "step", "TASKCREATE": "taskCreate", "TASKCREATESYNC": "taskCreateSync",
}
OPENERS = {"IF", "WHILE", "DO", "FOR", "SWITCH"}
CLOSERS = {"ENDIF", "ENDWHILE", "UNTIL", "ENDFOR", "ENDSWITCH"}
CLOSER_OF = {"IF": "ENDIF", "WHILE": "ENDWHILE", "DO": "UNTIL", "FOR": "ENDFOR", "SWITCH": "ENDSWITCH"}
OPENER_OF = {"ELSEIF": "IF", "ELSE": "IF", "ENDIF": "IF", "ENDWHILE": "WHILE", "UNTIL": "DO",
              "ENDFOR": "FOR", "CASE": "SWITCH", "DEFAULT": "SWITCH", "ENDSWITCH": "SWITCH"}
STRUCTURAL = set(OPENER_OF) | {"END", "BEGIN"}

PUNCT = {
    "EQUAL": "'='", "PLUS": "'+'", "MINUS": "'-'", "BANG": "'!'", "LBRACE": "'{'",
    "_RBRACE": "'}'", "_LPAR": "'('", "_RPAR": "')'", "_LSQB": "'['", "_RSQB": "']'",
    "_COMMA": "','", "_DOT": "'.'", "_COLON": "':'", "QMARK": "'?'",
}
EXPR_START = {"NAME", "SYSNAME", "NUMBER", "BADNUMBER", "STRING", "BADSTRING", "TRUE", "FALSE",
               "_LPAR", "MINUS", "BANG", "LBRACE", "ERROR"}
STMT_START = {"CALL", "RETURN", "BREAK", "IF", "WHILE", "DO", "FOR", "SWITCH", "NAME", "SYSNAME",
               "TASKCREATE", "TASKCREATESYNC", "QMARK"}
BINOPS = {"EQUAL", "EQOP", "RELOP", "PLUS", "MINUS", "MULOP", "AND", "OR", "XOR"}
CLOSING = {"_RPAR": ("_LPAR", "')'", "'('"), "_RSQB": ("_LSQB", "']'", "'['"),
            "_RBRACE": ("LBRACE", "'}'", "'{'")}


class Tok(tuple):
    """A token: (type, value, line, column), `line`/`column` 1-based in the CODE text (not the
    file). The driver makes plain tuples (one per token: a tuple is much cheaper to make than
    an object) and the builder indexes them; error messages view them as Tok (`as_tok`)."""

    __slots__ = ()

    type = property(itemgetter(0))
    value = property(itemgetter(1))
    line = property(itemgetter(2))
    column = property(itemgetter(3))

    @property
    def end_line(self) -> int:
        return self[2]

    @property
    def end_column(self) -> int:
        return self[3] + len(self[1])

    def __repr__(self) -> str:
        return f"Tok({self[0]}, {self[1]!r}, {self[2]}:{self[3]})"


def as_tok(v: Any) -> Any:
    """A value of the parser's stack: a token (type, value, line, column) as a Tok, anything
    else (a node, a list, a builder tuple whose first item is not a string) as it is."""
    if v.__class__ is tuple and len(v) == 4 and v[0].__class__ is str:
        return Tok(v)
    return v



def clip(text: str, n: int = 30) -> str:
    """`text` shortened to `n` characters, invisible characters shown as U+XXXX."""
    text = text if len(text) <= n else text[: n - 3] + "..."
    if not text.isprintable():
        text = "".join(c if c.isprintable() else f"U+{ord(c):04X}" for c in text)
    return text

