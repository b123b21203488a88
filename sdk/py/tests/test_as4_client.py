"""`jaus.As4Client`: an AS-4 client by message name, against the AS-4 component that
`jaus node` presents with `as4:` (the gateway over the demo vehicle, 1.1.1): Core
queries answered, control taken and given back, the component resumed, Mobility queries
answered; a vendor's YAML (`spec=`) names its messages; an unanswered query raises."""
import pytest

import jaus
from conftest import ROOT, RunningNode

GATEWAY = (
    "subsystem: 1\nnode: 1\nnode_name: vehicle\nbind: 127.0.0.1:{port}\n"
    "host: [vehicle]\nas4: {component: 1}\n"
)


@pytest.fixture(scope="module")
def gateway(tmp_path_factory):
    node = RunningNode(
        tmp_path_factory.mktemp("as4"), "gateway", GATEWAY, "'GlobalWaypointDriver'"
    )
    yield node
    node.stop()


def test_queries_control_and_state_by_name(gateway):
    a = jaus.As4Client(gateway.peer, "42.1.7", bind="127.0.0.1:0", timeout=3.0)
    status = a.query("1.1.1", "QueryStatus")
    assert status["message"] == "ReportStatus" and status["from"] == "1.1.1", status
    assert status["fields"]["status"] == "Standby"
    a.take_control("1.1.1", 10)
    assert a.query("1.1.1", "QueryControl")["fields"]["authority_code"] == 10
    a.send("1.1.1", "Resume")
    assert a.query("1.1.1", "QueryStatus")["fields"]["status"] == "Ready"
    pose = a.query("1.1.1", "QueryLocalPose", presence_vector=0x1FF)
    assert pose["message"] == "ReportLocalPose", pose
    a.send("1.1.1", "Standby")
    a.release_control("1.1.1")
    assert a.query("1.1.1", "QueryStatus")["fields"]["status"] == "Standby"


def test_a_vendors_messages_by_name_and_an_unanswered_query(gateway):
    a = jaus.As4Client(
        gateway.peer,
        bind="127.0.0.1:0",
        spec=[str(ROOT / "examples" / "vendor-lamp" / "defs")],
        timeout=0.5,
    )
    with pytest.raises(jaus.ClientError, match="QueryLampLevel to 1.1.1: no answer"):
        a.query("1.1.1", "QueryLampLevel")
    with pytest.raises(jaus.ClientError, match="NoSuchMessage"):
        a.send("1.1.1", "NoSuchMessage")
    with pytest.raises(ValueError, match="expected an AS-4 id"):
        a.send("1.1", "QueryStatus")
