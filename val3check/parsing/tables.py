"""The parse tables of a Lark LALR parser as plain Python data (`compile_tables`), the form
`_tables.py` ships and engine.py runs without Lark. `methods`: the names of the parser's tree
builder (`builder.Builder`), the callbacks a rule may have."""

from __future__ import annotations


def compile_tables(parser, methods: frozenset[str]) -> dict:
    """The parse tables of a Lark LALR parser as plain data:

    LEXER     one regex: every terminal as a named group, in Lark's order of precedence (priority,
              then longest possible match, then longest pattern); leading blanks skipped; `EOF` at
              the end. `TO`/`STEP` are left out: the lexer makes them from names (contextual).
    STATES    per state, {symbol: action}: an action >= 0 shifts to (or goes to) that state, -1-k
              reduces by RULES[k].
    RULES     per rule: (origin, number of symbols, plan); plan None: a `?rule` passing its one
              child through (only the state changes); else (callback, expand1, include, nones):
              `callback` the builder method (None: an inlined `__x` repetition, whose value is the
              list of its kept children), `expand1` a `?rule` alternative that returns a lone kept
              child, `include` the kept children as (index, inline its list, Nones before it),
              `nones` the Nones after them (absent `[x]` at the end); include None: all children
              kept as they are.
    START/END the start state and the state that accepts.
    """
    from lark.parse_tree_builder import maybe_create_child_filter
    from lark.parsers.lalr_analysis import Shift

    table = parser.parser.parser._parse_table
    lexer_conf = parser.parser.lexer_conf
    terms = [t for t in lexer_conf.terminals if t.name not in ("WS", "TO", "STEP")]
    terms.sort(key=lambda t: (-t.priority, -t.pattern.max_width, -len(t.pattern.value), t.name))
    alts = "|".join(f"(?P<{t.name}>{t.pattern.to_regexp()})" for t in terms)
    lexer = r"[ \t\f\r]*(?:" + alts + r"|(?P<EOF>\Z))"

    rules: list = []
    index: dict = {}
    states: list[dict] = [dict() for _ in range(len(table.states))]
    for state, row in sorted(table.states.items()):
        for sym, (action, arg) in sorted(row.items()):
            if action is Shift:
                states[state][sym] = arg
                continue
            if arg not in index:
                index[arg] = len(rules)
                rules.append(_rule_plan(arg, maybe_create_child_filter, methods))
            states[state][sym] = -1 - index[arg]
    missing = {r[2][0] for r in rules if r[2] is not None and r[2][0] is not None and not r[2][1]}
    missing -= methods
    if missing:
        raise SystemExit(f"no builder method for {sorted(missing)}: add them to builder.Builder")
    return {"LEXER": lexer, "STATES": states, "RULES": rules,
            "START": table.start_states["start"], "END": table.end_states["start"]}


def _rule_plan(rule, maybe_create_child_filter, methods: frozenset[str]) -> tuple:
    origin = str(rule.origin.name)
    size = len(rule.expansion)
    opts = rule.options
    if (size == 1 and opts.expand1 and not rule.alias and not rule.expansion[0].is_term
            and not rule.expansion[0].name.startswith("_")):
        return (origin, size, None)  # `?rule: other_rule`
    name = str(rule.alias or opts.template_source or origin)
    callback = None if name.startswith("_") or name not in methods else name
    filt = maybe_create_child_filter(rule.expansion, opts.keep_all_tokens, False, opts.empty_indices)
    if filt is None:
        include, nones = None, 0
    else:
        args = filt.args
        if len(args) == 2:  # ChildFilterLALR(to_include, nones_to_add)
            include, nones = tuple((i, bool(x), n) for i, x, n in args[0]), args[1]
        else:  # ChildFilterLALR_NoPlaceholders(to_include)
            include, nones = tuple((i, bool(x), 0) for i, x in args[0]), 0
    return (origin, size, (callback, bool(opts.expand1 and not rule.alias), include, nones))
