"""Every example of the manual (chapters 2-8, 12.1) that states a result or an output, run
through the simulator. Each test is named after the section of its example; the snippet is
the manual's, wrapped in start() with the globals/locals it needs and, where it reads the
keyboard, a scenario with the key presses. Where the manual's text is evidently mistyped (OCR,
names with spaces, `println` for `putln`...), the test follows the evident intent and says so.
Examples that need the arm (motion, chapters 9-11) are not here: they stop with R002.
"""

from __future__ import annotations

import struct

import pytest

from .simsupport import (
    add_libraries,
    build,
    codes,
    errors,
    gv,
    make_library,
    out,
    run_folder,
    sim,
)


def keys(*items) -> str:
    """A scenario of key presses: (time, code) or (time, "typed text")."""
    parts = []
    for at, k in items:
        if isinstance(k, str):
            parts.append(f'[[keys]]\nat = {at}\ntext = "{k}"\n')
        else:
            parts.append(f"[[keys]]\nat = {at}\nkey = {k}\n")
    return "\n".join(parts)


# ---- chapter 2: language elements ------------------------------------------------------------


DAY_IF = """begin
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
end
"""


@pytest.mark.parametrize("day,n", [("Lundi", 1), ("Mardi", 2), ("Mercredi", 3), ("Jeudi", 4), ("Vendredi", 5),
                                   ("Samedi", 0), ("Dimanche", 0)])
def test_2_2_5_if_example(tmp_path, day, n):
    # "Ce programme convertit un jour écrit dans une string (sJour) en un num (nJour)"
    r = sim(tmp_path, DAY_IF, globals_=["string sDay", "num nDay"], scenario=keys((0.5, day)))
    assert r.end_reason == "ended"
    assert gv(r, "sDay") == day
    assert gv(r, "nDay") == n
    assert out(r) == ["Entrer un jour : "]


def test_2_2_5_do_until_example(tmp_path):
    # "Ce programme s'exécute en boucle jusqu'à ce qu'on appuie sur la touche Enter"
    r = sim(tmp_path, """begin
  do
    // Attend l'appui d'une touche
    nKey = get()
    nCount = nCount + 1
    // Teste le code de la touche Enter
  until (nKey == 270)
end
""", globals_=["num nKey", "num nCount"], scenario=keys((0.1, 113), (0.2, 271), (0.3, 270), (0.4, 119)))
    assert r.end_reason == "ended"
    assert gv(r, "nKey") == 270
    assert gv(r, "nCount") == 3  # q, F1, then Enter ends the loop; 'w' is never read
    assert 0.3e6 <= r.sim_time_us < 0.4e6


MENU = """begin
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
end
"""


@pytest.mark.parametrize("key,text", [(271, "Menu 1"), (272, "Menu 2"), (273, "Menu 3 à 8"), (278, "Menu 3 à 8"),
                                      (270, "cette touche n'est pas une touche de menu")])
def test_2_2_5_switch_menu_example(tmp_path, key, text):
    r = sim(tmp_path, MENU, globals_=["num nMenu", "string s"], scenario=keys((0.1, key)))
    assert gv(r, "nMenu") == key
    assert gv(r, "s") == text


DAY_SWITCH = """begin
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
end
"""


@pytest.mark.parametrize("day,n", [("Lundi", 1), ("Mardi", 2), ("Mercredi", 3), ("Jeudi", 4), ("Vendredi", 5),
                                   ("Samedi", 0)])
def test_2_2_5_switch_day_example(tmp_path, day, n):
    r = sim(tmp_path, DAY_SWITCH, globals_=["string sJour", "num nJour"], scenario=keys((0.2, day)))
    assert gv(r, "nJour") == n


def test_2_4_1_simple_data_example(tmp_path):
    # 2.4.1: default values false / 0 / ""; then the example's assignments
    r = sim(tmp_path, """begin
  bDefault = bBool
  nDefault = nPi
  sDefault = sString
  bBool = true
  nPi = 3.141592653
  sString = "ceci est une chaîne"
end
""", globals_=["bool bBool", "num nPi", "string sString", "bool bDefault", "num nDefault", "string sDefault"])
    assert (gv(r, "bDefault"), gv(r, "nDefault"), gv(r, "sDefault")) == (False, 0, "")
    assert (gv(r, "bBool"), gv(r, "nPi"), gv(r, "sString")) == (True, 3.141592653, "ceci est une chaîne")


def test_2_4_2_structured_data_example(tmp_path):
    # 2.4.2: "Les valeurs des champs vides sont remplacées par 0"
    r = sim(tmp_path, """begin
  pPosition = {{100, -50, 200, 0, 0, 0}, {sfree, efree, wfree}}
  pOther = {{1, 2, 3, 4, 5, 6}, {righty, enegative, wpositive}}
  pOther.trsf = {100, -50, 200,,}
end
""", globals_=["point pPosition", "point pOther"])
    p = gv(r, "pPosition")
    assert p["trsf"] == {"x": 100, "y": -50, "z": 200, "rx": 0, "ry": 0, "rz": 0}
    assert p["config"] == {"shoulder": "sfree", "elbow": "efree", "wrist": "wfree"}
    q = gv(r, "pOther")
    assert q["trsf"] == {"x": 100, "y": -50, "z": 200, "rx": 0, "ry": 0, "rz": 0}
    assert q["config"] == {"shoulder": "righty", "elbow": "enegative", "wrist": "wpositive"}


def test_2_5_3_access_example(tmp_path):
    # 2.5.3: element, array and collection containers; indices rounded to the nearest integer;
    # a 1-D array of one value is an element
    r = sim(tmp_path, """begin
  nPi = 3.141592653
  sMonth[0] = "Janvier"
  sProductName["D 243 064 40 A"] = "VAL 3 CdRom"
  n2dArray[5, 7] = 57
  nRounded = n2dArray[5.01, 6.99]
  nSingle = 4
  nSingleIdx = nSingle[0]
end
""", globals_=["num nPi", "string sMonth[12]", 'string sProductName[""]', "num n2dArray[6,8]", "num nRounded",
               "num nSingle", "num nSingleIdx"])
    assert r.end_reason == "ended"
    assert gv(r, "nPi") == 3.141592653
    assert gv(r, "sMonth")[0] == "Janvier"
    assert gv(r, "sProductName") == {"D 243 064 40 A": "VAL 3 CdRom"}
    assert gv(r, "nRounded") == 57
    assert gv(r, "nSingleIdx") == 4


def test_2_5_4_size_example(tmp_path):
    # size(): 1 for an element, the number of values of a 1-D array or a collection, and
    # size(s1dArray[nIndex]) = size(s1dArray) - nIndex
    r = sim(tmp_path, """begin
  sCollection["a"] = "1"
  sCollection["b"] = "2"
  sCollection["c"] = "3"
  nNbElements=size(sCollection)
  nArr = size(s1dArray)
  nPart = size(s1dArray[3])
  nElem = size(nNbElements)
  nArr1 = size(s1dArray, 1)
end
""", globals_=['string sCollection[""]', "num nNbElements", "string s1dArray[10]", "num nArr", "num nPart",
               "num nElem", "num nArr1"])
    assert gv(r, "nNbElements") == 3
    assert gv(r, "nArr") == 10 and gv(r, "nArr1") == 10
    assert gv(r, "nPart") == 7
    assert gv(r, "nElem") == 1


ISDEFINED_COLL = """begin
  // Demander un nouveau nom de référence
  put("Nouvelle référence •")
  get(sReference)
  if isDefined(sReferenceColl[sReference])==true
    putln("Erreur : référence déjà définie")
  else
    // Ajouter nouvel article à la collection
    insert(sReferenceColl[sReference])
  endif
end
"""


def test_2_5_4_isdefined_collection_example(tmp_path):
    r = sim(tmp_path / "new", ISDEFINED_COLL, globals_=['string sReferenceColl[""]', "string sReference"],
            scenario=keys((0.1, "D243")))
    assert gv(r, "sReferenceColl") == {"D243": ""}
    assert out(r) == ["Nouvelle référence •"]
    folder = build(tmp_path / "old", ISDEFINED_COLL, globals_=['string sReferenceColl[""]', "string sReference"])
    text = (folder / "Example.dtx").read_text(encoding="utf-8")
    text = text.replace('type="string" />', 'type="string"><Value key="D243" value="vis" /></Data>', 1)
    (folder / "Example.dtx").write_text(text, encoding="utf-8")
    r = run_folder(folder, scenario=keys((0.1, "D243")))
    assert gv(r, "sReferenceColl") == {"D243": "vis"}
    assert out(r) == ["Nouvelle référence •Erreur : référence déjà définie"]


LIB_VERSION_ISDEFINED = """begin
  // Charger librairie de pièces
  nLoadCode = part:libLoad(sPartPath)
  // part:sVersion n'a pas été défini dans la première version de la librairie
  // Tester si cette librairie le définit
  if (nLoadCode==0) or (nLoadCode==11)
    if (isDefined(part:sVersion)==false)
      // version initiale
      sLibVersion = "v1.0"
    else
      sLibVersion = part:sVersion
    endif
  endif
end
"""


def _part_libraries(tmp_path):
    make_library(tmp_path, "PartV1", globals_=["num nLength"])
    make_library(tmp_path, "PartV2", globals_=["num nLength", "string sVersion"], values={"sVersion": "v2.0"})


@pytest.mark.parametrize("path,code,version", [("PartV1", 11, "v1.0"), ("PartV2", 0, "v2.0")])
def test_2_5_4_isdefined_library_example(tmp_path, path, code, version):
    _part_libraries(tmp_path)
    folder = build(tmp_path, LIB_VERSION_ISDEFINED, globals_=["num nLoadCode", "string sPartPath",
                                                              "string sLibVersion"], values={"sPartPath": path})
    add_libraries(folder, {"part": "Disk://PartV2"})
    r = run_folder(folder)
    assert r.end_reason == "ended", r.diagnostics
    assert gv(r, "nLoadCode") == code
    assert gv(r, "sLibVersion") == version


# 2.5.4 insert: the manual's variable names hold spaces and an apostrophe ("sNom de l'article",
# "sListe d'articles"), which no VAL 3 name can: sArticle / sArticleList here.
INSERT_LIST = """begin
  // Demander un nouveau nom d'article
  put("Nouvel article •")
  get(sArticle)
  putln("")
  // Demander la position dans la liste
  put("Position ? ")
  get(nIndex)
  if (nIndex<0) or (nIndex>size(sArticleList))
    putln("Erreur: position incorrecte")
  else
    // Ajouter le nouvel article à la liste
    insert(sArticleList[nIndex])
    sArticleList[nIndex] = sArticle
  endif
end
"""


@pytest.mark.parametrize("pos,result,err", [
    ("1", ["vis", "clou", "boulon", "écrou"], False),
    ("0", ["clou", "vis", "boulon", "écrou"], False),
    ("3", ["vis", "boulon", "écrou", "clou"], False),  # at size(): same as append
    ("4", ["vis", "boulon", "écrou"], True),
    ("-1", ["vis", "boulon", "écrou"], True),
])
def test_2_5_4_insert_example(tmp_path, pos, result, err):
    folder = build(tmp_path, INSERT_LIST, globals_=["string sArticle", "num nIndex", "string sArticleList[3]"])
    text = (folder / "Example.dtx").read_text(encoding="utf-8")
    text = text.replace('name="sArticleList" access="public" xsi:type="array" type="string" size="3" />',
                        'name="sArticleList" access="public" xsi:type="array" type="string" size="3">'
                        '<Value key="0" value="vis" /><Value key="1" value="boulon" /><Value key="2" value="écrou" />'
                        '</Data>')
    (folder / "Example.dtx").write_text(text, encoding="utf-8")
    r = run_folder(folder, scenario=keys((0.1, "clou"), (0.2, pos)))
    assert r.end_reason == "ended", r.diagnostics
    assert gv(r, "sArticleList") == result
    assert out(r)[-1] == ("Position ? Erreur: position incorrecte" if err else "Position ? ")


INSERT_COLL = """begin
  // Demander un nouveau nom d'article
  put("Nouvel article •")
  get(sArticle)
  if isDefined(sArticleColl[sArticle])==true
    putln("Erreur: référence déjà définie")
  else
    // Ajouter nouvel article à la collection
    insert(sArticleColl[sArticle])
  endif
  // 2.5.4: insert() of a key already used has no effect and returns false
  bAgain = insert(sArticleColl[sArticle])
end
"""


def test_2_5_4_insert_collection_example(tmp_path):
    r = sim(tmp_path, INSERT_COLL, globals_=["string sArticle", 'string sArticleColl[""]', "bool bAgain"],
            scenario=keys((0.1, "vis")))
    assert gv(r, "sArticleColl") == {"vis": ""}
    assert gv(r, "bAgain") is False
    assert out(r) == ["Nouvel article •"]


DELETE_COLL = """begin
  // Demander l'article à supprimer
  put("Article à supprimer")
  get(sArticle)
  if isDefined(sArticleColl[sArticle]) ==true
    // supprime l'article dans la collection
    delete(sArticleColl[sArticle])
  else
    putln("Erreur : article non défini")
  endif
end
"""


@pytest.mark.parametrize("typed,left,message", [("vis", {"clou": "2"}, None),
                                                ("écrou", {"clou": "2", "vis": "1"}, "Erreur : article non défini")])
def test_2_5_4_delete_example(tmp_path, typed, left, message):
    r = sim(tmp_path, """begin
  sArticleColl["vis"] = "1"
  sArticleColl["clou"] = "2"
""" + DELETE_COLL.split("begin\n", 1)[1], globals_=["string sArticle", 'string sArticleColl[""]'],
            scenario=keys((0.1, typed)))
    assert gv(r, "sArticleColl") == left
    if message:
        assert out(r) == ["Article à supprimer" + message]


@pytest.mark.parametrize("line,code", [('delete(sColl["nope"])', 20), ("delete(sArr[5])", 20), ("delete(sArr[-1])", 21),
                                       ("delete(sArr[1])\n  delete(sArr[0])", 70)])
def test_2_5_4_delete_errors(tmp_path, line, code):
    # "Une erreur de temps d'exécution est générée si l'index ou la clé spécifiés dépassent les
    # limites", "... si l'on essaie de supprimer le dernier élément d'un tableau"
    r = sim(tmp_path, f"""begin
  {line}
end
""", globals_=["string sArr[2]", 'string sColl[""]'])
    assert errors(r) == [code]


def _get_data_library(tmp_path):
    lib = make_library(tmp_path, "Partie", globals_=["point pApproche[2]", "point pTrajectoire[3]", "num nCount",
                                                     "string sName"])
    text = (lib / "Partie.dtx").read_text(encoding="utf-8")
    for name, n, base in (("pApproche", 2, 10), ("pTrajectoire", 3, 20)):
        vals = "".join(f'<Value key="{i}" x="{base + i}" y="0" z="0" rx="0" ry="0" rz="0" shoulder="ssame" '
                       f'elbow="esame" wrist="wsame" fatherId="" />' for i in range(n))
        text = text.replace(f'name="{name}" access="public" xsi:type="array" type="point" size="{n}" />',
                            f'name="{name}" access="public" xsi:type="array" type="point" size="{n}">{vals}</Data>')
    (lib / "Partie.dtx").write_text(text, encoding="utf-8")


def test_2_5_4_getdata_example(tmp_path):
    # "Ce programme fusionne 2 tableaux de points pApproche[] et pTrajectoire[] provenant d'une
    # librairie en un seul tableau local pChemin[]": 2 + 3 points
    _get_data_library(tmp_path)
    folder = build(tmp_path, """begin
  nLoad = Partie:libLoad("Partie")
  // Copier les points d'approche dans le chemin
  i = getData("Partie:pApproche", pChemin)
  if(i > 0)
    nPoints = i
    // Joindre les points de trajectoire dans le chemin
    i = getData("Partie:pTrajectoire", pChemin[nPoints])
    if(i >0)
      nPoints=nPoints+i
    endif
  endif
  for i = 0 to 5
    nX[i] = pChemin[i].trsf.x
  endFor
end
""", globals_=["num nLoad", "num nPoints", "num nX[6]"], locals_=["num i", "point pChemin[6]"])
    add_libraries(folder, {"Partie": "Disk://Partie"})
    r = run_folder(folder)
    assert r.end_reason == "ended", r.diagnostics
    assert gv(r, "nLoad") == 0
    assert gv(r, "nPoints") == 5
    assert gv(r, "nX") == [10, 11, 20, 21, 22, 0]


def test_2_5_4_getdata_return_codes(tmp_path):
    # the table of 2.5.4: n > 0 copied, -1 no such data, -2 no such library identifier,
    # -3 index out of range, -4 type mismatch
    _get_data_library(tmp_path)
    folder = build(tmp_path, """begin
  nLoad = Partie:libLoad("Partie")
  nR[0] = getData("Partie:pApproche", pOne)
  nR[1] = getData("Partie:pNothing", pOne)
  nR[2] = getData("Nolib:pApproche", pOne)
  nR[3] = getData("Partie:pTrajectoire[7]", pOne)
  nR[4] = getData("Partie:pTrajectoire", nNum)
  nR[5] = getData("Partie:pTrajectoire[2]", pOne)
  nR[6] = getData("nLoad", nNum)
  nX = pOne.trsf.x
end
""", globals_=["num nLoad", "num nR[7]", "point pOne", "num nNum", "num nX"])
    add_libraries(folder, {"Partie": "Disk://Partie"})
    r = run_folder(folder)
    assert r.end_reason == "ended", r.diagnostics
    assert gv(r, "nR") == [1, -1, -2, -3, -4, 1, 1]
    assert gv(r, "nX") == 22
    assert gv(r, "nNum") == 0


def test_2_5_5_append_example(tmp_path):
    # manual: "println" (a typo of putln); sListe d'articles -> sArticleList
    r = sim(tmp_path, """begin
  // Demander un nouveau nom d'article
  put("Nouvel article •")
  get(sArticle)
  putln("")
  append(sArticleList)
  sArticleList[size(sArticleList)-1] = sArticle
end
""", globals_=["string sArticle", "string sArticleList[2]"], scenario=keys((0.1, "vis")))
    assert gv(r, "sArticleList") == ["", "", "vis"]


def test_2_5_5_size_dimension_example(tmp_path):
    # size(s3dArray, 3); 0 when nDimension is beyond the array's dimensions; size(s1dArray, 1)
    r = sim(tmp_path, """begin
  nNbElements=size(s3dArray, 3)
  n1 = size(s3dArray, 1)
  n2 = size(s3dArray, 2)
  n4 = size(s3dArray, 4)
  n1d = size(s1dArray, 1)
  n1d2 = size(s1dArray, 2)
end
""", globals_=["string s3dArray[2,3,4]", "string s1dArray[5]", "num nNbElements", "num n1", "num n2", "num n4",
               "num n1d", "num n1d2"])
    assert [gv(r, n) for n in ("nNbElements", "n1", "n2", "n4", "n1d", "n1d2")] == [4, 2, 3, 0, 5, 0]


def test_2_5_5_resize_example(tmp_path):
    # "L'instruction suivante modifie s2dArray de telle façon que sa seconde dimension soit 5":
    # values are kept, new ones are "" at the end
    r = sim(tmp_path, """begin
  s2dArray[1, 2] = "x"
  resize(s2dArray, 2, 5)
  n1 = size(s2dArray, 1)
  n2 = size(s2dArray, 2)
  sKept = s2dArray[1, 2]
  sNew = s2dArray[1, 4]
  resize(s2dArray, 1, 1)
  nAfter = size(s2dArray, 1)
end
""", globals_=["string s2dArray[2,3]", "num n1", "num n2", "string sKept", "string sNew", "num nAfter"])
    assert r.end_reason == "ended", r.diagnostics
    assert (gv(r, "n1"), gv(r, "n2"), gv(r, "sKept"), gv(r, "sNew"), gv(r, "nAfter")) == (2, 5, "x", "", 1)


COLL_SETUP = """  sCollection["pomme"] = "1"
  sCollection["banane"] = "2"
  sCollection["cerise"] = "3"
  sCollection["Abricot"] = "4"
"""


def test_2_5_6_next_example(tmp_path):
    # "Cet exemple imprime tous les éléments d'une collection ... dans l'ordre alphabétique".
    # As printed, the example calls next() before println (a typo of putln): it shows the keys
    # from the second one on, then "". Both the literal code and its evident intent are run.
    r = sim(tmp_path, "begin\n" + COLL_SETUP + """  sKey = first(sCollection)
  while sKey != ""
    sKey = next(sCollection[sKey])
    putln(sKey)
  endWhile
  putln("--")
  sKey = first(sCollection)
  while sKey != ""
    putln(sKey)
    sKey = next(sCollection[sKey])
  endWhile
end
""", globals_=['string sCollection[""]', "string sKey"])
    # alphabetical = code point order: upper case first
    assert out(r) == ["banane", "cerise", "pomme", "", "--", "Abricot", "banane", "cerise", "pomme"]


def test_2_5_6_prev_example(tmp_path):
    # same remark as for next(): literal code, then its evident intent
    r = sim(tmp_path, "begin\n" + COLL_SETUP + """  sKey = last(sCollection)
  while sKey != ""
    sKey = prev(sCollection[sKey])
    putln(sKey)
  endWhile
  putln("--")
  sKey = last(sCollection)
  while sKey != ""
    putln(sKey)
    sKey = prev(sCollection[sKey])
  endWhile
  putln(first(sEmpty) + "|" + last(sEmpty))
end
""", globals_=['string sCollection[""]', "string sKey", 'string sEmpty[""]'])
    assert out(r) == ["cerise", "banane", "Abricot", "", "--", "pomme", "cerise", "banane", "Abricot", "|"]


SEND_CALLS = """begin
  sMessage = "m"
  sMessageArray[23] = "a"
  s2dArray[12, 3] = "b"
  s3dArray[5, 7, 9] = "c"
  sMessageName = "k"
  sMessageColl[sMessageName] = "d"
  call sendMessage (sMessage)
  call sendMessage (sMessageArray[23])
  call sendMessage (s2dArray[12, 3])
  call sendMessage (s3dArray[5, 7, 9])
  call sendMessage (sMessageColl[sMessageName])
end
"""
SEND_GLOBALS = ["string sMessage", "string sMessageArray[30]", "string s2dArray[13,4]", "string s3dArray[6,8,10]",
                'string sMessageColl[""]', "string sMessageName", "string sSignalName", "string sSeen"]


def _sent(r):
    return (gv(r, "sMessage"), gv(r, "sMessageArray")[23], gv(r, "s2dArray")[12 * 4 + 3],
            gv(r, "s3dArray")[(5 * 8 + 7) * 10 + 9], gv(r, "sMessageColl")["k"])


def test_2_6_1_by_value_example(tmp_path):
    # "Après ces appels, la valeur de sMessage, ... n'a pas été modifiée"
    code = SEND_CALLS.replace("begin\n", """begin
  sSignalName = "Start"
  call sendMessage ("Attente du signal StartCycle")
  call sendMessage ("Attente du signal"+sSignalName)
""")
    r = sim(tmp_path, code, globals_=SEND_GLOBALS, programs={"sendMessage": {"params": ["string sMsg"], "code": """begin
  sSeen = sSeen + sMsg + ";"
  sMsg = "changed"
end
"""}})
    assert _sent(r) == ("m", "a", "b", "c", "d")
    assert gv(r, "sSeen") == "Attente du signal StartCycle;Attente du signalStart;m;a;b;c;d;"


def test_2_6_2_by_reference_example(tmp_path):
    # "Après ces appels, la valeur de sMessage, ... peut avoir été modifiée"
    r = sim(tmp_path, SEND_CALLS, globals_=SEND_GLOBALS, programs={"sendMessage": {"params": ["string& sMsg"],
                                                                                   "code": """begin
  sMsg = sMsg + "!"
end
"""}})
    assert _sent(r) == ("m!", "a!", "b!", "c!", "d!")


def test_2_6_3_array_reference_example(tmp_path):
    # "seule la partie du tableau sMessageArray commençant à l'index 23 est transmise"
    r = sim(tmp_path, """begin
  call send2dMessage (s2dArray)
  call send3dMessage (s3dArray)
  call sendCollMessage (sMessageColl)
  call send1dMessage (sMessageArray)
  call send1dMessage (sMessageArray[23])
end
""", globals_=["string sMessageArray[30]", "string s2dArray[13,4]", "string s3dArray[6,8,10]",
               'string sMessageColl[""]', "num nSizes[5]", "num nCall"],
        programs={
            "send1dMessage": {"params": ["string& s1dArray[]"], "code": """begin
  nSizes[nCall] = size(s1dArray)
  nCall = nCall + 1
  s1dArray[0] = s1dArray[0] + "x"
end
"""},
            "send2dMessage": {"params": ["string& s2d[,]"], "code": """begin
  nSizes[nCall] = size(s2d, 1) * 100 + size(s2d, 2)
  nCall = nCall + 1
  s2d[12, 3] = "2d"
end
"""},
            "send3dMessage": {"params": ["string& s3d[,,]"], "code": """begin
  nSizes[nCall] = size(s3d, 3)
  nCall = nCall + 1
  s3d[5, 7, 9] = "3d"
end
"""},
            "sendCollMessage": {"params": ['string& sColl[""]'], "code": """begin
  nSizes[nCall] = size(sColl)
  nCall = nCall + 1
  sColl["new"] = "coll"
end
"""}})
    assert r.end_reason == "ended", r.diagnostics
    assert gv(r, "nSizes") == [1304, 10, 0, 30, 7]
    arr = gv(r, "sMessageArray")
    assert arr[0] == "x" and arr[23] == "x" and arr[22] == "" and arr[24] == ""
    assert gv(r, "s2dArray")[12 * 4 + 3] == "2d"
    assert gv(r, "s3dArray")[(5 * 8 + 7) * 10 + 9] == "3d"
    assert gv(r, "sMessageColl") == {"new": "coll"}


def test_2_6_2_reference_kept_through_nested_calls(tmp_path):
    # an element passed by reference (2.6.2), then handed on by reference to an element or to an
    # array parameter (2.6.3), or to an instruction taking an array: the callee's writes reach
    # the first caller's variable; a by-value parameter handed on to an array parameter is the
    # callee's own copy
    r = sim(tmp_path, """begin
  call level1(nX)
  call level1(nArr[2])
  call byVal(nY)
end
""", globals_=["num nX", "num nArr[4]", "num nY", "num nSeen"], programs={
        "level1": {"params": ["num& x_n"], "code": "begin\n  call level2(x_n)\n  call fill(x_n)\n  x_n = x_n + 1\nend\n"},
        "level2": {"params": ["num& x_m"], "code": "begin\n  x_m = x_m + 10\nend\n"},
        "fill": {"params": ["num& x_a[]"], "code": "begin\n  x_a[0] = x_a[0] * 2\n  nSeen = size(x_a)\nend\n"},
        "byVal": {"params": ["num x_v"], "code": "begin\n  x_v = 5\n  call fill(x_v)\n  nY = x_v\nend\n"},
    })
    assert r.end_reason == "ended", r.diagnostics
    assert gv(r, "nX") == 21
    assert gv(r, "nArr") == [0, 0, 21, 0]
    assert gv(r, "nY") == 10
    assert gv(r, "nSeen") == 1


# ---- chapter 3: simple types -------------------------------------------------------------------


def test_3_1_2_bool_operators(tmp_path):
    # '=' assigns and returns the value; 'or'/'and' evaluate their right operand only when
    # needed (an out-of-range index there would be error 20); xor, ==, !=, !
    r = sim(tmp_path, """begin
  bR[0] = (bA = true)
  bR[1] = true or (nArr[99] == 0)
  bR[2] = false and (nArr[99] == 0)
  bR[3] = true xor false
  bR[4] = true xor true
  bR[5] = (true != false)
  bR[6] = (false == false)
  bR[7] = !bA
end
""", globals_=["bool bA", "bool bR[8]", "num nArr[2]"])
    assert r.end_reason == "ended", r.diagnostics
    assert gv(r, "bA") is True
    assert gv(r, "bR") == [True, True, False, True, False, True, True, False]


def test_3_2_1_num_constants_example(tmp_path):
    r = sim(tmp_path, """begin
  nC[0] = 1
  nC[1] = 0.2
  nC[2] = -3.141592653
  nC[3] = 6.02214179e23
  nC[4] = 1.054571628e-34
  nC[5] = 1e3
  nC[6] = 1e-2
  nAngle = 90
  bExact = cos(nAngle)==0
  bNear = abs(cos(nAngle))<1e-10
end
""", globals_=["num nC[7]", "num nAngle", "bool bExact", "bool bNear"])
    assert gv(r, "nC") == [1, 0.2, -3.141592653, 6.02214179e23, 1.054571628e-34, 1000, 0.01]
    assert gv(r, "bNear") is True


def test_3_2_2_num_operators(tmp_path):
    # "Le signe du reste est le signe de nValeur1"; '/' and '%' by 0 are runtime errors
    r = sim(tmp_path, """begin
  nR[0] = 7 % 3
  nR[1] = -7 % 3
  nR[2] = 7 % -3
  nR[3] = 7 / 2
  nR[4] = -(2 * 3) - 1 + 10
  nR[5] = (nA = 30)
  b[0] = 2 >= 2
  b[1] = 2 > 2
  b[2] = 1 <= 2
  b[3] = 1 < 1
  b[4] = 1 != 1
  b[5] = 1 == 1
end
""", globals_=["num nR[6]", "num nA", "bool b[6]"])
    assert gv(r, "nR") == [1, -1, 1, 3.5, 3, 30]
    assert gv(r, "b") == [True, False, True, False, False, True]
    for expr in ("1 / 0", "1 % 0"):
        r = sim(tmp_path / expr.replace(" ", "").replace("/", "div").replace("%", "mod"),
                f"begin\n  nR = {expr}\nend\n", globals_=["num nR"])
        assert errors(r) == [10]


MATH = [
    ("sin", "sin(30)", 0.5), ("asin", "asin(0.5)", 30), ("cos", "cos(60)", 0.5), ("acos", "acos(0.5)", 60),
    ("tan", "tan(45)", 1.0), ("atan", "atan(1)", 45), ("abs", "abs(3.1415)", 3.1415),
    ("abs_neg", "abs(-3.1415)", 3.1415), ("sqrt", "sqrt(9)", 3), ("exp", "exp(1)", 2.718281828459),
    ("power", "power(5, 7)", 78125), ("power_exp_ln", "exp(7*ln(5))", 78125),
    ("ln", "ln(2.718281828)", 0.99999999983113), ("log", "log(1000)", 3),
    ("roundUp", "roundUp(7.8)", 8), ("roundUp_neg", "roundUp(-7.8)", -7),
    ("roundDown", "roundDown(7.8)", 7), ("roundDown_neg", "roundDown(-7.8)", -8),
    ("round", "round(7.8)", 8), ("round_neg", "round(-7.8)", -8), ("round_half", "round(0.5)", 1),
    ("round_neg_half", "round(-0.5)", 0), ("min", "min(-1, 10)", -1), ("max", "max(-1, 10)", 10),
    ("limit", "limit(30, -90, 90)", 30), ("limit_high", "limit(100, -90, 90)", 90),
    ("limit_low", "limit(-100, -90, 90)", -90), ("sel_true", "sel(true, -90, 90)", -90),
    ("sel_false", "sel(false, -90, 90)", 90),
]


@pytest.mark.parametrize("expr,expected", [m[1:] for m in MATH], ids=[m[0] for m in MATH])
def test_3_2_3_examples(tmp_path, expr, expected):
    r = sim(tmp_path, f"begin\n  nResultat = {expr}\nend\n", globals_=["num nResultat"])
    assert r.end_reason == "ended", r.diagnostics
    # the manual's results have 14 significant digits (3.2.1); exp(7*ln(5)) is "avec imprécision"
    assert gv(r, "nResultat") == pytest.approx(expected, rel=1e-13 if "ln(5)" not in expr else 1e-9, abs=1e-13)


@pytest.mark.parametrize("expr", ["asin(1.5)", "acos(-2)", "sqrt(-1)", "exp(1000)", "power(-2, 2)", "power(0, 2)",
                                  "ln(0)", "log(-1)"])
def test_3_2_3_runtime_errors(tmp_path, expr):
    # "Une erreur d'exécution est générée si ...": error 11 (12.1: "calcul numérique non valide")
    r = sim(tmp_path, f"begin\n  nResultat = {expr}\nend\n", globals_=["num nResultat"])
    assert errors(r) == [11]


def test_3_3_3_bnot_example(tmp_path):
    # reset bits i to j of a bit field with a mask
    r = sim(tmp_path, """begin
  i = 4
  j = 7
  nChampBit = 4095
  // Calculer un masque de bits avec les bits i à j initialisés à 1 (voir les explications sous bOr)
  nMasque=(power(2,j-i+1)-1)*power(2,i)
  // Inverser le masque pour que tous les bits soient à 1 sauf les bits i à j
  nMasque=bNot(nMasque)
  // Réinitialiser les bits i à j à l'aide de l'opération binaire 'and'
  nChampBit=bAnd(nChampBit, nMasque)
end
""", globals_=["num i", "num j", "num nChampBit", "num nMasque"])
    assert gv(r, "nMasque") == 2**32 - 1 - 0xF0
    assert gv(r, "nChampBit") == 4095 - 0xF0


def test_3_3_3_band_example(tmp_path):
    # "Ce programme affiche un champ de bits nChampBit de 32 bits à l'écran"
    r = sim(tmp_path, """begin
  nChampBit = 2868903935
  for i=31 to 0 step -1
    // Calculer le masque pour le i ème bit
    nMasque=power(2,i)
    if bAnd(nChampBit, nMasque)==nMasque
      put("1")
    else
      put("0")
    endIf
  endFor
  putln("")
end
""", globals_=["num i", "num nChampBit", "num nMasque"])
    assert out(r) == [format(2868903935, "032b")]


def test_3_3_3_bor_example(tmp_path):
    # "calcule de deux manières différentes un masque ... dans lequel les i ème à j ème bits sont activés"
    r = sim(tmp_path, """begin
  i = 3
  j = 9
  // Première manière : logique 'or' sur les bits i à j
  nChampBit=0
  for k=i to j
    nChampBit=bOr (nChampBit, power (2,k))
  endFor
  nFirst = nChampBit
  // Deuxième manière : calculer un masque de bits de (j-i) bits
  nChampBit=(power (2,j-i+1)-1)
  // Déplacer ensuite le masque de bits de i bits
  nChampBit=nChampBit*power (2,i)
end
""", globals_=["num i", "num j", "num k", "num nChampBit", "num nFirst"])
    assert gv(r, "nFirst") == gv(r, "nChampBit") == 0b1111111000


def test_3_3_3_bxor_example(tmp_path):
    r = sim(tmp_path, """begin
  i = 0
  j = 3
  nChampBit = 0b
  nChampBit = 165
  // Calculer le masque pour les bits i à j (voir l'exemple bOr)
  nMasque=(power (2,j-i+1)-1)*power (2,i)
  // Inverser les bits i à j à l'aide du masque
  nChampBit=bXor (nChampBit,nMasque)
end
""".replace("  nChampBit = 0b\n", ""), globals_=["num i", "num j", "num nChampBit", "num nMasque"])
    assert gv(r, "nChampBit") == 165 ^ 0xF


def test_3_3_3_tobinary_frombinary_example(tmp_path):
    # the first program encodes a trsf in 48 bytes and sends them on siTcpClient; the second one
    # reads 48 bytes on siTcpServer (sent here by the scenario's peer) and decodes them.
    # The manual declares "nByteOut[48]" inline: a global num nByteOut[48] here.
    trsf_in = (1.5, -2.25, 300.0, 90.0, -45.5, 0.125)
    data = list(struct.pack(">6d", *trsf_in))
    r = sim(tmp_path, """begin
  trShiftOut = {10, 20, 30, 0, 90, 180}
  // ---- Programme pour envoyer une trsf ----
  // Copie les coordonnées de la trsf dans une variable numérique tampon
  nTrsfOut[0]=trShiftOut.x
  nTrsfOut[1]=trShiftOut.y
  nTrsfOut[2]=trShiftOut.z
  nTrsfOut[3]=trShiftOut.rx
  nTrsfOut[4]=trShiftOut.ry
  nTrsfOut[5]=trShiftOut.rz
  // Code 6 valeurs numériques (virgule flottante double précision, donc 8 octets) dans 6*8=48 octets dans le tableau
  nEncoded = toBinary(nTrsfOut, 6, "8.0b", nByteOut)
  // Envoyer le tableau nByte (48 octets) sur tcpClient
  nSent = sioSet(siTcpClient, nByteOut)
  call readTrsf()
end
""", globals_=["trsf trShiftOut", "trsf trShiftIn", "num nTrsfOut[6]", "num nTrsfIn[6]", "num nByteOut[48]",
               "num nByteIn[48]", "num nb", "num i", "num nEncoded", "num nSent", "sio siTcpClient",
               "sio siTcpServer", "bool bDone"],
        programs={"readTrsf": {"code": """begin
  // ---- Programme pour lire une trsf ---
  nb=0
  i=0
  while (nb<48)
    nb=sioGet(siTcpServer, nByteIn[i])
    if(nb>0)
      i=i+nb
    else
      // Erreur de communication
      return
    endIf
  endWhile
  if (fromBinary(nByteIn, 48, "8.0b", nTrsfIn) != 6)
    // Données altérées
    return
  else
    trShiftIn.x=nTrsfIn[0]
    trShiftIn.y=nTrsfIn[1]
    trShiftIn.z=nTrsfIn[2]
    trShiftIn.rx=nTrsfIn[3]
    trShiftIn.ry=nTrsfIn[4]
    trShiftIn.rz=nTrsfIn[5]
    bDone = true
  endif
end
"""}}, links={"siTcpClient": "client", "siTcpServer": "server"},
        scenario=f'[[serial]]\nsio = "siTcpServer"\nat = 0.5\nbytes = {data}\n')
    assert r.end_reason == "ended", r.diagnostics
    assert gv(r, "nEncoded") == 48 and gv(r, "nSent") == 48
    assert gv(r, "nByteOut") == list(struct.pack(">6d", 10, 20, 30, 0, 90, 180))
    assert len([e for e in r.io_log if e[2] == "client"]) == 1  # one write of 48 bytes
    assert gv(r, "bDone") is True
    t = gv(r, "trShiftIn")
    assert (t["x"], t["y"], t["z"], t["rx"], t["ry"], t["rz"]) == trsf_in


def test_3_4_2_string_operators(tmp_path):
    # '+' keeps the first 128 bytes; '=' returns the string; == and !=
    r = sim(tmp_path, """begin
  sLong = "0123456789012345678901234567890123456789012345678901234567890123"
  sLong = sLong + sLong + "abc"
  nLen = len(sLong)
  sB = (sA = "hello wild world")
  bEq = sA == "hello wild world"
  bNe = sA != "hello"
  sHan = "中中中中中中中中中中中中中中中中中中中中中中中中中中中中中中中中中中中中中中中中中中中中中中中中"
  nHan = len(sHan)
end
""", globals_=["string sLong", "num nLen", "string sA", "string sB", "bool bEq", "bool bNe", "string sHan",
               "num nHan"])
    assert gv(r, "nLen") == 128
    assert gv(r, "sB") == "hello wild world"
    assert gv(r, "bEq") is True and gv(r, "bNe") is True
    assert gv(r, "nHan") == 42  # 3.4.1: "celle d'une chaîne en chinois de 42 caractères"


def test_3_4_3_tostring_example(tmp_path):
    # The printed results lost their spaces; the counts in parentheses give them.
    r = sim(tmp_path, """begin
  nPi = 3.141592654
  s[0] = toString(".4", nPi)
  s[1] = toString("8", nPi)
  s[2] = toString("8.4", nPi)
  s[3] = toString("8.4", 2.70001)
  s[4] = toString("", nPi)
  s[5] = toString("1.2", 1234.1234)
end
""", globals_=["num nPi", "string s[6]"])
    assert gv(r, "s") == ["3.1416", " " * 7 + "3", "  3.1416", "  2.7   ", "3", "1234.12"]


def test_3_4_3_tonum_example(tmp_path):
    r = sim(tmp_path, """begin
  nVal = 5
  s[0] = toNum("10 20 30", nVal, bOk)
  n[0] = nVal
  b[0] = bOk
  nVal = 5
  s[1] = toNum("a10 20 30", nVal, bOk)
  n[1] = nVal
  b[1] = bOk
  s[2] = toNum("10 end", nVal, bOk)
  n[2] = nVal
  b[2] = bOk
  // Ce programme affiche successivement 90, 0, -7.6, 17.3
  sBuffer = "+90 0.0 -7.6 17.3"
  do
    sBuffer = toNum(sBuffer, nVal, bOk)
    putln(nVal)
  until (sBuffer== "") or (bOk != true)
end
""", globals_=["num nVal", "bool bOk", "string s[3]", "num n[3]", "bool b[3]", "string sBuffer"])
    assert gv(r, "s") == ["20 30", "a10 20 30", ""]
    assert gv(r, "n") == [10, 5, 10]
    assert gv(r, "b") == [True, False, True]
    assert out(r) == ["90", "0", "-7.6", "17.3"]


STRINGS = [
    ("chr", 'chr(65)', "A"), ("chr_invalid", 'chr(1114112)', ""),
    ("left", 'left ("salut tout le monde", 5)', "salut"),
    ("left_long", 'left ("salut tout le monde", 20)', "salut tout le monde"),
    ("right", 'right ("salut tout le monde", 5)', "monde"),
    ("right_long", 'right ("salut tout le monde", 20)', "salut tout le monde"),
    ("mid", 'mid("salut joli monde", 4, 6)', "joli"), ("mid_long", 'mid("salut joli monde", 20, 6)', "joli monde"),
    # The printed insert()/delete() results do not follow from their arguments (insert "joli" at
    # 6 of "salut tout le monde" cannot give "salut joli monde"; the two lines look swapped):
    # the function's definition is followed.
    ("insert", 'insert("salut tout le monde", "joli", 6)', "salut jolitout le monde"),
    ("insert_intent", 'insert("salut monde", "joli ", 6)', "salut joli monde"),
    ("delete", 'delete("salut joli monde", 5, 6)', "salut monde"),
    ("replace", 'replace("salut • monde", "joli", 1, 6)', "salut joli monde"),
]


@pytest.mark.parametrize("expr,expected", [m[1:] for m in STRINGS], ids=[m[0] for m in STRINGS])
def test_3_4_3_string_examples(tmp_path, expr, expected):
    r = sim(tmp_path, f"begin\n  sResult = {expr}\nend\n", globals_=["string sResult"])
    assert r.end_reason == "ended", r.diagnostics
    assert gv(r, "sResult") == expected


def test_3_4_3_num_string_examples(tmp_path):
    r = sim(tmp_path, """begin
  n[0] = asc("A", 0)
  n[1] = asc("A", 1)
  n[2] = asc("A", -1)
  n[3] = find("salut joli monde", "joli")
  n[4] = find("salut joli monde", "moche")
  n[5] = len("salut joli monde")
end
""", globals_=["num n[6]"])
    assert gv(r, "n") == [65, -1, -1, 6, -1, 16]


@pytest.mark.parametrize("expr", ['left("abc", -1)', 'right("abc", -1)', 'mid("abc", -1, 0)', 'mid("abc", 1, -1)',
                                  'insert("abc", "x", -1)', 'delete("abc", -1, 0)', 'replace("abc", "x", 1, -1)'])
def test_3_4_3_string_runtime_errors(tmp_path, expr):
    # "Une erreur d'exécution est générée si nTaille (ou nPosition) est négatif": error 70
    r = sim(tmp_path, f"begin\n  sResult = {expr}\nend\n", globals_=["string sResult"])
    assert errors(r) == [70]


def test_3_5_2_dio_operators(tmp_path):
    # '=' writes the output and returns the value; == / != between dio and bool or two dio;
    # s7: "diOut = diIn" is replaced by "diOut = (diIn==true)"
    r = sim(tmp_path, """begin
  bR[0] = (doOut = true)
  bR[1] = doOut == true
  bR[2] = doOut != true
  bR[3] = doOut == diIn
  doOut = (diIn==true)
  bR[4] = doOut
  bR[5] = doOut == diIn
end
""", globals_=["dio doOut", "dio diIn", "bool bR[6]"], links={"doOut": "out0", "diIn": "in0"})
    assert r.end_reason == "ended", r.diagnostics
    assert gv(r, "bR") == [True, True, False, False, False, True]
    assert gv(r, "doOut") is False


DIOLINK = """begin
  if(ioStatus(diDevice1Signal)>=0)
    // appareil 1 installé : utiliser cet appareil
    dioLink(diSignal, diDevice1Signal)
  elseIf (ioStatus(diDevice2Signal)>=0)
    // appareil 2 installé : utiliser cet appareil
    dioLink(diSignal, diDevice2Signal)
  else
    putln("Erreur : pas d'appareil e/s installé")
  endif
  nStatus = ioStatus(diSignal)
  bValue = diSignal
end
"""


@pytest.mark.parametrize("io,value,message", [
    ("", True, None),
    ("[io]\ndiDevice1Signal = { status = -2 }\n", False, None),
    ("[io]\ndiDevice1Signal = { status = -2 }\ndiDevice2Signal = { status = -3 }\n", None,
     "Erreur : pas d'appareil e/s installé"),
])
def test_3_5_3_diolink_iostatus_example(tmp_path, io, value, message):
    # The dioLink example (printed with println, a typo of putln) and the ioStatus one: the
    # scenario's [io] table tells which device is installed
    r = sim(tmp_path, DIOLINK, globals_=["dio diDevice1Signal", "dio diDevice2Signal", "dio diSignal", "num nStatus",
                                         "bool bValue"],
            links={"diDevice1Signal": "Dev1\\Mod\\%I0", "diDevice2Signal": "Dev2\\Mod\\%I0"},
            scenario="[inputs]\ndiDevice1Signal = true\ndiDevice2Signal = false\n" + io)
    if message is None:
        assert r.end_reason == "ended", r.diagnostics
        assert gv(r, "nStatus") == 0
        assert gv(r, "bValue") is value
        assert out(r) == []
    else:
        assert out(r) == [message]
        # diSignal keeps its undefined link: ioStatus -1, then reading it is error 123
        assert gv(r, "nStatus") == -1
        assert errors(r) == [123]


def test_3_5_3_iostatus_table(tmp_path):
    # 0 works, 1 locked (writing has no effect), 2 simulated, -1 no link, -2 not installed
    # (using it: error 123), -3 device in error (error 125); the description and the link
    r = sim(tmp_path, """begin
  nS[0] = ioStatus(doOk)
  nS[1] = ioStatus(doLocked)
  nS[2] = ioStatus(doSim)
  nS[3] = ioStatus(doNone)
  nS[4] = ioStatus(doMissing)
  nS[5] = ioStatus(doBroken, sDescription, sPath)
  nS[6] = ioStatus(aiOk)
  doLocked = true
  doSim = true
  bLocked = doLocked
  bSim = doSim
  if ioStatus(doBroken, sDescription, sPath)<0
    putln("Signal "+sPath+ " en erreur")
    putln("Description :" +sDescription)
  endif
  nBus = ioBusStatus(sBusErrors)
  doMissing = true
end
""", globals_=["dio doOk", "dio doLocked", "dio doSim", "dio doNone", "dio doMissing", "dio doBroken", "aio aiOk",
               "num nS[7]", "string sDescription", "string sPath", "bool bLocked", "bool bSim", "num nBus",
               "string sBusErrors[1]"],
        links={"doOk": "BIO\\M1\\%Q0", "doLocked": "BIO\\M1\\%Q1", "doSim": "BIO\\M1\\%Q2", "doMissing": "BIO\\M9\\%Q0",
               "doBroken": "Fieldbus\\Slave3\\%Q0", "aiOk": "BIO\\M1\\%IW0"},
        scenario="""[io]
doLocked = { status = 1 }
doSim = { status = 2 }
doMissing = { status = -2 }
doBroken = { status = -3, description = "vanne de sortie" }
""")
    assert gv(r, "nS") == [0, 1, 2, -1, -2, -3, 0]
    assert gv(r, "bLocked") is False and gv(r, "bSim") is True
    assert out(r) == ["Signal Fieldbus\\Slave3\\%Q0 en erreur", "Description :vanne de sortie"]
    assert gv(r, "nBus") == 1 and gv(r, "sBusErrors") == "-3:Fieldbus\\Slave3"
    assert errors(r) == [123]


def test_3_5_3_dioget_example(tmp_path):
    r = sim(tmp_path, """begin
  diArray[0] = false
  diArray[1] = true
  diArray[2] = false
  diArray[3] = true
  nValue = dioGet(diArray)
end
""", globals_=["dio diArray[4]", "num nValue"], links={"diArray": ["o0", "o1", "o2", "o3"]})
    assert gv(r, "nValue") == 10


def test_3_5_3_dioset_example(tmp_path):
    # dioSet(di4bitsArray, 26) returns 10: "26 demande 5 bits en codage binaire : 10 = 26 - 2^4"
    r = sim(tmp_path, """begin
  n[0] = dioSet(di4bitsArray, 10)
  n[1] = dioGet(di4bitsArray)
  n[2] = dioSet(di4bitsArray, 26)
  n[3] = dioSet(di4bitsArray, 5.9)
end
""", globals_=["dio di4bitsArray[4]", "num n[4]"], links={"di4bitsArray": ["o0", "o1", "o2", "o3"]})
    assert gv(r, "n") == [10, 10, 10, 5]
    assert gv(r, "di4bitsArray") == [True, False, True, False]


def test_3_5_1_unlinked_dio_is_error_123(tmp_path):
    r = sim(tmp_path, "begin\n  doX = true\nend\n", globals_=["dio doX"])
    assert errors(r) == [123]


AIOLINK = """begin
  if (ioStatus(aiDevice1Signal) >= 0)
    // appareil 1 installé : utiliser cet appareil
    aioLink(aiSignal, aiDevice1Signal)
  elseIf (ioStatus(aiDevice2Signal) >= 0)
    // appareil 2 installé : utiliser cet appareil
    aioLink(aiSignal, aiDevice2Signal)
  else
    putln("Erreur : pas d'appareil e/s installé")
  endif
  nValue = aioGet(aiSignal)
end
"""


@pytest.mark.parametrize("io,value", [("", 1.5), ("[io]\naiDevice1Signal = { status = -2 }\n", 2.5)])
def test_3_6_2_aiolink_iostatus_example(tmp_path, io, value):
    r = sim(tmp_path, AIOLINK, globals_=["aio aiDevice1Signal", "aio aiDevice2Signal", "aio aiSignal", "num nValue"],
            links={"aiDevice1Signal": "Dev1\\%IW0", "aiDevice2Signal": "Dev2\\%IW0"},
            scenario="[inputs]\naiDevice1Signal = 1.5\naiDevice2Signal = 2.5\n" + io)
    assert r.end_reason == "ended", r.diagnostics
    assert gv(r, "nValue") == value


def test_3_6_2_aioget_aioset_example(tmp_path):
    # aioGet(aiSensor) "renvoie la valeur actuelle du capteur"; aioSet(aiCommand, -12.3) writes
    # and returns -12.3 on a floating-point output, aioSet(aiCommand, 12.3) writes and returns
    # 12 on an integer output (the scenario's [io] table declares it)
    r = sim(tmp_path, """begin
  n[0] = aioGet(aiSensor)
  delay(1)
  n[1] = aioGet(aiSensor)
  n[2] = aioSet(aiCommand, -12.3)
  n[3] = aioSet(aiIntCommand, 12.3)
  n[4] = aioGet(aiIntCommand)
end
""", globals_=["aio aiSensor", "aio aiCommand", "aio aiIntCommand", "num n[5]"],
        links={"aiSensor": "sensor", "aiCommand": "cmd", "aiIntCommand": "icmd"},
        scenario="[inputs]\naiSensor = 4.2\n[[events]]\nat = 0.5\nset = { aiSensor = 7.5 }\n"
                 "[io]\naiIntCommand = { integer = true }\n")
    assert gv(r, "n") == [4.2, 7.5, -12.3, 12, 12]
    assert gv(r, "aiCommand") == -12.3


def test_3_7_2_sio_operators(tmp_path):
    # sio = string writes UTF-8 and the end-of-string character (13 by default) and returns the
    # text; sio = num writes the nearest integer modulo 256 and returns it; num = sio reads one
    # byte; string = sio reads up to the end-of-string character (not copied)
    r = sim(tmp_path, """begin
  sR = (siLine = "héllo")
  nR[0] = (siLine = 300.4)
  nR[1] = (siLine = -1)
  nR[2] = siLine
  sIn = siLine
  nR[3] = siLine
end
""", globals_=["sio siLine", "string sR", "num nR[4]", "string sIn"], links={"siLine": "Serial0"},
        scenario='[[serial]]\nsio = "siLine"\nat = 0.1\nbytes = [65, 111, 107, 13, 66, 67]\n')
    assert gv(r, "sR") == "héllo"
    assert gv(r, "nR")[:2] == [44, 255]
    assert gv(r, "nR")[2] == 65
    assert gv(r, "sIn") == "ok"
    assert gv(r, "nR")[3] == 66
    sent = [e[3] for e in r.io_log if e[2] == "Serial0" and e[4] != "scenario"]
    assert sent[0] == "héllo\r"


def test_3_7_3_clearbuffer_sioget_sioset(tmp_path):
    # clearBuffer returns the number of characters cleared; sioGet reads until the array is full
    # or the input buffer is empty and returns the count (waiting for data when there is none;
    # -1 at the communication timeout); sioSet writes the nearest integers modulo 256
    r = sim(tmp_path, """begin
  delay(0.2)
  n[0] = clearBuffer(siLine)
  n[1] = sioGet(siLine, nBuf)
  n[2] = sioGet(siLine, nBuf[3])
  nBuf[0] = 256.6
  nBuf[1] = -1
  n[3] = sioSet(siLine, nBuf)
  n[4] = sioCtrl(siLine, "timeout", 0.5)
  n[5] = sioGet(siLine, nBuf)
  n[6] = clock()
end
""", globals_=["sio siLine", "num n[7]", "num nBuf[5]"], links={"siLine": "Serial0"},
        scenario='[[serial]]\nsio = "siLine"\nat = 0.1\nbytes = [1, 2, 3]\n'
                 '[[serial]]\nsio = "siLine"\nat = 0.5\nbytes = [10, 11, 12, 13, 14, 15, 16]\n')
    assert r.end_reason == "ended", r.diagnostics
    n = gv(r, "n")
    assert n[0] == 3
    assert n[1] == 5  # waited for the bytes sent at 0.5 s: the 5 first ones
    assert n[2] == 2  # the 2 left, from index 3
    assert gv(r, "nBuf") == [256.6, -1, 12, 15, 16]
    assert n[3] == 5
    assert [e[3] for e in r.io_log if e[4] != "scenario"] == [[1, 255, 12, 15, 16]]
    assert n[4] == 0
    assert n[5] == -1 and n[6] == pytest.approx(1.0, abs=0.01)


@pytest.mark.parametrize("name,value,code", [
    ('"baudRate"', "115200", 0), ('"bits"', "8", 0), ('"parity"', '"none"', 0), ('"stopBits"', "1", 0),
    ('"timeout"', "0", 0), ('"endOfString"', "13", 0),
    ('"speed"', "9600", -1), ('"parity"', "1", -2), ('"parity"', '"mark"', -3), ('"bits"', "9", -3),
    ('"endOfString"', "300", -3), ('"nagle"', "false", 0), ('"mode"', '"rs485"', -3),
    ('"flowControl"', '"xon"', -3),
])
def test_3_7_3_sioctrl_example(tmp_path, name, value, code):
    # "Ce programme configure les paramètres principaux d'une ligne série": each call returns 0;
    # and the table of return codes
    r = sim(tmp_path, f"begin\n  nR = sioCtrl(siPortSerial1, {name}, {value})\nend\n",
            globals_=["sio siPortSerial1", "num nR"], links={"siPortSerial1": "Serial1"})
    assert r.end_reason == "ended", r.diagnostics
    assert gv(r, "nR") == code


def test_3_7_3_sioctrl_end_of_string(tmp_path):
    r = sim(tmp_path, """begin
  sioCtrl(siPortSerial1, "endOfString", 59)
  siPortSerial1 = "a"
  s = siPortSerial1
end
""", globals_=["sio siPortSerial1", "string s"], links={"siPortSerial1": "Serial1"},
        scenario='[[serial]]\nsio = "siPortSerial1"\nat = 0.1\nsend = "x"\n[[serial]]\nsio = "siPortSerial1"\n'
                 'at = 0.2\nbytes = [121, 59]\n')
    assert gv(r, "s") == "x\ry"  # the scenario's send used the default end of string (13)


# ---- chapter 4: user interface ----------------------------------------------------------------


def test_4_3_put_putln(tmp_path):
    # "affiche le sTexte ou nValeur spécifié (à 3 décimales)"; at the end of a line the display
    # goes on with the next one; at the end of the page the page scrolls up one line
    r = sim(tmp_path, """begin
  putln(3.14159)
  putln(-7.6)
  put(2)
  putln("")
  put("0123456789012345678901234567890123456789ABC")
  putln("")
  for i = 1 to 12
    putln(i)
  endFor
end
""", globals_=["num i"])
    assert out(r)[:3] == ["3.142", "-7.6", "2"]
    # 18 lines were used (the 40 characters wrapped, then the cursor's line): the page scrolled
    # up by 4
    lines = r.screen["lines"]
    assert lines[0] == "ABC"
    assert lines[1:13] == [str(i) for i in range(1, 13)]
    assert lines[13] == ""


def test_4_3_gotoxy_cls_title(tmp_path):
    # gotoxy: nX modulo 40, nY modulo 14; title() does not move the cursor; cls() clears and
    # goes to (0,0)
    r = sim(tmp_path, """begin
  put("old")
  cls()
  gotoxy(42, 15)
  put("a")
  title("Titre")
  put("b")
  gotoxy(-1, 0)
  put("z")
end
""")
    lines = r.screen["lines"]
    assert lines[1] == "  ab"
    assert lines[0] == " " * 39 + "z"
    assert r.screen["title"] == "Titre"


def test_4_2_screens_and_userpage(tmp_path):
    # writes to a screen that is not displayed stay hidden until userPage() shows it; the
    # default page is not affected
    r = sim(tmp_path, """begin
  title(scDebug, "Debug")
  putln(scDebug, "caché")
  putln("visible")
  userPage(scDebug)
  userPage()
end
""", globals_=["screen scDebug"])
    entries = [(e[2], e[3], e[4]) for e in r.transcript]
    assert entries == [("title", "Debug", "scDebug"), ("putln", "caché", "scDebug"), ("putln", "visible", None),
                       ("userPage", "scDebug", "scDebug"), ("userPage", "", None)]
    assert r.screen["lines"][0] == "visible" and r.screen["title"] == ""


def test_4_3_get_example(tmp_path):
    # "Ce programme lit une valeur numérique validée avec la touche Retour": a menu key updates
    # nValeur but does not end the loop; Esc leaves it unchanged; Return ends it
    r = sim(tmp_path, """begin
  do
    nKey = get (nValeur)
    nSeen[nCount] = nValeur
    nCount = nCount + 1
  until (nKey == 270)
end
""", globals_=["num nKey", "num nValeur", "num nSeen[3]", "num nCount"],
        scenario='[[keys]]\nat = 0.1\ntext = "12"\nkey = 271\n[[keys]]\nat = 0.2\ntext = "99"\nkey = 255\n'
                 '[[keys]]\nat = 0.3\ntext = "42"\n')
    assert r.end_reason == "ended", r.diagnostics
    assert gv(r, "nSeen") == [12, 12, 42]
    assert gv(r, "nKey") == 270


def test_4_3_getkey_example(tmp_path):
    # "Ce programme actualise l'affichage de l'horloge système jusqu'à ce qu'on appuie sur une
    # touche" (also the example of delay(), 5.10); the key pressed before the first getKey()
    # is forgotten
    r = sim(tmp_path, """begin
  // Réinitialiser d'abord le code de la dernière touche enfoncée
  delay(0.5)
  getKey()
  while (getKey() == -1)
    gotoxy(0, 0)
    put(toString("", clock() * 10))
    delay(0)
  endWhile
  nEnd = clock()
end
""", globals_=["num nEnd"], scenario=keys((0.2, 113), (2.0, 119)))
    assert r.end_reason == "ended", r.diagnostics
    assert gv(r, "nEnd") == pytest.approx(2.0, abs=0.01)
    assert r.screen["lines"][0] in ("19", "20")


def test_4_3_iskeypressed(tmp_path):
    r = sim(tmp_path, """begin
  delay(1.1)
  b[0] = isKeyPressed(271)
  b[1] = isKeyPressed(272)
  delay(0.5)
  b[2] = isKeyPressed(271)
end
""", globals_=["bool b[3]"], scenario="[[keys]]\nat = 1.0\nkey = 271\nhold = 0.3\n")
    assert gv(r, "b") == [True, False, False]


def test_4_3_getdisplaylen(tmp_path):
    # ASCII: the same as len(); Chinese characters take two columns
    r = sim(tmp_path, """begin
  n[0] = getDisplayLen("salut")
  n[1] = len("salut")
  n[2] = getDisplayLen("中文")
  n[3] = len("中文")
end
""", globals_=["num n[4]"])
    assert gv(r, "n") == [5, 5, 4, 2]


def test_4_3_popupmsg_logmsg_example(tmp_path):
    # logMsg: "USR" is added before the text; the example loops until the message is logged
    r = sim(tmp_path, """begin
  sMessage = "cycle terminé"
  while logMsg (sMessage) ==false
    delay(0)
  endWhile
  popUpMsg("Erreur : en attente de signal")
end
""", globals_=["string sMessage"])
    assert [(e[2], e[3]) for e in r.transcript] == [("logMsg", "USR cycle terminé"),
                                                    ("popUpMsg", "Erreur : en attente de signal")]


def test_4_3_setprofile_codes(tmp_path):
    # 0 done, 1 unknown profile, 2 wrong password, 3 'staubli' not allowed
    r = sim(tmp_path, """begin
  s[0] = getProfile()
  n[0] = setProfile("nobody", "")
  n[1] = setProfile("maintenance", "0000")
  n[2] = setProfile("staubli", "x")
  n[3] = setProfile("maintenance", "1234")
  s[1] = getProfile()
end
""", globals_=["num n[4]", "string s[2]"], scenario='[controller]\nprofiles = { maintenance = "1234" }\n')
    assert gv(r, "n") == [1, 2, 3, 0]
    assert gv(r, "s") == ["default", "maintenance"]
    r = sim(tmp_path / "staubli", 'begin\n  nR = setProfile("maintenance", "1234")\nend\n', globals_=["num nR"],
            scenario='[controller]\nprofile = "staubli"\nprofiles = { maintenance = "1234" }\n')
    assert gv(r, "nR") == 4  # "Le profil d'utilisateur en cours est 'staubli'"


LANGUAGE = """begin
  switch(getLanguage())
    case "francais"
      sMessage="Attention!"
    break
    case "english"
      sMessage="Warning!"
    break
    case "deutsch"
      sMessage="Achtung!"
    break
    case "italiano"
      sMessage="Avviso!"
    break
    case "espanol"
      sMessage="¡Advertencia!"
    break
    default
      sMessage="Warning!"
    break
  endSwitch
end
"""


@pytest.mark.parametrize("lang,message", [(None, "Warning!"), ("francais", "Attention!"), ("deutsch", "Achtung!"),
                                          ("italiano", "Avviso!"), ("espanol", "¡Advertencia!"),
                                          ("chinois", "Warning!")])
def test_4_3_getlanguage_example(tmp_path, lang, message):
    # the printed ";Advertencia!" is an OCR of "¡Advertencia!"
    sc = f'[controller]\nlanguage = "{lang}"\n' if lang else None
    r = sim(tmp_path, LANGUAGE, globals_=["string sMessage"], scenario=sc)
    assert gv(r, "sMessage") == message


@pytest.mark.parametrize("languages,message", [
    (None, ["La langue chinoise n'est pas disponible sur le contrôleur du robot"]), ('["english", "chinois"]', [])])
def test_4_3_setlanguage_example(tmp_path, languages, message):
    r = sim(tmp_path, """begin
  if(setLanguage ("chinois") ==false)
    putln ("La langue chinoise n'est pas disponible sur le contrôleur du robot")
  endif
  sNow = getLanguage()
end
""", globals_=["string sNow"], scenario=f"[controller]\nlanguages = {languages}\n" if languages else None)
    assert out(r) == message
    assert gv(r, "sNow") == ("english" if message else "chinois")


GETDATE = """begin
  switch (getDate ("%m"))
    case "01"
      sMois="Janvier"
    break
    case "02"
      sMois="Février"
    break
    case "03"
      sMois="Mars"
    break
    case "04"
      sMois="Avril"
    break
    case "05"
      sMois="Mai"
    break
    case "06"
      sMois="Juin"
    break
    case "07"
      sMois="Juillet"
    break
    case "08"
      sMois="Août"
    break
    case "09"
      sMois="Septembre"
    break
    case "10"
      sMois="October"
    break
    case "11"
      sMois="Novembre"
    break
    case "12"
      sMois="Décembre"
    break
    default
      sMois="???"
    break
  endSwitch
  // Afficher date et heure sous la forme : "January 01, 2007 13:45:23"
  putln(getDate(sMois+" %d, %Y %H:%M:%S"))
  putln(getDate("%y %I %p"))
end
"""


def test_4_3_getdate_example(tmp_path):
    # The example's last line uses sMonth where it set sMois (a typo), and its comment shows
    # the English month name where the example sets the French one: sMois is used.
    r = sim(tmp_path, GETDATE, globals_=["string sMois"], scenario="[controller]\ndate = 2007-01-01T13:45:23\n")
    assert out(r) == ["Janvier 01, 2007 13:45:23", "07 01 PM"]
    r = sim(tmp_path / "oct", GETDATE, globals_=["string sMois"], scenario="[controller]\ndate = 2010-10-09T08:05:00\n")
    assert out(r) == ["October 09, 2010 08:05:00", "10 08 AM"]


# ---- chapter 5: tasks ---------------------------------------------------------------------------


def test_5_2_start_and_stop_tasks(tmp_path):
    # start() runs in task "APP~", stop() in "~APP", both of priority 10
    r = sim(tmp_path, 'begin\n  putln("start")\nend\n', programs={"stop": {"code": 'begin\n  putln("stop")\nend\n'}})
    assert [(e[1], e[3]) for e in r.transcript] == [("Example~", "start"), ("~Example", "stop")]
    assert [(t.name, t.priority) for t in r.tasks] == [("Example~", 10), ("~Example", 10)]


def test_5_4_sequencing(tmp_path):
    # tasks take turns in creation order, each running as many lines as its priority; a line
    # that cannot complete (here delay(0)) hands over at once
    code = "begin\n" + '  sTrace = sTrace + "{c}"\n' * 6 + "end\n"
    r = sim(tmp_path, """begin
  taskCreate "a", 2, lineA()
  taskCreate "b", 3, lineB()
  taskCreate "c", 50, lineC()
  wait(false)
end
""", globals_=["string sTrace"], programs={
        "lineA": {"code": code.format(c="a")}, "lineB": {"code": code.format(c="b")},
        "lineC": {"code": 'begin\n  sTrace = sTrace + "c"\n  delay(0)\n  sTrace = sTrace + "C"\nend\n'}},
        duration=1)
    assert gv(r, "sTrace") == "aabbbcaabbbCaa"


def test_5_5_taskcreatesync_example(tmp_path):
    # "Créer une tâche de supervision programmée toutes les 20 ms": one run per period
    r = sim(tmp_path, """begin
  taskCreateSync "supervisor", 0.02, bSupervisor, supervisor()
  delay(1)
  taskKill("supervisor")
end
""", globals_=["bool bSupervisor", "num nRuns"], programs={"supervisor": {"code": """begin
  while true
    nRuns = nRuns + 1
    delay(0)
  endWhile
end
"""}})
    assert r.end_reason == "ended", r.diagnostics
    assert 49 <= gv(r, "nRuns") <= 51
    assert gv(r, "bSupervisor") is False


def test_5_6_overrun(tmp_path):
    # a run longer than the period: the next one is cancelled and bOverrun is true at the
    # start of the following one
    r = sim(tmp_path, """begin
  taskCreateSync "slow", 0.004, bOver, slow()
  delay(0.1)
  taskKill("slow")
end
""", globals_=["bool bOver", "num nRuns", "num nSeen"], programs={"slow": {"locals": ["num i"], "code": """begin
  while true
    nRuns = nRuns + 1
    if bOver
      nSeen = nSeen + 1
    endIf
    for i = 1 to 1500
    endFor
    delay(0)
  endWhile
end
"""}})
    assert "R005" in codes(r)
    assert gv(r, "nSeen") >= 1
    assert gv(r, "nRuns") < 25 + 1  # every other period was cancelled (0.1 s / 4 ms = 25)


SYNCHRO = """begin
  n = n + 1
  // Synchronisation de tâches en attente d'instructions
  // vérifiez que toutes les tâches sont en attente ici pour reprendre l'opération
  wait((n==nN) or (bSynch==true))
  bSynch = true
  n = n - 1
  // Libération de tâches en attente d'instructions
  // vérifiez que toutes les tâches ont repris pour supprimer le contexte de synchronisation
  wait((n==0) or (bSynch == false))
  bSynch = false
end
"""


def test_5_8_synchronisation_example(tmp_path):
    # synchro(num& n, bool& bSynch, num nN) called in each of the nN tasks: nobody goes on
    # before the slowest has arrived; used twice in a row
    r = sim(tmp_path, """begin
  n = 0
  bSynch = false
  taskCreate "fast", 10, worker("fast", 0.1)
  taskCreate "mid", 10, worker("mid", 0.7)
  taskCreate "slow", 10, worker("slow", 1.5)
end
""", globals_=["num n", "bool bSynch"], programs={
        "synchro": {"params": ["num& n", "bool& bSynch", "num nN"], "code": SYNCHRO},
        "worker": {"params": ["string sName", "num nDelay"], "code": """begin
  delay(nDelay)
  call synchro(n, bSynch, 3)
  putln(sName + "1")
  delay(2 - nDelay)
  call synchro(n, bSynch, 3)
  putln(sName + "2")
end
"""}})
    assert r.end_reason == "ended", r.diagnostics
    first = [(e[0], e[3]) for e in r.transcript if e[3].endswith("1")]
    second = [(e[0], e[3]) for e in r.transcript if e[3].endswith("2")]
    assert sorted(t for _, t in first) == ["fast1", "mid1", "slow1"]
    assert min(t for t, _ in first) >= 1_500_000 and max(t for t, _ in first) < 1_520_000
    assert sorted(t for _, t in second) == ["fast2", "mid2", "slow2"]
    assert min(t for t, _ in second) >= max(t for t, _ in first)
    assert gv(r, "n") == 0 and gv(r, "bSynch") is False


def test_5_9_mutex_example(tmp_path):
    # "Cet affichage de programme (num c) remplit l'écran des mêmes caractères, en vérifiant
    # qu'aucune autre tâche n'écrit sur l'écran en même temps". The printed code closes two
    # endFor for one for (OCR lost the "for x=0 to 39" line): the intended double loop is run.
    display = """begin
  // vérifiez qu'une seule tâche accède à l'écran à la fois
  setMutex (bEcran)
  c=c%10
  // remplissez l'écran de caractères
  for x=0 to 39
    for y=0 to 13
      gotoxy (x,y)
      put (c)
    endFor
  endFor
  // attente de l'actualisation de l'écran
  delay (0.2)
  // laissez les autres tâches accéder à l'écran
  bEcran=false
end
"""
    r = sim(tmp_path, """begin
  bEcran = false
  taskCreate "t1", 10, affichage(1)
  taskCreate "t2", 10, affichage(2)
  taskCreate "t3", 10, affichage(13)
end
""", globals_=["bool bEcran"], programs={"affichage": {"params": ["num c"], "locals": ["num x", "num y"],
                                                       "code": display}})
    assert r.end_reason == "ended", r.diagnostics
    seq = [e[1] for e in r.transcript if e[2] == "put"]
    assert seq == ["t1"] * 560 + ["t2"] * 560 + ["t3"] * 560  # never two tasks at once
    assert r.screen["lines"] == ["3" * 40] * 14
    assert r.transcript[-1][3] == "3"


def test_5_10_tasksuspend_taskresume_taskkill(tmp_path):
    # taskSuspend of a STOPPED task: no effect; taskResume of a task that is not STOPPED: no
    # effect; taskKill: the task is no longer in the system (no effect when there is none)
    r = sim(tmp_path, """begin
  taskCreate "worker", 10, count()
  delay(0.1)
  taskSuspend("worker")
  n[0] = taskStatus("worker")
  n[1] = nCount
  taskSuspend("worker")
  delay(0.1)
  n[2] = nCount
  taskResume("worker", 0)
  n[3] = taskStatus("worker")
  taskResume("worker", 0)
  delay(0.1)
  n[4] = nCount
  taskKill("worker")
  n[5] = taskStatus("worker")
  taskKill("worker")
  taskKill("nobody")
end
""", globals_=["num n[6]", "num nCount"], programs={"count": {"code": """begin
  while true
    nCount = nCount + 1
    delay(0.01)
  endWhile
end
"""}})
    assert r.end_reason == "ended", r.diagnostics
    n = gv(r, "n")
    assert n[0] == 0 and n[1] == n[2] and n[3] == 1 and n[4] > n[2] and n[5] == -1


@pytest.mark.parametrize("call", ['taskSuspend("nobody")', 'taskResume("nobody", 0)'])
def test_5_10_unknown_task_is_error_30(tmp_path, call):
    r = sim(tmp_path, f"begin\n  {call}\nend\n")
    assert errors(r) == [30]


RESUME_WORKER = """begin
  sTrace = sTrace + "a"
  sTrace = sTrace + "b"
  nX = 1 / nZero
  sTrace = sTrace + "d"
  sTrace = sTrace + "e"
end
"""


@pytest.mark.parametrize("jump,trace,err", [
    (0, "ab", [10, 10]),          # the failing line again: it fails again
    (1, "abde", [10]),            # the next line
    (2, "abe", [10]),             # two lines after
    (3, "ab", [10]),              # the end of the program
    (-1, "abbde", [10]),          # one line before (nZero is set to 1 before resuming)
    (-2, "ababde", [10]),
    (-3, "ab", [10, 90]),         # before the first line: error 90 in the caller
    (4, "ab", [10, 90]),          # beyond the end: error 90
])
def test_5_10_taskresume_jump_after_error(tmp_path, jump, trace, err):
    # "reprend l'exécution de la tâche sNom sur la ligne située à nSaut lignes d'instructions
    # avant ou après la ligne courante ... erreur s'il n'y a pas de ligne d'instruction à
    # l'endroit du nSaut spécifié"
    fix = "nZero = 1\n  " if jump < 0 else ""
    r = sim(tmp_path, f"""begin
  taskCreate "worker", 10, worker()
  wait(taskStatus("worker") == 10)
  {fix}taskResume("worker", {jump})
  delay(0.1)
end
""", globals_=["string sTrace", "num nX", "num nZero"], programs={"worker": {"code": RESUME_WORKER}})
    assert gv(r, "sTrace") == trace
    assert errors(r) == err
    if err[-1] == 90:
        assert next(d for d in r.diagnostics if d.error == 90).task == "Example~"


def test_5_10_taskresume_jump_in_nested_sequences(tmp_path):
    # a structure (if, while, for...) counts as one instruction of its sequence; jumps stay in
    # the sequence of the line where the task stopped
    r = sim(tmp_path, """begin
  taskCreate "worker", 10, worker()
  wait(taskStatus("worker") == 20)
  taskResume("worker", -1)
  wait(taskStatus("worker") == 20)
  taskResume("worker", 2)
  wait(taskStatus("worker") == -1)
end
""", globals_=["string sTrace", "num nArr[2]", "num i"], programs={"worker": {"code": """begin
  for i = 0 to 1
    sTrace = sTrace + "<"
    if i == 1
      sTrace = sTrace + "i"
      nArr[5] = 1
      sTrace = sTrace + "x"
    endIf
    sTrace = sTrace + ">"
  endFor
  sTrace = sTrace + "."
end
"""}})
    assert r.end_reason == "ended", r.diagnostics
    # first error at nArr[5]: -1 goes back to 'sTrace + "i"'; second error: +2 is the end of
    # the if's sequence, so the loop goes on after the if
    assert gv(r, "sTrace") == "<><ii>."


def test_5_10_taskresume_jump_after_suspend(tmp_path):
    r = sim(tmp_path, """begin
  taskCreate "worker", 10, worker()
  delay(0.5)
  taskSuspend("worker")
  taskResume("worker", 2)
  delay(0.1)
  taskSuspend("worker")
  taskResume("worker", -3)
  wait(taskStatus("worker") == -1)
  taskCreate "worker", 10, worker()
  delay(0.5)
  taskSuspend("worker")
  taskResume("worker", 9)
end
""", globals_=["string sTrace"], programs={"worker": {"code": """begin
  sTrace = sTrace + "a"
  delay(1)
  sTrace = sTrace + "b"
  sTrace = sTrace + "c"
  delay(1)
  sTrace = sTrace + "d"
end
"""}}, duration=10)
    # suspended in the first delay: +2 goes to "c"; suspended in the second delay: -3 goes back
    # to "b"
    assert gv(r, "sTrace").startswith("acbcd")
    assert errors(r) == [90]


def test_5_10_help_example(tmp_path):
    # "Ce programme vérifie s'il y a une erreur dans la tâche "robot" et affiche le code d'erreur"
    r = sim(tmp_path, """begin
  taskCreate "robot", 10, robot()
  delay(0.1)
  nCodeErreur=taskStatus ("robot")
  if (nCodeErreur > 1)
    gotoxy(0,12)
    put(help(nCodeErreur))
  endif
end
""", globals_=["num nCodeErreur", "num nArr[3]"], programs={"robot": {"code": "begin\n  nArr[3] = 1\nend\n"}})
    assert gv(r, "nCodeErreur") == 20
    assert r.screen["lines"][12] == "array index beyond the size of the array"


def test_5_10_taskstatus_table(tmp_path):
    # -1 no such task (or created by another library), 0 suspended, 1 running, else the error code
    r = sim(tmp_path, """begin
  n[0] = taskStatus("nobody")
  taskCreate "run", 10, forever()
  taskCreate "susp", 10, forever()
  taskCreate "err", 10, fails()
  taskSuspend("susp")
  delay(0.1)
  n[1] = taskStatus("run")
  n[2] = taskStatus("susp")
  n[3] = taskStatus("err")
  n[4] = taskStatus("Example~")
  taskKill("run")
  taskKill("susp")
  taskKill("err")
end
""", globals_=["num n[5]"], programs={"forever": {"code": "begin\n  while true\n    delay(0.01)\n  endWhile\nend\n"},
                                      "fails": {"code": "begin\n  n[0] = ln(-1)\nend\n"}})
    assert gv(r, "n") == [-1, 1, 0, 11, 1]


def test_5_10_taskcreate_example(tmp_path):
    r = sim(tmp_path, """begin
  // lancer une nouvelle tâche pour lire un message
  taskCreate "t1", 10, read(sMessage)
  // attente de la fin de la tâche t1
  wait(taskStatus("t1") == -1)
  // Utiliser le message
  putln(sMessage)
end
""", globals_=["string sMessage", "sio siLine"], links={"siLine": "Serial0"},
        programs={"read": {"params": ["string& sText"], "code": "begin\n  sText = siLine\nend\n"}},
        scenario='[[serial]]\nsio = "siLine"\nat = 1.0\nsend = "bonjour"\n')
    assert out(r) == ["bonjour"]
    assert r.end_reason == "ended"


@pytest.mark.parametrize("call,code", [('taskCreate "bad name", 10, idle()', 29),
                                       ('taskCreate "a23456789012345x", 10, idle()', 29),
                                       ('taskCreate "t", 0, idle()', 70), ('taskCreate "t", 101, idle()', 70),
                                       ('taskCreate "t", 10, idle()\n  taskCreate "t", 10, idle()', 31),
                                       (('taskCreateSync "s1", 0.004, bO, idle()\n  taskCreateSync "s2", 0.008, bO, idle()'
                                         '\n  taskCreateSync "s3", 0.012, bO, idle()'), 32)])
def test_5_10_taskcreate_errors(tmp_path, call, code):
    r = sim(tmp_path, f"begin\n  {call}\nend\n", globals_=["bool bO"],
            programs={"idle": {"code": "begin\n  delay(0.01)\nend\n"}}, check_lint=False)
    assert errors(r) == [code]


def test_5_10_wait(tmp_path):
    # "Si bCondition est true lors de la première évaluation, l'exécution se poursuit
    # immédiatement sur la même tâche (il n'y a pas séquencement de la tâche suivante)"
    r = sim(tmp_path, """begin
  taskCreate "other", 50, other()
  sTrace = sTrace + "1"
  wait(true)
  sTrace = sTrace + "2"
  wait(bGo)
  sTrace = sTrace + "3"
end
""", globals_=["string sTrace", "bool bGo"], programs={"other": {"code": """begin
  sTrace = sTrace + "o"
  bGo = true
end
"""}})
    assert gv(r, "sTrace") == "12o3"


def test_5_10_clock_example(tmp_path):
    # the time between two instructions with clock() (millisecond precision)
    r = sim(tmp_path, """begin
  nDebut=clock()
  delay(0.25)
  nDelay = clock() -nDebut
end
""", globals_=["num nDebut", "num nDelay"])
    assert gv(r, "nDelay") == pytest.approx(0.25, abs=0.0045)


@pytest.mark.parametrize("signal_at,popup", [(5.0, False), (25.0, True)])
def test_5_10_watch_example(tmp_path, signal_at, popup):
    # "Ce programme attend un signal et affiche un message d'erreur après 20 s" (the printed
    # "if (watch (diSignal==true, 20) == false" misses a closing parenthesis)
    r = sim(tmp_path, """begin
  if (watch (diSignal==true, 20) == false)
    popUpMsg ("Erreur : en attente de signal")
    wait(diSignal==true)
  endIf
  nEnd = clock()
end
""", globals_=["dio diSignal", "num nEnd"], links={"diSignal": "in0"},
        scenario=f"[[events]]\nat = {signal_at}\nset = {{ diSignal = true }}\n", duration=60)
    assert r.end_reason == "ended", r.diagnostics
    assert gv(r, "nEnd") == pytest.approx(signal_at, abs=0.005)
    popups = [e for e in r.transcript if e[2] == "popUpMsg"]
    assert bool(popups) is popup
    if popup:
        assert popups[0][0] == pytest.approx(20e6, abs=5000)


# ---- chapter 6: libraries -----------------------------------------------------------------------


def _article(tmp_path, name, text):
    return make_library(tmp_path, name, globals_=["string sNom", "num nInit"], values={"sNom": text},
                        programs={"init": {"code": "begin\n  nInit = nInit + 1\nend\n"}})


def test_6_4_content_example(tmp_path):
    # load "article_7" under "article", show article:sNom as the title, call article:init();
    # using the library before libLoad is error 80
    _article(tmp_path, "article_7", "Article sept")
    folder = build(tmp_path, """begin
  bBefore = isDefined(article:sNom)
  // Charger la librairie "article_7" sous l'identifiant"article"
  nCode = article:libLoad("article_7")
  // Afficher comme titre le contenu de la variable 'sNom' de la librairie article_7
  title(article:sNom)
  // Appeler le programme init() pour l'article en cours
  call article:init()
  nInit = article:nInit
end
""", globals_=["num nCode", "num nInit", "bool bBefore"])
    add_libraries(folder, {"article": "Disk://article_7"})
    r = run_folder(folder)
    assert r.end_reason == "ended", r.diagnostics
    assert (gv(r, "bBefore"), gv(r, "nCode"), gv(r, "nInit")) == (False, 0, 1)
    assert r.screen["title"] == "Article sept"
    folder = build(tmp_path / "early", "begin\n  title(article:sNom)\nend\n")
    add_libraries(folder, {"article": "Disk://article_7"})
    _article(tmp_path / "early", "article_7", "x")
    assert errors(run_folder(folder)) == [80]


def test_6_6_shared_library_example(tmp_path):
    # "Dans l'exemple ci-dessous, lib1 et lib2 utilisent la même variable en mémoire"
    make_library(tmp_path, "appData", globals_=["string sText"])
    folder = build(tmp_path, """begin
  lib1:libLoad("appData")
  lib1:sText = "lib1"
  lib2:libLoad("appData")
  // Le changement de lib2:sText s'applique aussi à lib1:sText dans ce cas
  lib2:sText = "lib2"
  sSeen = lib1:sText
end
""", globals_=["string sSeen"])
    add_libraries(folder, {"lib1": "Disk://appData", "lib2": "Disk://appData"})
    r = run_folder(folder)
    assert gv(r, "sSeen") == "lib2"


def test_6_6_path_examples(tmp_path):
    # "article_1" is "Disk://article_1"; libSave to a USB device; "./defaultArticle" is in the
    # current application's folder. Nothing is written to the user's files.
    _article(tmp_path, "article_1", "un")
    folder = build(tmp_path, """begin
  // charger la librairie "article_1" sur le disque équivaut à "Disk://article_1"
  n[0] = article:libLoad("article_1")
  s[0] = article:libPath()
  s[1] = article:sNom
  // Sauvegarder la librairie sur un périphérique USB
  n[1] = article:libSave ("USB0://articles/article_1")
  // Charger l'article par défaut défini dans l'application courante
  n[2] = article:libLoad("./defaultArticle")
  s[2] = article:sNom
  n[3] = article:libLoad("USB0://articles/article_1")
  s[3] = article:libPath()
  s[4] = libPath()
end
""", globals_=["num n[4]", "string s[5]"])
    _article(folder, "defaultArticle", "défaut")
    add_libraries(folder, {"article": "Disk://article_1"})
    r = run_folder(folder)
    assert r.end_reason == "ended", r.diagnostics
    assert gv(r, "n") == [0, 0, 0, 0]
    assert gv(r, "s") == ["Disk://article_1", "un", "défaut", "USB0://articles/article_1", "Disk://Example"]
    assert not (tmp_path / "articles").exists()


def test_6_6_error_codes(tmp_path):
    # the codes of 6.6 ("ne génèrent jamais d'erreur d'exécution")
    _article(tmp_path, "article_1", "un")
    make_library(tmp_path, "other", globals_=["num nZ"])
    make_library(tmp_path, "broken", globals_=["num nZ"], programs={"bad": {"code": "begin\n  nZ = = 1\nend\n"}})
    make_library(tmp_path, "busy", globals_=["num nZ"], programs={"spin": {"code": "begin\n  while true\n    delay(0.1)\n"
                                                                                   "  endWhile\nend\n"},
                                                                   "go": {"code": 'begin\n  taskCreate "spin", 10, spin()\nend\n'}})
    folder = build(tmp_path, """begin
  n[0] = article:libSave()
  n[1] = article:libLoad("other")
  n[2] = article:libLoad("Foo://article_1")
  n[3] = article:libLoad("Disk://../../article_1")
  n[4] = article:libLoad("Disk://bad name!")
  n[5] = article:libLoad("nowhere")
  n[6] = article:libLoad("broken")
  n[7] = article:libLoad("article_1")
  n[8] = article:libSave("Disk://article_1")
  n[9] = article:libDelete("Disk://nowhere")
  n[10] = busy:libLoad("busy")
  call busy:go()
  n[11] = busy:libLoad("busy")
end
""", globals_=["num n[12]"])
    add_libraries(folder, {"article": "Disk://article_1", "busy": "Disk://busy"})
    r = run_folder(folder, check_lint=False)
    assert r.end_reason in ("ended", "duration"), r.diagnostics
    assert gv(r, "n") == [10, 11, 20, 21, 22, 39, 12, 0, 31, 0, 0, 14]
    assert not errors(r)


LIBEXIST_VERSION = LIB_VERSION_ISDEFINED.replace('(isDefined(part:sVersion)==false)', '(part:libExist("sVersion")==false)')


@pytest.mark.parametrize("path,code,version", [("PartV1", 11, "v1.0"), ("PartV2", 0, "v2.0")])
def test_6_7_libexist_version_example(tmp_path, path, code, version):
    _part_libraries(tmp_path)
    folder = build(tmp_path, LIBEXIST_VERSION, globals_=["num nLoadCode", "string sPartPath", "string sLibVersion"],
                   values={"sPartPath": path})
    add_libraries(folder, {"part": "Disk://PartV2"})
    r = run_folder(folder)
    assert gv(r, "nLoadCode") == code
    assert gv(r, "sLibVersion") == version


@pytest.mark.parametrize("lib,called", [("ProtoA", 1), ("ProtoB", 0)])
def test_6_7_libexist_program_example(tmp_path, lib, called):
    # "Ce programme appelle le programme "init" dans la librairie "protocol", si elle existe"
    make_library(tmp_path, "ProtoA", globals_=["num nInit"], programs={"init": {"code": "begin\n  nInit = 1\nend\n"}})
    make_library(tmp_path, "ProtoB", globals_=["num nInit"], programs={"other": {"code": "begin\nend\n"}})
    folder = build(tmp_path, f"""begin
  protocol:libLoad("{lib}")
  b[0] = protocol:libExist("init()")
  b[1] = protocol:libExist("init")
  b[2] = protocol:libExist("nInit")
  if(protocol:libExist("init()")==true)
    call protocol:init()
  endif
  nCalled = protocol:nInit
end
""", globals_=["num nCalled", "bool b[3]"])
    add_libraries(folder, {"protocol": "Disk://ProtoA"})
    r = run_folder(folder)
    assert r.end_reason == "ended", r.diagnostics
    assert gv(r, "nCalled") == called
    assert gv(r, "b") == [bool(called), False, True]


def test_6_7_liblist(tmp_path):
    # every element is first set to ""; the list ends at the first "" ; true when complete; a
    # global array grows as needed
    for name in ("Alpha", "beta", "Gamma"):
        make_library(tmp_path / "usr", name, globals_=["num nX"])
    folder = build(tmp_path / "usr", """begin
  sSmall[2] = "old"
  b[0] = libList("Disk://", sSmall)
  b[1] = libList("Disk://", sGrow)
  b[2] = libList("Disk://", sLocal)
  nLocal = size(sLocal)
  sLast = sLocal[1]
  n = lib:libLoad("Alpha")
  lib:libSave("Disk://saved/Delta")
  b[3] = libList("Disk://saved", sGrow2)
end
""", globals_=["string sSmall[5]", "string sGrow[1]", "string sGrow2[1]", "bool b[4]", "num nLocal", "string sLast",
               "num n"], locals_=["string sLocal[2]"])
    add_libraries(folder, {"lib": "Disk://Alpha"})
    r = run_folder(folder)
    assert r.end_reason == "ended", r.diagnostics
    assert gv(r, "sSmall") == ["Alpha", "beta", "Example", "Gamma", ""]
    assert gv(r, "sGrow") == ["Alpha", "beta", "Example", "Gamma"]
    assert gv(r, "b") == [True, True, False, True]
    assert gv(r, "nLocal") == 2 and gv(r, "sLast") == "beta"
    assert gv(r, "sGrow2") == "Delta"


def test_6_7_libdelete(tmp_path):
    # 0 when the library does not exist or was deleted; then it cannot be loaded (39)
    make_library(tmp_path, "Lib", globals_=["num nX"])
    folder = build(tmp_path, """begin
  n[0] = lib:libLoad("Lib")
  n[1] = lib:libSave("Disk://Copy")
  n[2] = libDelete("Disk://Copy")
  n[3] = libDelete("Disk://Copy")
  n[4] = lib:libLoad("Disk://Copy")
  n[5] = lib:libSave("Disk://Copy")
  n[6] = lib:libLoad("Disk://Copy")
end
""", globals_=["num n[7]"])
    add_libraries(folder, {"lib": "Disk://Lib"})
    r = run_folder(folder)
    assert gv(r, "n") == [0, 0, 0, 0, 39, 0, 0]
    assert not (tmp_path / "Copy").exists()


# ---- chapter 7: user types ----------------------------------------------------------------------


def test_7_user_type_fields_and_copy(tmp_path):
    # 7.2: the public globals of the type application are the fields, with their values as
    # defaults (private ones are not fields); 7.3: field containers can change size
    # (insert/delete/append/resize); a new element gets the type's defaults; '=' copies
    make_library(tmp_path, "PartType", globals_=["string sRef", "num nDims[3]", 'num nTags[""]', "private num nRev"],
                 values={"sRef": "PRT-0"})
    folder = build(tmp_path, """begin
  sRef = pA.sRef
  nDefault = pA.nDims[0] + pA.nDims[1] + pA.nDims[2]
  pA.sRef = "A"
  append(pA.nDims)
  pA.nDims[3] = 7
  insert(pA.nDims[0])
  delete(pA.nDims[1])
  resize(pA.nDims, 1, 5)
  pA.nTags["x"] = 1
  pB = pA
  pA.sRef = "changed"
  pA.nDims[3] = -1
  append(pA.nDims)
  nSizeB = size(pB.nDims)
  nSizeA = size(pA.nDims)
  sRefB = pB.sRef
  nB3 = pB.nDims[3]
  nTagB = pB.nTags["x"]
  append(pArr)
  sNewRef = pArr[1].sRef
end
""", globals_=["Part pA", "Part pB", "Part pArr[1]", "string sRef", "num nDefault", "num nSizeA", "num nSizeB",
               "string sRefB", "num nB3", "num nTagB", "string sNewRef"])
    dims = (tmp_path / "PartType" / "PartType.dtx")
    dims.write_text(dims.read_text(encoding="utf-8").replace(
        'name="nDims" access="public" xsi:type="array" type="num" size="3" />',
        'name="nDims" access="public" xsi:type="array" type="num" size="3"><Value key="0" value="100" />'
        '<Value key="1" value="60" /><Value key="2" value="40" /></Data>'), encoding="utf-8")
    pjx = folder / "Example.pjx"
    pjx.write_text(pjx.read_text(encoding="utf-8").replace(
        "<Libraries />", '<Libraries />\n  <Types>\n    <Type name="Part" path="Disk://PartType" />\n  </Types>'),
        encoding="utf-8")
    r = run_folder(folder)
    assert r.end_reason == "ended", r.diagnostics
    assert gv(r, "sRef") == "PRT-0" and gv(r, "nDefault") == 200
    assert gv(r, "nSizeB") == 5 and gv(r, "nSizeA") == 6
    assert gv(r, "sRefB") == "A" and gv(r, "nB3") == 7 and gv(r, "nTagB") == 1
    assert gv(r, "sNewRef") == "PRT-0"
    assert set(gv(r, "pA")) == {"sRef", "nDims", "nTags"}
    assert gv(r, "pB")["nDims"] == [0, 60, 40, 7, 0]


# ---- chapter 8: robot control ---------------------------------------------------------------------


ENABLE_POWER = """begin
  // Met la puissance et attend qu'elle soit installée
  enablePower()
  if(watch(isPowered(), 5) == false)
    putln("Impossible d'activer l'alimentation du bras")
  endif
  nEnd = clock()
end
"""


@pytest.mark.parametrize("controller,powered", [("", True), ("working_mode = 3\n", False), ("es_status = 2\n", False)])
def test_8_1_enablepower_example(tmp_path, controller, powered):
    # in remote mode the arm is powered (after the scenario's power_delay, 0.5 s by default);
    # in local, manual or test mode enablePower() has no effect but logs a message. (The
    # printed example uses println, a typo of putln.)
    # (a run starts with the arm powered; this example is about the power coming on)
    r = sim(tmp_path, ENABLE_POWER, globals_=["num nEnd"], scenario="[controller]\npowered = false\n" + controller)
    if powered:
        assert out(r) == [] and gv(r, "nEnd") == pytest.approx(0.5, abs=0.005)
    else:
        assert out(r) == ["Impossible d'activer l'alimentation du bras"]
        assert gv(r, "nEnd") == pytest.approx(5.0, abs=0.005)
        assert any(e[2] == "logMsg" for e in r.transcript)


def test_8_1_power_state(tmp_path):
    # isPowered() is false while the power comes; disablePower() cuts it and waits
    r = sim(tmp_path, """begin
  b[0] = isPowered()
  enablePower()
  b[1] = isPowered()
  wait(isPowered())
  b[2] = isPowered()
  disablePower()
  b[3] = isPowered()
  b[4] = isCalibrated()
end
""", globals_=["bool b[5]"], scenario="[controller]\npowered = false\n")
    assert gv(r, "b") == [False, False, True, False, True]
    r = sim(tmp_path / "uncal", "begin\n  bC = isCalibrated()\nend\n", globals_=["bool bC"],
            scenario="[controller]\ncalibrated = false\n")
    assert gv(r, "bC") is False


@pytest.mark.parametrize("mode,state", [(0, 0), (1, 2), (2, 3), (3, 1), (4, 2)])
def test_8_1_workingmode(tmp_path, mode, state):
    r = sim(tmp_path, "begin\n  nMode = workingMode(nState)\n  nMode2 = workingMode()\nend\n",
            globals_=["num nMode", "num nMode2", "num nState"],
            scenario=f"[controller]\nworking_mode = {mode}\nworking_state = {state}\n")
    assert (gv(r, "nMode"), gv(r, "nMode2"), gv(r, "nState")) == (mode, mode, state)


def test_8_1_esstatus_safetyfault(tmp_path):
    r = sim(tmp_path, """begin
  n[0] = esStatus()
  b[0] = safetyFault(sSignal)
  delay(2)
  n[1] = esStatus()
  b[1] = safetyFault(sSignal)
end
""", globals_=["num n[2]", "bool b[2]", "string sSignal"],
        scenario='[controller]\nchanges = [ { at = 1.0, es_status = 2, safety_fault = "ESTOP1" } ]\n')
    assert gv(r, "n") == [0, 2]
    assert gv(r, "b") == [False, True]
    assert gv(r, "sSignal") == "ESTOP1"


@pytest.mark.parametrize("controller,speed,code,after", [
    ("", 50, 0, 50), ("", 120, -3, 100), ("working_mode = 3\n", 50, -1, 100),
    ("monitor_speed = 20\noperator_speed = true\n", 50, -2, 20), ("monitor_speed = 20\noperator_speed = true\n", 10, 0, 10),
])
def test_8_1_setmonitorspeed(tmp_path, controller, speed, code, after):
    # 0 changed; -1 not in remote mode; -2 controlled by the operator (it can always be
    # lowered); -3 not in [0, 100]
    r = sim(tmp_path, f"begin\n  nR = setMonitorSpeed({speed})\n  nS = getMonitorSpeed()\nend\n",
            globals_=["num nR", "num nS"], scenario="[controller]\n" + controller)
    assert (gv(r, "nR"), gv(r, "nS")) == (code, after)


@pytest.mark.parametrize("versions,message", [("", True), ('versions = { compliance = "enabled" }\n', False),
                                              ('versions = { compliance = "demo" }\n', True)])
def test_8_1_getversion_example(tmp_path, versions, message):
    # The French example compares with "activé", a translation of the value "enabled" that the
    # table gives: "enabled" is used
    r = sim(tmp_path, """begin
  if getVersion ("compliance") != "enabled"
    putln ("Pas de licence de compliance sur le contrôleur")
  endif
  sVal3 = getVersion("VAL 3")
  sArm = getVersion("ArmType")
end
""", globals_=["string sVal3", "string sArm"],
        scenario='[controller]\n' + versions.replace("{ ", '{ ArmType = "tx2-60", ') if versions else
        '[controller]\nversions = { ArmType = "tx2-60" }\n')
    assert (out(r) == ["Pas de licence de compliance sur le contrôleur"]) is message
    assert gv(r, "sVal3").startswith("s7") and gv(r, "sArm") == "tx2-60"


# ---- 12.1: runtime error codes -------------------------------------------------------------------


ERRORS = [
    (10, "nX = 1 / nZero"), (11, "nX = sqrt(-1)"), (20, "nX = nArr[2]"), (21, "nX = nArr[-1]"),
    (29, 'taskCreate "", 10, idle()'), (30, 'taskSuspend("nobody")'),
    (31, 'taskCreate "dup", 10, idle()\n  taskCreate "dup", 10, idle()'),
    (32, ('taskCreateSync "s1", 0.004, bO, idle()\n  taskCreateSync "s2", 0.008, bO, idle()\n'
          '  taskCreateSync "s3", 0.012, bO, idle()')),
    (40, "resize(nArr, 1, 10000)"), (41, "call deep()"), (70, 'sX = left("abc", -1)'),
    (80, "nX = lib:nY"), (90, 'taskCreate "t", 10, idle()\n  taskSuspend("t")\n  taskResume("t", 5)'),
    (122, "diIn = true"), (123, "doNone = true"), (125, 'sioCtrl(siLine, "timeout", 0.1)\n  nX = siLine'),
]


@pytest.mark.parametrize("code,line", ERRORS, ids=[str(e[0]) for e in ERRORS])
def test_12_1_runtime_error_codes(tmp_path, line, code):
    # the task stops with the code; taskStatus() reports it and help() describes it
    folder = build(tmp_path, """begin
  taskCreate "robot", 10, robot()
  wait(taskStatus("robot") != 1)
  nStatus = taskStatus("robot")
  sHelp = help(nStatus)
end
""", globals_=["num nX", "num nZero", "num nArr[2]", "string sX", "bool bO", "dio diIn", "dio doNone", "sio siLine",
               "num nStatus", "string sHelp"], programs={
        "robot": {"code": f"begin\n  {line}\n  delay(10)\nend\n"},
        "idle": {"code": "begin\n  delay(0.1)\nend\n"},
        "deep": {"locals": ["num l_n"], "code": "begin\n  call deep()\nend\n"}}, links={"diIn": "in0", "siLine": "Serial0"})
    add_libraries(folder, {"lib": "Disk://Lib"})
    make_library(tmp_path, "Lib", globals_=["num nY"])
    r = run_folder(folder, scenario="[inputs]\ndiIn = false\n", check_lint=False)
    from val3check.language.runtime_errors import RUNTIME_CODES

    assert gv(r, "nStatus") == code
    assert gv(r, "sHelp") == RUNTIME_CODES[code]
    assert code in errors(r)


# ---- 2.1.3, 2.2.2 - 2.2.4: start, stop, reentrance ----------------------------------------------


def test_2_1_3_application_ends_with_its_last_task(tmp_path):
    # the application stops when its last task ends; then stop() runs. start() can be called
    # like any program (2.2.3); calling stop() does not stop the application (2.2.4)
    r = sim(tmp_path, """begin
  nStarts = nStarts + 1
  if nStarts == 1
    call start()
    call stop()
    taskCreate "late", 10, late()
  endIf
end
""", globals_=["num nStarts", "num nStops"], programs={
        "stop": {"code": 'begin\n  nStops = nStops + 1\n  putln("stop")\nend\n'},
        "late": {"code": 'begin\n  delay(1)\n  putln("late")\nend\n'}})
    assert r.end_reason == "ended"
    assert gv(r, "nStarts") == 2 and gv(r, "nStops") == 2
    assert [(e[1], e[3]) for e in r.transcript] == [("Example~", "stop"), ("late", "late"), ("~Example", "stop")]


def test_2_2_2_reentrance(tmp_path):
    # each call has its own locals: a recursive factorial, and one program run by two tasks
    r = sim(tmp_path, """begin
  call fact(10, nF)
  taskCreate "a", 10, count("a")
  taskCreate "b", 10, count("b")
end
""", globals_=["num nF", "string sTrace"], programs={
        "fact": {"params": ["num x_n", "num& x_r"], "locals": ["num l_sub"], "code": """begin
  if x_n <= 1
    x_r = 1
  else
    call fact(x_n - 1, l_sub)
    x_r = x_n * l_sub
  endIf
end
"""},
        "count": {"params": ["string x_s"], "locals": ["num l_i"], "code": """begin
  for l_i = 1 to 3
    sTrace = sTrace + x_s + toString("", l_i)
    delay(0.01)
  endFor
end
"""}})
    assert gv(r, "nF") == 3628800
    assert gv(r, "sTrace") == "a1b1a2b2a3b3"


def test_2_1_4_2_execution_memory(tmp_path):
    # 5000 bytes per task by default: a deep recursion stops with error 41
    r = sim(tmp_path, "begin\n  call deep(0)\nend\n", globals_=["num nDepth"], programs={
        "deep": {"params": ["num x_n"], "code": "begin\n  nDepth = x_n\n  call deep(x_n + 1)\nend\n"}})
    assert errors(r) == [41]
    assert 50 < gv(r, "nDepth") < 200


def test_program_with_syntax_errors_stops_with_r004(tmp_path):
    # a program that cannot be parsed: the task that runs it stops with R004 where it starts
    # (not with an internal error), and a call of it stops the caller's line the same way
    r = sim(tmp_path, """begin
  taskCreate "t", 10, bad()
  delay(0.1)
  nStatus = taskStatus("t")
  call bad()
end
""", globals_=["num nZ", "num nStatus"], programs={"bad": {"code": "begin\n  nZ = = 1\nend\n"}}, check_lint=False)
    assert gv(r, "nStatus") == 0
    assert codes(r) == ["R004", "R004"]
    assert not errors(r)


def test_4_2_3_keys_reach_the_displayed_screen_only(tmp_path):
    # "une séquence de touches ne peut être lue que par l'écran affiché sur le MCP": get() on a
    # screen that is not displayed waits until userPage() shows it; getKey()/isKeyPressed() of
    # it see nothing (except keys (1) (2) (3), always seen by isKeyPressed)
    r = sim(tmp_path, """begin
  taskCreate "debug", 10, debugPage()
  delay(0.5)
  n[0] = getKey(scDebug)
  b[0] = isKeyPressed(scDebug, 271)
  b[1] = isKeyPressed(scDebug, 281)
  n[1] = get()
  userPage(scDebug)
  wait(n[2] != 0)
end
""", globals_=["screen scDebug", "num n[3]", "bool b[2]"], programs={"debugPage": {"code": """begin
  n[2] = get(scDebug)
end
"""}}, scenario="[[keys]]\nat = 0.4\nkey = 271\nhold = 0.5\n[[keys]]\nat = 0.45\nkey = 281\nhold = 0.5\n"
                 "[[keys]]\nat = 1.0\nkey = 272\n")
    assert r.end_reason == "ended", r.diagnostics
    # (the simulator queues the scenario's keys: the debug page's get() takes the next one, 281,
    # once userPage() shows it)
    assert gv(r, "n") == [-1, 271, 281]
    assert gv(r, "b") == [False, True]


def test_3_6_2_iostatus_aio_description_example(tmp_path):
    # "Ce programme teste un signal et affiche des informations d'erreur si celui-ci ne
    # fonctionne pas" (println: putln)
    r = sim(tmp_path, """begin
  if ioStatus(aiSignal, sDescription, sPath) < 0
    putln("Signal "+sPath+ "en erreur")
    putln("Description :" +sDescription)
  endif
end
""", globals_=["aio aiSignal", "string sDescription", "string sPath"], links={"aiSignal": "Bus\\Slave2\\%IW4"},
        scenario='[io]\naiSignal = { status = -3, description = "capteur de pression" }\n')
    assert out(r) == ["Signal Bus\\Slave2\\%IW4en erreur", "Description :capteur de pression"]


def test_2_2_5_while_example_with_issettled(tmp_path):
    # the arm has not moved: it is settled, the lamp loop does not run (no arm model needed:
    # isSettled() acts on an idle arm, issue 11 item 14)
    r = sim(tmp_path, """begin
  diLampe = false
  while (isSettled() == false)
    diLampe = !diLampe
    delay(0.5)
  endWhile
  diLampe = false
end
""", globals_=["dio diLampe"], links={"diLampe": "lamp"})
    assert codes(r) == [] and r.end_reason == "ended" and r.sim_time_us < 10_000


def test_2_2_5_for_example_moves_the_arm(tmp_path):
    """The for loop of 2.2.5: joint 1 from 90° to -90° by steps of 10°, each move waited for."""
    from val3check.robot import load_robot

    tx = load_robot("TX2-60")
    r = sim(tmp_path, """begin
  for nPos = 90 to -90 step -10
    jDest.j1 = nPos
    movej(jDest, flange, mNomSpeed)
    waitEndMove()
  endFor
  jEnd = herej()
end
""", globals_=["num nPos", "joint jDest", "joint jEnd", "mdesc mNomSpeed"], robot=tx)
    assert codes(r) == [] and r.end_reason == "ended"
    assert gv(r, "jEnd")["j1"] == pytest.approx(-90.0, abs=1e-9)
    v, a = tx.nominal_speeds[0], tx.accelerations[0]

    def bang(d):  # trapezoid or triangle, accel = decel (mdesc at 100 %)
        return d / v + v / a if d >= v * v / a else 2 * (d / a) ** 0.5

    moves = [bang(90.0)] + [bang(10.0)] * 18
    # each waitEndMove() returns at the first 4 ms tick at or after the end of its move
    assert sum(moves) <= r.sim_time_us / 1e6 <= sum(moves) + 19 * 0.004 + 0.004


def test_8_1_getmonitorspeed_example_with_stopmove(tmp_path):
    # 8.1: the first cycles must run at 10 %: stopMove() holds the arm until the operator lowers
    # the monitor speed (here the scenario at 2 s), then restartMove()
    r = sim(tmp_path, """begin
  while true
    if (nCycle < 2)
      if (getMonitorSpeed() > 10)
        stopMove()
        gotoxy(0, 0)
        putln("La vitesse moniteur doit rester à 10% pour le premier cycle")
        wait (getMonitorSpeed() <= 10)
      endif
      restartMove()
    endif
    delay(0)
  endWhile
end
""", globals_=["num nCycle"], duration=3.0, scenario="[controller]\nchanges = [{ at = 2.0, monitor_speed = 10 }]\n")
    assert out(r) == ["La vitesse moniteur doit rester à 10% pour le premier cycle"]
    assert r.end_reason == "duration" and codes(r) == ["R007"]
