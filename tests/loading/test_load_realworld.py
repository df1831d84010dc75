"""Shapes seen in real repositories that the format note does not describe."""

from __future__ import annotations

from val3check.loading import load

from loadhelp import codes, make_app, pgx, pjx, write


def test_two_dimensional_keys_written_with_a_comma(tmp_path):
    body = '<Data name="nM" access="public" xsi:type="array" type="num" size="3 3">\n'
    body += '  <Value key="1,1" value="0.5" />\n  <Value key="2, 0" value="2" />\n</Data>'
    folder = tmp_path / "App"
    make_app(folder, data_body=body)
    ws, diags = load([str(folder)])
    assert codes(diags, "F007") == []
    data = ws.apps[ws.targets[0]].data["nM"]
    assert [v.key for v in data.values] == ["1 1", "2 0"]


def test_s6_byval_false_is_by_reference(tmp_path):
    folder = tmp_path / "Old"
    write(folder / "Old.pjx", """<?xml version="1.0" encoding="utf-8"?>
<project xmlns="ProjectNameSpace">
  <parameters version="s6.8" stackSize="5000" millimeterUnit="true" />
  <programSection><program file="start.pgx" /><program file="stop.pgx" /></programSection>
  <dataSection />
</project>
""")
    for name in ("start", "stop"):
        params = '<param name="nOut" type="num" byVal="false" /><param name="nIn" type="num" byVal="true" />' if name == "start" else ""
        write(folder / f"{name}.pgx", f"""<?xml version="1.0" encoding="utf-8"?>
<programList xmlns="ProgramNameSpace">
  <program name="{name}" public="false">
    <paramSection>{params}</paramSection>
    <localSection />
    <source><code>begin
end</code></source>
  </program>
</programList>
""")
    ws, diags = load([str(folder)])
    params = ws.apps[ws.targets[0]].programs["start"].parameters
    assert [(p.name, p.by_reference) for p in params] == [("nOut", True), ("nIn", False)]


def test_disk_path_found_from_a_type_checked_on_its_own(tmp_path):
    # App/Types/Msg uses Disk://App/Types/Header: checked alone, the disk root is above App,
    # inside the repository (its git top level: the walk up never leaves it).
    (tmp_path / ".git").mkdir()
    app = tmp_path / "App"
    write(app / "Types" / "Header" / "Header.pjx", pjx(programs=()))
    msg = app / "Types" / "Msg"
    write(msg / "Msg.pjx", pjx(programs=(), types=(("Header", "Disk://App/Types/Header/Header.pjx"),)))
    ws, diags = load([str(msg)])
    assert codes(diags, "L002") == []
    ref = ws.apps[ws.targets[0]].types["Header"]
    assert ref.resolved == str(app / "Types" / "Header" / "Header.pjx")


def test_unlisted_program_in_a_subfolder_is_not_an_application(tmp_path):
    folder = tmp_path / "Cell"
    make_app(folder)
    write(folder / "Comm" / "extra.pgx", pgx("extra"))
    write(folder / "orphan.pgx", pgx("orphan"))
    ws, diags = load([str(tmp_path)])
    assert [ws.apps[k].name for k in ws.targets] == ["Cell"]
    found = sorted((d.code, d.path) for d in diags if d.code in ("F009", "F012"))
    assert found == [("F012", str(folder / "Comm" / "extra.pgx")), ("F012", str(folder / "orphan.pgx"))]


def test_unread_listed_files_are_recorded(tmp_path):
    folder = tmp_path / "App"
    make_app(folder, data_body='<Data name="nX" access="public" xsi:type="array" type="num" size="1" />')
    ws, _ = load([str(folder)])
    assert ws.apps[ws.targets[0]].unread == set()
    write(folder / "App.dtx", "<Database")  # malformed: the globals are only partly known
    (folder / "stop.pgx").unlink()
    ws, diags = load([str(folder)])
    assert ws.apps[ws.targets[0]].unread == {"data", "program"}


def test_listed_files_outside_the_application_are_not_read(tmp_path):
    import os

    secret = tmp_path / "secret.txt"
    secret.write_text("root:x:0:0:do not quote me\n")
    folder = tmp_path / "App"
    make_app(folder, programs=("start",))
    pjx = folder / "App.pjx"
    text = pjx.read_text().replace('<Program file="start.pgx" />',
                                   '<Program file="start.pgx" />\n    <Program file="../secret.txt" />\n    <Program file="link.pgx" />')
    pjx.write_text(text)
    os.symlink(secret, folder / "link.pgx")  # a link inside the folder that leads out of it
    ws, diags = load([str(folder)])
    found = [(d.code, d.path) for d in diags]
    assert found == [("F013", str(pjx)), ("F013", str(pjx))]
    assert all("do not quote me" not in d.message for d in diags)
    assert "program" in ws.apps[ws.targets[0]].unread
