"""The `junit` format: well-formed XML with consistent counts."""

from __future__ import annotations

import xml.etree.ElementTree as ET

from val3check.reporting import render

NASTY = "bad <tag> & \"quoted\" 'x' ]]> é 日本\nsecond line \x01\x1b end"


def sample(make_result, d):
    return make_result(
        [
            d("F001", "cannot read", "b.pgx"),
            d("F101", "unexpected 'endWhile'", "a.pgx", 12, 5),
            d("S301", NASTY, "a.pgx", 14, 0),
            d("N201", "just info", "c.pgx", 1, 1),
            d("S301", "unlisted file", "z/extra.pgx", 2, 2),
        ],
        files=["a.pgx", "b.pgx", "c.pgx", "clean.pgx"],
    )


def parse(text):
    assert text.startswith('<?xml version="1.0" encoding="UTF-8"?>\n')
    return ET.fromstring(text.encode("utf-8"))


def test_well_formed_and_counts(make_result, d):
    result = sample(make_result, d)
    result.fail_on = "warning"
    text = render("junit", result)
    assert text.isascii()
    root = parse(text)
    assert root.tag == "testsuites"
    suites = root.findall("testsuite")
    assert len(suites) == 1 and suites[0].get("name") == "val3check"
    suite = suites[0]
    cases = suite.findall("testcase")
    failures = suite.findall("testcase/failure")
    assert len(failures) == 4  # info findings are below --fail-on warning
    assert all(len(c.findall("failure")) <= 1 for c in cases)
    # 4 failing findings + passing cases for c.pgx (info only) and clean.pgx
    assert len(cases) == 6
    for element in (root, suite):
        assert element.get("tests") == str(len(cases))
        assert element.get("failures") == str(len(failures))
        assert element.get("errors") == "0"
        assert element.get("skipped") == "0"
    passing = {c.get("classname"): c for c in cases if c.find("failure") is None}
    assert set(passing) == {"c.pgx", "clean.pgx"}
    assert all(c.get("name") == "val3check" for c in passing.values())
    assert "c.pgx:1:1: N201 [info] just info" in passing["c.pgx"].find("system-out").text
    classnames = [c.get("classname") for c in cases]
    assert classnames == sorted(classnames)
    assert "z/extra.pgx" in classnames  # a finding in a file not listed in `files` is kept


def test_failures_are_what_fails_the_build(make_result, d):
    """Default --fail-on error: warnings are not failures; they go to the file's system-out."""
    suite = parse(render("junit", sample(make_result, d))).find("testsuite")
    failing = [c for c in suite.findall("testcase") if c.find("failure") is not None]
    assert sorted(c.find("failure").get("type") for c in failing) == ["F001", "F101"]
    assert suite.get("failures") == "2"
    a_cases = [c for c in suite.findall("testcase") if c.get("classname") == "a.pgx"]
    assert len(a_cases) == 1  # the F101 failure; the S301 warning is in its system-out
    assert "a.pgx:14: S301 [warning]" in a_cases[0].find("system-out").text
    extra = [c for c in suite.findall("testcase") if c.get("classname") == "z/extra.pgx"]
    assert [c.get("name") for c in extra] == ["val3check"] and extra[0].find("failure") is None
    result = sample(make_result, d)
    result.fail_on = "never"
    assert parse(render("junit", result)).get("failures") == "0"


def test_cases_carry_file_and_line(make_result, d):
    suite = parse(render("junit", sample(make_result, d))).find("testsuite")
    by_type = {c.find("failure").get("type"): c for c in suite.findall("testcase") if c.find("failure") is not None}
    assert by_type["F101"].get("file") == "a.pgx" and by_type["F101"].get("line") == "12"
    assert by_type["F001"].get("file") == "b.pgx" and by_type["F001"].get("line") is None  # the whole file
    assert all(c.get("file") == c.get("classname") for c in suite.findall("testcase"))


def test_failure_contents_round_trip(make_result, d):
    result = sample(make_result, d)
    result.fail_on = "warning"
    suite = parse(render("junit", result)).find("testsuite")
    by_type = {}
    for case in suite.findall("testcase"):
        failure = case.find("failure")
        if failure is not None:
            by_type.setdefault(failure.get("type"), []).append((case, failure))
    case, failure = by_type["F101"][0]
    assert case.get("classname") == "a.pgx"
    assert case.get("name") == "F101 syntax-error at 12:5"
    assert failure.get("message") == "F101: unexpected 'endWhile'"
    assert failure.text.startswith("a.pgx:12:5: F101 [error] unexpected 'endWhile'")
    nasty = [f for c, f in by_type["S301"] if c.get("classname") == "a.pgx"][0]
    expected = NASTY.replace("\x01", "\\x01").replace("\x1b", "\\x1b")  # written as escapes
    assert nasty.get("message") == "S301: " + expected
    assert nasty.text.startswith("a.pgx:14: S301 [warning] " + expected)
    case, failure = by_type["F001"][0]
    assert case.get("name") == "F001 file-unreadable"
    assert failure.text.startswith("b.pgx: F001 [error] cannot read")


def test_clean_run(make_result):
    root = parse(render("junit", make_result([], files=["a.pgx", "b.pgx"])))
    assert root.get("tests") == "2" and root.get("failures") == "0"
    assert [c.get("classname") for c in root.iter("testcase")] == ["a.pgx", "b.pgx"]


def test_deterministic(make_result, d):
    assert render("junit", sample(make_result, d)) == render("junit", sample(make_result, d))
