"""Every statement form of manual chapter 2.2.5, mostly with the manual's own examples."""

from __future__ import annotations

from val3check.parsing import ast as A

from .shapes import parse, stmts, sx


def test_empty_program_and_blank_lines():
    body = parse("begin\nend")
    assert body.statements == [] and (body.line, body.col) == (1, 1)
    assert (body.end_line, body.end_col) == (2, 4)
    body = parse("\n\nbegin\n\n   \n\t\nend\n\n  \n// after\n   ")
    assert body.statements == [] and body.line == 3


def test_manual_call_loop():
    # 2.2.5 call
    (loop,) = stmts("""
// Appel les programmes pick() et place() pour i,j entre 1 et 10
for i = 1 to 10
  for j = 1 to 10
    call pick(pPallet1[i,j])
    call place(pPallet2[i,j])
  endFor
endFor
""")
    assert isinstance(loop, A.For) and sx(loop.counter) == "i" and loop.step is None
    (inner,) = loop.body
    pick, place = inner.body
    assert isinstance(pick, A.Call) and sx(pick.target) == "pick"
    assert [sx(a) for a in pick.args] == ["(idx pPallet1 i j)"]
    assert (pick.line, pick.col) == (5, 5)
    assert sx(place.target) == "place"


def test_call_forms():
    a, b, c, d = stmts('call prog()\ncall lib:prog(1, "a")\ncall send1dMessage ("x")\nCALL p(x)')
    assert isinstance(a, A.Call) and a.args == [] and sx(a.target) == "prog"
    assert isinstance(b.target, A.LibraryName) and (b.target.alias, b.target.name) == ("lib", "prog")
    assert [sx(x) for x in b.args] == ["1", '"a"']
    assert sx(c.target) == "send1dMessage" and sx(d.target) == "p"


def test_return_and_break():
    r, b = stmts("return\nbreak")
    assert isinstance(r, A.Return) and (r.line, r.col) == (2, 1)
    assert isinstance(b, A.Break) and (b.line, b.col) == (3, 1)


def test_manual_if_day_example():
    # 2.2.5 if
    put, get, st = stmts("""
put ("Entrer un jour : ")
get (sDay)
if sDay=="Lundi"
  nDay=1
elseif sDay=="Mardi"
  nDay=2
elseif sDay=="Mercredi"
  nDay=3
elseif sDay=="Jeudi"
  nDay=4
elseif sDay=="Vendredi"
  nDay=5
else
  // Week-end !
  nDay=0
endif
""")
    assert isinstance(put, A.ExprStatement) and sx(put.call) == '(call put "Entrer un jour : ")'
    assert isinstance(st, A.If) and len(st.branches) == 5
    assert [sx(b.cond) for b in st.branches][:2] == ['(== sDay "Lundi")', '(== sDay "Mardi")']
    assert [(b.line, b.col) for b in st.branches] == [(4, 1), (6, 1), (8, 1), (10, 1), (12, 1)]
    assert [sx(s.value) for s in st.orelse] == ["0"]
    assert (st.else_line, st.else_col) == (14, 1)
    assert (st.end_line, st.end_col) == (17, 6)


def test_if_without_else():
    (st,) = stmts("if(x)\n  y = 1\nendIf")
    assert st.orelse is None and (st.else_line, st.else_col) == (0, 0)
    assert sx(st.branches[0].cond) == "x"


def test_manual_while_lamp_example():
    # 2.2.5 while
    a, w, b = stmts("""
diLampe = false
while (isSettled() == false)
//Inverse la valeur de diLampe : vrai faux
diLampe = !diLampe
//Attend ½ s
delay(0.5)
endWhile
diLampe = false
""")
    assert isinstance(w, A.While) and sx(w.cond) == "(== (call isSettled) false)"
    assert [type(s) for s in w.body] == [A.Assign, A.ExprStatement]
    assert sx(w.body[0].value) == "(! diLampe)"
    assert (w.line, w.end_line, w.end_col) == (3, 8, 9)


def test_manual_do_until():
    # 2.2.5 do ... until
    (d,) = stmts("""
// Ce programme s'exécute en boucle jusqu'à ce qu'on appuie sur la touche Enter
do
// Attend l'appui d'une touche
nKey = get()
// Teste le code de la touche Enter
until (nKey == 270)
""")
    assert isinstance(d, A.DoUntil) and sx(d.cond) == "(== nKey 270)"
    assert sx(d.body[0].value) == "(call get)"
    assert (d.line, d.col, d.until_line, d.until_col) == (3, 1, 7, 1)


def test_manual_for_negative_step():
    # 2.2.5 for
    (f,) = stmts("""
for nPos = 90 to -90 step -10
  jDest.j1 = nPos
  movej(jDest, flange, mNomSpeed)
  waitEndMove()
endFor
""")
    assert isinstance(f, A.For)
    assert (sx(f.counter), sx(f.start), sx(f.stop), sx(f.step)) == ("nPos", "90", "-90", "-10")
    assert sx(f.body[0].target) == "(. jDest j1)"
    assert sx(f.body[1].call) == "(call movej jDest flange mNomSpeed)"
    assert (f.end_line, f.end_col) == (6, 7)


def test_for_counter_element_or_field():
    a, b = stmts("for n[2] = 0 to 5\nendFor\nfor p.trsf.x = a to b step c\nendFor")
    assert sx(a.counter) == "(idx n 2)" and sx(b.counter) == "(. (. p trsf) x)" and sx(b.step) == "c"


def test_manual_switch_menu_example():
    # 2.2.5 switch, first example
    a, sw = stmts("""
nMenu = get()
switch nMenu
  case 271
    s = "Menu 1"
  break
  case 272
    s = "Menu 2"
  break
  case 273, 274, 275, 276, 277, 278
    s = "Menu 3 à 8"
  break
  default
    s = "cette touche n'est pas une touche de menu"
  break
endSwitch
""")
    assert isinstance(sw, A.Switch) and sx(sw.subject) == "nMenu"
    assert [[sx(v) for v in c.values] for c in sw.cases] == [["271"], ["272"], ["273", "274", "275", "276", "277", "278"]]
    assert all(c.has_break for c in sw.cases) and sw.default.has_break
    assert [type(s) for s in sw.cases[0].body] == [A.Assign, A.Break]
    assert (sw.cases[2].line, sw.cases[2].col) == (10, 3)
    assert (sw.default.line, sw.default.col) == (13, 3)
    assert (sw.end_line, sw.end_col) == (16, 10)


def test_manual_switch_day_example_unindented():
    # 2.2.5 switch, second example (the manual prints it partly without indentation)
    p, g, sw = stmts("""
put("Entrer un jour : ")
get(sJour)
switch sJour
  case "Lundi"
    nJour=1
  break
  case "Mardi"
    nJour=2
break
case "Mercredi"
nJour=3
break
case "Jeudi"
nJour=4
break
case "Vendredi"
nJour=5
break
default
// N'est pas un jour de la semaine !
nJour=0
break
endSwitch
""")
    assert [sx(c.values[0]) for c in sw.cases] == ['"Lundi"', '"Mardi"', '"Mercredi"', '"Jeudi"', '"Vendredi"']
    assert sx(sw.default.body[0].value) == "0"


def test_case_without_break_is_visible():
    (sw,) = stmts("switch n\ncase 1\n  x = 1\ncase 2\n  if a\n    break\n  endIf\nendSwitch")
    assert sw.default is None
    assert [c.has_break for c in sw.cases] == [False, False]  # a nested break does not count
    assert isinstance(sw.cases[1].body[0], A.If) and isinstance(sw.cases[1].body[0].branches[0].body[0], A.Break)


def test_empty_switch_and_default_only():
    a, b = stmts("switch n\nendSwitch\nswitch n\ndefault\nendSwitch")
    assert a.cases == [] and a.default is None
    assert b.cases == [] and b.default is not None and not b.default.has_break


def test_break_outside_switch_parses():
    (w,) = stmts("while true\n  break\nendWhile")
    assert isinstance(w.body[0], A.Break)


def test_assignment_targets():
    got = [sx(s.target) for s in stmts("""
x = 1
a[i] = 1
a[i,j] = 1
a[i, j, k] = 1
c["key"] = 1
p.trsf.x = 1
a[1].trsf.x = 1
lib:nX = 1
lib:nArr[2].x = 1
sProductName["D 243 064 40 A"] = "VAL 3 CdRom"
""")]
    assert got == ["x", "(idx a i)", "(idx a i j)", "(idx a i j k)", '(idx c "key")', "(. (. p trsf) x)",
                   "(. (. (idx a 1) trsf) x)", "lib:nX", "(. (idx lib:nArr 2) x)", '(idx sProductName "D 243 064 40 A")']


def test_manual_structured_values():
    # 2.4.2
    a, b = stmts("pPosition = {{100, -50, 200, 0, 0, 0}, {sfree, efree, wfree}}\npPosition.trsf = {100, -50, 200,,}")
    assert sx(a.value) == "{{100, -50, 200, 0, 0, 0}, {sfree, efree, wfree}}"
    assert sx(b.target) == "(. pPosition trsf)"
    assert [sx(f) for f in b.value.fields] == ["100", "-50", "200", "_", "_"]


def test_instruction_calls_as_statements():
    got = [sx(s.call) for s in stmts('movej(j, flange, m)\nlib:libLoad(s)\n$system(1)\nputln("x")\nwaitEndMove()')]
    assert got == ["(call movej j flange m)", "(call lib:libLoad s)", "(call $system 1)", '(call putln "x")', "(call waitEndMove)"]
    assert all(isinstance(s, A.ExprStatement) for s in stmts("f()\ng(1)"))


def test_nested_blocks():
    (st,) = stmts("""
if a
  while b
    do
      for i = 0 to 3
        switch i
          case 0
            x = 1
          break
        endSwitch
      endFor
    until c
  endWhile
endIf
""")
    sw = st.branches[0].body[0].body[0].body[0].body[0]
    assert isinstance(sw, A.Switch) and sx(sw.cases[0].body[0].value) == "1"


def test_statement_lines_are_file_lines():
    body = parse("begin\n  x = 1\n\n  // c\n  if a\n    y = 2\n  endIf\nend", first_line=40, first_col=13)
    assign, st = body.statements
    assert (assign.line, assign.col) == (41, 3)
    assert (st.line, st.col, st.branches[0].body[0].line, st.end_line) == (44, 3, 45, 46)
    assert (body.line, body.col, body.end_line, body.end_col) == (40, 13, 47, 4)


def test_walk_visits_every_node():
    body = parse("begin\n  if a\n    x = f(b[1], {1,,2})\n  endIf\nend")
    kinds = [type(n).__name__ for n in A.walk(body)]
    assert kinds == ["ProgramBody", "If", "Branch", "Name", "Assign", "Name", "CallExpr", "Name", "Index",
                     "Name", "Number", "Struct", "Number", "Number"]


def test_manual_task_creation():
    # 5.10 taskCreate / taskCreateSync: the program is written as a call, without `call`
    a, w, b, c = stmts("""
taskCreate "t1", 10, read(sMessage)
wait(taskStatus("t1") == -1)
taskCreateSync "supervisor", 0.02, bSupervisor, supervisor()
TASKCREATE sName + "x", nPrio, lib:prog(a, b[1])
""")
    assert isinstance(a, A.TaskCreate) and (sx(a.task), sx(a.priority), sx(a.target)) == ('"t1"', "10", "read")
    assert [sx(x) for x in a.args] == ["sMessage"] and (a.line, a.col) == (2, 1)
    assert isinstance(b, A.TaskCreateSync)
    assert (sx(b.task), sx(b.period), sx(b.overrun), sx(b.target), b.args) == ('"supervisor"', "0.02", "bSupervisor", "supervisor", [])
    assert isinstance(c.target, A.LibraryName) and sx(c.task) == '(+ sName "x")'


def test_s8_print_statement():
    # `? expr` (s8): one or several values; `?` elsewhere is a syntax error, not an invalid character
    a, b = stmts('? nX * 2\n?"n=", toString("", n)')
    assert isinstance(a, A.Print) and [sx(v) for v in a.values] == ["(* nX 2)"] and (a.line, a.col) == (2, 1)
    assert [sx(v) for v in b.values] == ['"n="', "(call toString \"\" n)"]
    from .shapes import errors

    assert [e[:3] for e in errors("begin\n  x = ?\n  ?\nend")] == [("F101", 2, 7), ("F101", 3, 4)]
