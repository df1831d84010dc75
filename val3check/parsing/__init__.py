"""VAL 3 code -> typed syntax tree (`ast`), with syntax errors as diagnostics (F101-F105).

    from val3check.parsing.parser import parse_code, parse_program, scan_comments
"""
