"""The arm of the controller tree an application sits in (loading/controller.py)."""

from __future__ import annotations

from val3check.loading.controller import controller_arm, find_arm_cfx

CFX = '<?xml version="1.0" encoding="utf-8"?>\n<Configuration>\n  <Arm>\n    <String name="arm" value="{}" />\n  </Arm>\n</Configuration>\n'


def _tree(root, arm="tx2-60-S1"):
    (root / "usr" / "configs").mkdir(parents=True)
    (root / "usr" / "configs" / "arm.cfx").write_text(CFX.format(arm))
    app = root / "usr" / "usrapp" / "Cell"
    app.mkdir(parents=True)
    return app


def test_arm_of_the_controller_tree(tmp_path):
    app = _tree(tmp_path / "Controller1")
    assert controller_arm(str(app)) == ("tx2-60-S1", str(tmp_path / "Controller1" / "usr" / "configs" / "arm.cfx"))
    nested = app.parent / "Group" / "Sub"
    nested.mkdir(parents=True)
    assert controller_arm(str(nested))[0] == "tx2-60-S1"


def test_no_controller_tree_no_arm(tmp_path):
    # an arm.cfx above an application that is not under usr/usrapp is not its controller's
    (tmp_path / "usr" / "configs").mkdir(parents=True)
    (tmp_path / "usr" / "configs" / "arm.cfx").write_text(CFX.format("ts60-S1"))
    app = tmp_path / "usr" / "apps" / "Cell"
    app.mkdir(parents=True)
    assert find_arm_cfx(str(app)) is None and controller_arm(str(app)) is None


def test_unreadable_or_hostile_arm_cfx_gives_no_arm(tmp_path):
    app = _tree(tmp_path / "C")
    cfx = tmp_path / "C" / "usr" / "configs" / "arm.cfx"
    cfx.write_text('<?xml version="1.0"?>\n<!DOCTYPE x [<!ENTITY e "tx60-S1">]>\n<C><String name="arm" value="&e;"/></C>')
    assert controller_arm(str(app)) is None  # entities are never followed
    cfx.write_text("<C><String name='arm' value='")
    assert controller_arm(str(app)) is None
    cfx.write_text("<C><String name='arm' value='tx60-S1'/></C>")
    assert controller_arm(str(app), max_size=10) is None  # over the size limit
