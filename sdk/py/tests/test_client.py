"""jaus.Client against the demo vehicle hosted by `jaus node`: the system tree,
queries, control granted, refused and given back, watches (service connections and
events) ended at the provider, asyncio, and what closing the client ends."""

import asyncio
import gc
import time

import pytest

import jaus
from conftest import RunningNode

GWD = "1.1.45.1"  # the demo vehicle's Global Waypoint Driver
GPS = "1.1.38.1"  # its Global Pose Sensor
POSE = jaus.message("QueryGlobalPose", presence_vector=0x43)  # latitude, longitude, yaw


def client(vehicle, me=None, **kw):
    # bind 127.0.0.1:0: `jaus node` answers any port (OpenJAUS would need 3794).
    return jaus.Client(peer=vehicle.peer, me=me, bind="127.0.0.1:0", **kw)


def events_at(c, provider):
    """The events `provider` serves (Query Events)."""
    return len(c.query(provider, jaus.message("QueryEvents")).events)


def test_the_tree_lists_the_vehicle(vehicle):
    with client(vehicle) as c:
        tree = c.tree()
        components = {
            comp["address"]: comp["name"]
            for s in tree["subsystems"]
            for n in s["nodes"]
            for comp in n["components"]
        }
        assert components[GWD] == "GlobalWaypointDriver"
        assert components[GPS] == "GlobalPoseSensor"
        assert components[c.me] == "jaus Python client"
        assert not c.joined
    with client(vehicle, name="survey station") as c:
        names = {
            comp["address"]: comp["name"]
            for s in c.tree()["subsystems"]
            for n in s["nodes"]
            for comp in n["components"]
        }
        assert names[c.me] == "survey station"


def test_query_returns_the_report(vehicle):
    with client(vehicle) as c:
        pose = c.query(GPS, POSE)
        assert pose.name == "ReportGlobalPose"
        assert abs(pose.latitude - 29.6436) < 1e-3
        assert abs(pose.longitude + 82.3549) < 1e-3
        assert pose.elevation is None  # not asked for by the presence vector
        # A tuple address works too.
        assert c.query((1, 1, 38, 1), POSE).name == "ReportGlobalPose"


def test_an_unanswered_query_names_the_message_and_address(vehicle):
    with client(vehicle) as c:
        t0 = time.monotonic()
        with pytest.raises(jaus.ClientError) as e:
            c.query("1.1.99.1", POSE, timeout=0.5)
        assert time.monotonic() - t0 < 3
        assert e.value.message == "QueryGlobalPose"
        assert e.value.address == "1.1.99.1"
        assert "QueryGlobalPose" in str(e.value) and "1.1.99.1" in str(e.value)
        with pytest.raises(jaus.ClientError, match="not a query"):
            c.query(GPS, jaus.message("Resume"))


def test_a_command_is_acknowledged(vehicle):
    with client(vehicle) as c:
        c.send(GPS, jaus.message("QueryComponentStatus"))  # fire and forget
        with c.control(GWD, authority=10):
            c.send(GWD, jaus.message("SetTravelSpeed", speed=1.0), ack=True)
            c.send(GWD, jaus.message("Standby"), ack=True)


def test_an_unacknowledged_command_says_what_is_known(vehicle):
    with client(vehicle) as c:
        with pytest.raises(jaus.ClientError) as e:
            c.send("1.1.99.1", jaus.message("Standby"), ack=True, timeout=0.5)
        text = str(e.value)
        assert "Standby" in text and "1.1.99.1" in text
        assert "system tree does not list it" in text, text


def test_control_is_granted_refused_and_given_back(vehicle):
    with client(vehicle, me="201.1.40.1") as a, client(vehicle, me="202.1.40.1") as b:
        with a.control(GWD, authority=10) as held:
            assert held.held and held.address == GWD
            with pytest.raises(jaus.ControlRefused) as e:
                with b.control(GWD, authority=5, timeout=3):
                    pass
            assert e.value.response_code == "Rejected"
            assert e.value.address == GWD
            assert e.value.message == "RequestComponentControl"
            assert GWD in str(e.value)
        assert not held.held
        # Given back: b now gets it at its lower authority.
        with b.control(GWD, authority=5) as c:
            assert c.held


def test_a_higher_authority_takes_control_and_the_keeper_asks_again(vehicle):
    with client(vehicle, me="203.1.40.1") as a, client(vehicle, me="204.1.40.1") as b:
        with a.control(GWD, authority=10):
            with b.control(GWD, authority=50):
                # a lost it to b, and keeps asking (refused while b holds it).
                deadline = time.monotonic() + 3
                while a.stats()["control_lost"] < 1 and time.monotonic() < deadline:
                    time.sleep(0.05)
                assert a.stats()["control_lost"] == 1


def test_a_refusal_names_the_response_code(tmp_path):
    # A policy caps subsystem 77's authority at 5: a request at 10 is answered with
    # Confirm Component Control, response code InsufficientAuthority.
    guarded = RunningNode(
        tmp_path,
        "guarded",
        "subsystem: 2\nnode: 1\nbind: 127.0.0.1:{port}\nhost: [vehicle]\n"
        "policy:\n  default: query\n  rules:\n"
        "    - { from: 77.*.*.*, may: command, max_authority: 5 }\n",
        "'GlobalWaypointDriver'",
    )
    try:
        with client(guarded, me="77.1.40.1") as c:
            with pytest.raises(jaus.ControlRefused) as e:
                with c.control("2.1.45.1", authority=10, timeout=3):
                    pass
            assert e.value.response_code == "InsufficientAuthority"
            assert "InsufficientAuthority" in str(e.value)
            with c.control("2.1.45.1", authority=5) as held:
                assert held.held
    finally:
        guarded.stop()


def test_an_event_watch_yields_reports_and_is_cancelled_on_close(vehicle):
    with client(vehicle) as c:
        before = events_at(c, GPS)
        w = c.watch(GPS, POSE)  # every change: an event
        assert events_at(c, GPS) == before + 1
        poses = [p for _, p in zip(range(3), w)]
        assert [p.name for p in poses] == ["ReportGlobalPose"] * 3
        w.close()
        assert w.closed and w.end_reason == "closed"
        assert list(w) == []
        deadline = time.monotonic() + 3
        while events_at(c, GPS) != before and time.monotonic() < deadline:
            time.sleep(0.05)
        assert events_at(c, GPS) == before


def test_a_watch_dropped_by_the_garbage_collector_ends_its_event(vehicle):
    with client(vehicle) as c:
        before = events_at(c, GPS)
        w = c.watch(GPS, POSE)
        assert w.get(timeout=2) is not None
        assert events_at(c, GPS) == before + 1
        del w
        gc.collect()
        deadline = time.monotonic() + 3
        while events_at(c, GPS) != before and time.monotonic() < deadline:
            time.sleep(0.05)
        assert events_at(c, GPS) == before


def test_a_service_connection_watch_stops_when_closed(vehicle):
    with client(vehicle) as c:
        with c.watch(GPS, POSE, periodic_hz=10) as w:
            t0 = time.monotonic()
            poses = [p for _, p in zip(range(5), w)]
            assert len(poses) == 5
            assert time.monotonic() - t0 < 3
            assert poses[0].yaw is not None
        assert w.closed
        # Ended at the provider: no more poses arrive (they would be unclaimed).
        time.sleep(0.5)
        unclaimed = c.stats()["unclaimed"]
        time.sleep(1.0)
        assert c.stats()["unclaimed"] - unclaimed <= 1


def test_a_full_watch_queue_drops_the_oldest_and_counts(vehicle):
    with client(vehicle) as c:
        with c.watch(GPS, POSE, periodic_hz=50, queue=2) as w:
            time.sleep(0.6)
            assert w.dropped > 0
            assert c.stats()["reports_dropped"] >= w.dropped
            assert w.get(timeout=1) is not None


def test_async_watch(vehicle):
    async def main(c):
        got = []
        async with c.watch_async(GPS, POSE, periodic_hz=10) as poses:
            async for pose in poses:
                got.append(pose.latitude)
                if len(got) == 3:
                    break
        assert poses.watch.closed
        return got

    with client(vehicle) as c:
        got = asyncio.run(asyncio.wait_for(main(c), 10))
        assert len(got) == 3 and all(abs(x - 29.6436) < 1e-3 for x in got)


def test_closing_the_client_releases_control_and_ends_watches(vehicle):
    with client(vehicle, me="205.1.40.1") as other:
        before = events_at(other, GPS)
        with client(vehicle, me="206.1.40.1") as c:
            held = c.control(GWD, authority=100)
            held.acquire()
            w = c.watch(GPS, POSE)
            assert events_at(other, GPS) == before + 1
        assert c.closed and w.closed
        with pytest.raises(jaus.ClientError, match="closed"):
            c.query(GPS, POSE)
        # Control given back: the other client gets it at a lower authority.
        with other.control(GWD, authority=1) as mine:
            assert mine.held
        deadline = time.monotonic() + 3
        while events_at(other, GPS) != before and time.monotonic() < deadline:
            time.sleep(0.05)
        assert events_at(other, GPS) == before


def test_nobody_there_is_an_error_saying_so():
    t0 = time.monotonic()
    with pytest.raises(jaus.ClientError, match="no datagram"):
        jaus.Client(peer="127.0.0.1:9", bind="127.0.0.1:0", timeout=0.5)
    assert time.monotonic() - t0 < 4
