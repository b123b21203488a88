"""The package's type stubs (python/jaus/__init__.pyi) are generated from the message
definitions: the committed file must equal what the generator writes now, as the
repository's golden files (UPDATE_GOLDEN=1 rewrites it)."""

import ast
import os
import re

import jaus
from conftest import HERE

STUBS = HERE.parent / "python" / "jaus" / "__init__.pyi"


def test_the_committed_stubs_are_up_to_date():
    text = jaus._jaus._stubs()
    if os.environ.get("UPDATE_GOLDEN") == "1":
        STUBS.write_text(text)
    assert STUBS.read_text() == text, (
        "python/jaus/__init__.pyi is stale: UPDATE_GOLDEN=1 python -m pytest tests/test_stubs.py"
    )


def test_the_stubs_are_python_with_a_typed_class_per_message():
    tree = ast.parse(STUBS.read_text())
    classes = {n.name: n for n in tree.body if isinstance(n, ast.ClassDef)}
    for name in jaus.messages():
        assert name in classes, name
    pose = classes["ReportGlobalPose"]
    attrs = {
        n.target.id: ast.unparse(n.annotation) for n in pose.body if isinstance(n, ast.AnnAssign)
    }
    assert attrs["latitude"] == "Optional[float]"
    assert attrs["time_stamp"] == "Optional[Record]"
    status = {
        n.target.id: ast.unparse(n.annotation)
        for n in classes["ReportComponentStatus"].body
        if isinstance(n, ast.AnnAssign)
    }
    assert status["primary_status_code"].startswith("Union[Literal['Initialize', ")
    # Client.query is typed per query with its report.
    text = STUBS.read_text()
    assert re.search(r"def query\(self, dest: Address, message: QueryGlobalPose, .*\) -> ReportGlobalPose: \.\.\.", text)
    assert re.search(r"def watch\(self, dest: Address, query: QueryGlobalPose, .*\) -> Watch\[ReportGlobalPose\]", text)


def test_the_message_classes_exist_at_run_time():
    m = jaus.SetTravelSpeed(speed=2.0)
    assert m == jaus.message("SetTravelSpeed", speed=2.0)
    assert isinstance(m, jaus.SetTravelSpeed) and isinstance(m, jaus.Message)
    assert not isinstance(m, jaus.ReportGlobalPose)
    assert "ReportGlobalPose" in jaus.__all__
