"""Values, expressions and statements (manual chapter 2, 3) run through the simulator."""

from __future__ import annotations

from support import code_position

from .simsupport import errors, out, sim


def test_arithmetic_and_for(tmp_path):
    r = sim(tmp_path, """begin
  nX = 0
  for l_i = 0 to 9
    nX = nX + l_i
  endFor
  putln(nX)
  for l_i = 90 to -90 step -10
    nY = nY + 1
  endFor
  putln(nY)
  putln(7 % 3)
  putln(-7 % 3)
end
""", globals_=["num nX", "num nY"], locals_=["num l_i"])
    assert r.end_reason == "ended"
    assert out(r) == ["45", "19", "1", "-1"]


def test_if_elseif_else_with_scripted_text(tmp_path):
    # 2.2.5 `if` example: a day name typed on the pendant
    code = """begin
  put("Entrer un jour : ")
  get(sDay)
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
  putln(nDay)
end
"""
    for day, n in (("Mercredi", "3"), ("Samedi", "0"), ("Lundi", "1")):
        r = sim(tmp_path / day, code, globals_=["string sDay", "num nDay"],
                scenario=f'[[keys]]\nat = 1.5\ntext = "{day}"\n')
        assert out(r) == ["Entrer un jour : " + n]
        assert r.end_reason == "ended"
        assert r.sim_time_us >= 1_500_000


def test_switch_menu_keys(tmp_path):
    code = """begin
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
  putln(s)
end
"""
    for key, text in ((271, "Menu 1"), (275, "Menu 3 à 8"), (113, "cette touche n'est pas une touche de menu")):
        r = sim(tmp_path / str(key), code, globals_=["num nMenu", "string s"], scenario=f"[[keys]]\nat = 0.1\nkey = {key}\n")
        assert out(r) == [text]


def test_switch_on_strings(tmp_path):
    code = """begin
  get(sJour)
  switch sJour
    case "Lundi"
      nJour=1
    break
    case "Mardi"
      nJour=2
    break
    default
      nJour=0
    break
  endSwitch
  putln(nJour)
end
"""
    r = sim(tmp_path, code, globals_=["string sJour", "num nJour"], scenario='[[keys]]\ntext = "Mardi"\n')
    assert out(r) == ["2"]


def test_do_until_enter_key(tmp_path):
    # 2.2.5 do ... until: loop until Return (270)
    r = sim(tmp_path, """begin
  do
    nKey = get()
    nCount = nCount + 1
  until (nKey == 270)
  putln(nCount)
end
""", globals_=["num nKey", "num nCount"], scenario="[[keys]]\nat=0.1\nkey=113\n[[keys]]\nat=0.2\nkey=119\n[[keys]]\nat=0.3\nkey=270\n")
    assert out(r) == ["3"]


def test_string_limit_and_operators(tmp_path):
    r = sim(tmp_path, """begin
  s = "abc" + "def"
  putln(s)
  b = (1 < 2) and !(2 < 1) xor false
  if b
    putln("yes")
  endIf
  nA = 10 / 4
  putln(nA)
end
""", globals_=["string s", "bool b", "num nA"])
    assert out(r) == ["abcdef", "yes", "2.5"]


def test_division_by_zero_is_error_10(tmp_path):
    r = sim(tmp_path, """begin
  nA = 0
  nB = 1 / nA
  putln("never")
end
""", globals_=["num nA", "num nB"])
    assert errors(r) == [10]
    d = [d for d in r.diagnostics if d.code == "R001"][0]
    assert d.task == "Example~" and d.program == "start"
    assert d.path.endswith("start.pgx") and (d.line, d.col) == code_position(3, 3)
    assert out(r) == []


def test_modulo_by_zero_and_ln(tmp_path):
    r = sim(tmp_path, "begin\n  nB = 5 % nA\nend\n", globals_=["num nA", "num nB"])
    assert errors(r) == [10]
    r = sim(tmp_path / "ln", "begin\n  nB = ln(-1)\nend\n", globals_=["num nB"])
    assert errors(r) == [11]


def test_index_errors(tmp_path):
    r = sim(tmp_path, "begin\n  nA[3] = 1\nend\n", globals_=["num nA[3]"])
    assert errors(r) == [20]
    r = sim(tmp_path / "neg", "begin\n  nI = -1\n  nA[nI] = 1\nend\n", globals_=["num nA[3]", "num nI"])
    assert errors(r) == [21]
    # 2.5.3: indices are rounded to the nearest integer
    r = sim(tmp_path / "round", "begin\n  nA[1.6] = 7\n  putln(nA[2])\n  n2[0.4, 1.51] = 3\n  putln(n2[0,2])\nend\n",
            globals_=["num nA[3]", "num n2[2,3]"])
    assert out(r) == ["7", "3"]


def test_collections_alphabetical(tmp_path):
    # 2.5.6: first/next walk the keys in alphabetical order
    r = sim(tmp_path, """begin
  insert(nColl["pear"])
  insert(nColl["apple"])
  insert(nColl["fig"])
  nColl["fig"] = 3
  if insert(nColl["fig"]) == false
    putln("fig exists")
  endIf
  sKey = first(nColl)
  while sKey != ""
    putln(sKey)
    sKey = next(nColl[sKey])
  endWhile
  putln(size(nColl))
  delete(nColl["apple"])
  putln(last(nColl))
  putln(prev(nColl["pear"]))
  if isDefined(nColl["apple"]) == false
    putln("gone")
  endIf
end
""", globals_=['num nColl[""]', "string sKey"])
    assert out(r) == ["fig exists", "apple", "fig", "pear", "3", "pear", "fig", "gone"]


def test_arrays_size_resize_append_insert_delete(tmp_path):
    r = sim(tmp_path, """begin
  putln(size(nA))
  append(nA)
  nA[size(nA)-1] = 9
  insert(nA[0])
  nA[0] = 4
  putln(size(nA))
  putln(nA[0] + nA[4])
  delete(nA[0])
  putln(size(nA))
  putln(size(nA[1]))
  resize(n2, 2, 5)
  putln(size(n2, 2))
  putln(size(n2, 1))
  putln(size(n2, 3))
  n2[1, 4] = 2
  putln(n2[1,4])
end
""", globals_=["num nA[3]", "num n2[2,3]"])
    assert out(r) == ["3", "5", "13", "4", "3", "5", "2", "0", "2"]


def test_9999_limit(tmp_path):
    r = sim(tmp_path, """begin
  resize(nA, 1, 9999)
  append(nA)
end
""", globals_=["num nA[3]"])
    assert errors(r) == [40]


def test_structured_values_and_deep_copy(tmp_path):
    r = sim(tmp_path, """begin
  pPosition = {{100, -50, 200, 0, 0, 0}, {sfree, efree, wfree}}
  pPosition.trsf = {100, -50, 200,,}
  pOther = pPosition
  pOther.trsf.x = 5
  putln(pPosition.trsf.x)
  putln(pOther.trsf.x)
  mD.vel = 30
  putln(mD.tvel)
  if pPosition.config.shoulder == sfree
    putln("free")
  endIf
end
""", globals_=["point pPosition", "point pOther", "mdesc mD"])
    assert out(r) == ["100", "5", "9999", "free"]


def test_arm_instruction_stops_the_task(tmp_path):
    r = sim(tmp_path, """begin
  putln("before")
  movej(jHome, flange, mD)
  putln("after")
end
""", globals_=["joint jHome", "mdesc mD"])
    assert out(r) == ["before"]
    d = [d for d in r.diagnostics if d.code == "R002"]
    assert d and "movej" in d[0].message and "arm" in d[0].message
    assert (d[0].line, d[0].col) == code_position(3, 3)


def test_s8_print_statement_writes_a_user_page_line(tmp_path):
    # `? expr` (s8): the emulator prints the value; the simulator writes it as putln does
    r = sim(tmp_path, 'begin\n  nX = 2\n  ? nX * 3\n  ? "done " + toString("", nX)\n  ? nX > 1\n  ? "n=", nX\nend',
            globals_=["num nX"])
    assert errors(r) == []
    assert out(r) == ["6", "done 2", "true", "n=2"]
