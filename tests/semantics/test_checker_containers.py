"""T codes about containers: indices, keys, whole variables (manual 2.3.4, 2.5.3-2.5.6, 2.6.3)."""

from __future__ import annotations

from checkhelp import codes, collect, findings, write_app

G = ["num nOne", "num nArr[4]", "num nGrid[3,4]", "num nCube[2,3,4]", 'num nColl[""]', "string sKey", "num nX",
     'string sColl[""]', "string s3d[10,10,10]", "string s2d[20,5]", "string sArr[30]", "string sMsg"]


def test_indices_and_keys_that_compile(tmp_path):
    code = """begin
  nOne = 1
  nOne[0] = 2
  nArr[3] = nGrid[2, 3] + nCube[1, 2, 3]
  nColl["a"] = nColl[sKey]
  nArr[1.4] = nArr[nOne]
end"""
    assert codes(tmp_path, code, globals_=G) == []


def test_wrong_index_counts(tmp_path):
    code = "begin\n  nArr[1, 2] = 0\n  nGrid[1] = 0\n  nColl[\"a\", \"b\"] = 0\n  nOne[0, 0] = 0\nend"
    assert findings(tmp_path, code, globals_=G) == [("T009", 2, 11), ("T009", 3, 3), ("T009", 4, 14), ("T009", 5, 11)]


def test_wrong_index_types(tmp_path):
    code = "begin\n  nColl[1] = 0\n  nArr[\"1\"] = 0\n  nGrid[1, sKey] = 0\nend"
    assert findings(tmp_path, code, globals_=G) == [("T010", 2, 9), ("T010", 3, 8), ("T010", 4, 12)]


def test_containers_used_as_one_value(tmp_path):
    code = "begin\n  nArr = 0\n  nX = nGrid\n  putln(sColl)\n  if nCube == 1\n  endIf\nend"
    # nArr: a 1-D array of several values, a warning (T025); the others are errors (T011)
    assert findings(tmp_path, code, globals_=G) == [("T025", 2, 3), ("T011", 3, 8), ("T011", 4, 9), ("T011", 5, 6)]


def test_whole_variable_instructions(tmp_path):
    ok = """begin
  nX = size(sColl) + size(s3d, 3) + size(sArr[3]) + size(nOne) + size(sArr, 1)
  sKey = first(sColl)
  sKey = next(sColl[sKey])
  sKey = last(sColl)
  sKey = prev(sColl[sKey])
  if isDefined(sColl[sKey])
    insert(sColl[sKey])
    delete(sColl[sKey])
  endIf
  insert(sArr[size(sArr)])
  delete(sArr[0])
  append(sArr)
  resize(s2d, 2, 5)
  nX = getData("lib:sArr", sArr[2])
  nX = getData("sMsg", sMsg)
  sMsg = insert(sMsg, "x", 2)
  sMsg = delete(sMsg, 1, 0)
end"""
    assert codes(tmp_path, ok, globals_=G) == []


def test_manual_compile_errors_of_2_5_4_and_2_5_5(tmp_path):
    code = """begin
  nX = size(sColl[sKey])
  nX = size(s3d[1, 2, 3], 3)
  sKey = first(sArr)
  sKey = next(sColl)
  append(sArr[2])
  insert(sArr)
end"""
    assert findings(tmp_path, code, globals_=G) == [("T020", 2, 13), ("T020", 3, 13), ("T008", 4, 16), ("T011", 5, 15),
                                                    ("T020", 6, 10), ("T011", 7, 10)]


def test_insert_delete_append_not_on_2d_arrays_nor_local_arrays(tmp_path):
    code = "begin\n  append(nGrid)\n  insert(nGrid[1, 2])\n  delete(nCube[0, 0, 0])\n  resize(nGrid, 1, 2)\nend"
    assert findings(tmp_path, code, globals_=G) == [("T021", 2, 10), ("T021", 3, 10), ("T021", 4, 10)]
    progs = {"fill": {"locals": ["num l_buf[4]", 'num l_coll[""]', "num l_one"],
                      "code": "begin\n  append(l_buf)\n  resize(l_buf, 1, 5)\n  insert(l_buf[1])\n  insert(l_coll[\"a\"])\n"
                              "  delete(l_coll[\"a\"])\n  append(l_one)\nend"}}
    folder = write_app(tmp_path / "b", "begin\n  call fill()\nend", programs=progs)
    assert [f[0] for f in collect(folder)] == ["T021", "T021", "T021", "T021"]


def test_manual_2_6_3_parameters(tmp_path):
    progs = {"send1dMessage": {"params": ["string& x_s[]"]}, "send2dMessage": {"params": ["string& x_s[,]"]},
             "send3dMessage": {"params": ["string& x_s[,,]"]}, "sendCollMessage": {"params": ['string& x_s[""]']},
             "sendMessage": {"params": ["string& x_s"]}, "sendValue": {"params": ["string x_s"]}}
    ok = """begin
  call send2dMessage(s2d)
  call send3dMessage(s3d)
  call sendCollMessage(sColl)
  call send1dMessage(sArr)
  call send1dMessage(sArr[23])
  call send1dMessage(sMsg)
  call sendMessage(sMsg)
  call sendMessage(sArr[23])
  call sendMessage(s2d[12, 3])
  call sendMessage(s3d[5, 7, 9])
  call sendMessage(sColl[sKey])
  call sendValue("Attente du signal" + sMsg)
  call sendValue(s3d[5, 7, 9])
end"""
    assert codes(tmp_path, ok, globals_=G, programs=progs) == []
    bad = """begin
  call sendMessage("Attente du signal StartCycle")
  call sendMessage("Attente du signal" + sMsg)
  call send1dMessage("Attente du signal StartCycle")
  call send1dMessage(sColl)
  call send1dMessage(s2d[12, 3])
  call sendCollMessage(sMsg)
  call send2dMessage(s2d[12, 3])
  call send3dMessage(s3d[5, 7, 9])
  call sendCollMessage(sColl[sKey])
  call send2dMessage(s3d)
  call sendValue(sArr)
  call sendMessage(sArr)
end"""
    found = codes(tmp_path / "b", bad, globals_=G, programs=progs)
    assert found == ["T007", "T007", "T007", "T008", "T008", "T008", "T020", "T020", "T020", "T008", "T025", "T025"]


def test_array_parameters_inside_the_program(tmp_path):
    progs = {"use": {"params": ["num& x_a[]", "num& x_g[,]", 'num& x_c[""]'],
                     "code": "begin\n  x_a = 1\n  x_a[0] = size(x_a)\n  x_g[1, 2] = size(x_g, 2)\n  x_c[\"k\"] = 0\n"
                             "  x_g = 1\n  x_c[0] = 1\nend"}}
    folder = write_app(tmp_path, "begin\n  call use(nArr, nGrid, nColl)\nend", globals_=G, programs=progs)
    # x_a bare: a 1-D array parameter may hold one value (size unknown): not reported
    assert [f[0] for f in collect(folder)] == ["T011", "T010"]


def test_a_field_of_a_bare_multi_value_array_is_written_as_it_is_read(tmp_path):
    # the same warning (T025) whether the field is read or written; never "must be a variable" (T013)
    code = "begin\n  pTarget.trsf.x = 5\n  nX = pTarget.trsf.x\n  call setNum(pTarget.trsf.y)\nend"
    progs = {"setNum": {"params": ["num& x_n"], "code": "begin\n  x_n = 1\nend"}}
    found = findings(tmp_path, code, globals_=["point pTarget[3]", "num nX"], programs=progs)
    assert found == [("T025", 2, 3), ("T025", 3, 8), ("T025", 4, 15)]
    # a collection or a 2-D array stays an error, once
    code = "begin\n  pColl.trsf.x = 5\n  pGrid.trsf.x = 5\nend"
    found = findings(tmp_path / "b", code, globals_=['point pColl[""]', "point pGrid[2,2]"])
    assert found == [("T011", 2, 3), ("T011", 3, 3)]
