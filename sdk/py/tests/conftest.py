"""Shared fixtures: the repository's files the tests read."""

import json
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[3]
HERE = pathlib.Path(__file__).resolve().parent


@pytest.fixture(scope="session")
def vectors():
    """The OpenJAUS 3.3 reference vectors (tests/data/openjaus33.jsonl)."""
    path = ROOT / "tests" / "data" / "openjaus33.jsonl"
    return [json.loads(line) for line in path.read_text().splitlines() if line.strip()]


@pytest.fixture(scope="session")
def cli_lines():
    """Packets with the line `jaus decode HEX` printed for each (tests/data/cli_decode.jsonl)."""
    path = HERE / "data" / "cli_decode.jsonl"
    return [json.loads(line) for line in path.read_text().splitlines() if line.strip()]


@pytest.fixture(scope="session")
def vendor_overlay():
    """The vendor-rover example's overlay."""
    return ROOT / "examples" / "vendor-rover" / "defs" / "vendor_rover.yaml"


def jaus_binary():
    """The `jaus` CLI: $JAUS_BIN, else the workspace's debug build (built once if
    missing: CI has built it before the Python step)."""
    import os
    import subprocess

    if os.environ.get("JAUS_BIN"):
        return os.environ["JAUS_BIN"]
    path = ROOT / "target" / "debug" / "jaus"
    if not path.exists():
        subprocess.run(["cargo", "build", "-q", "-p", "jaus-cli"], cwd=ROOT, check=True)
    return str(path)


def free_udp_port():
    """A UDP port of 127.0.0.1 nobody uses now."""
    import socket

    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class RunningNode:
    """A `jaus node` started from a node file; `.peer` is its socket."""

    def __init__(self, tmp, name, yaml_text, ready, seconds=300):
        import subprocess
        import time

        self.port = free_udp_port()
        self.peer = f"127.0.0.1:{self.port}"
        config = tmp / f"{name}.yaml"
        config.write_text(yaml_text.replace("{port}", str(self.port)))
        self.log = tmp / f"{name}.log"
        with open(self.log, "w") as out:
            self.process = subprocess.Popen(
                [jaus_binary(), "node", "--config", str(config), "--seconds", str(seconds)],
                stdout=out,
                stderr=subprocess.STDOUT,
            )
        end = time.monotonic() + 20
        while ready not in self.log.read_text():
            if self.process.poll() is not None or time.monotonic() > end:
                self.stop()
                raise RuntimeError(f"jaus node {name} did not start: {self.log.read_text()}")
            time.sleep(0.05)

    def stop(self):
        if self.process.poll() is None:
            self.process.terminate()
            try:
                self.process.wait(timeout=5)
            except Exception:
                self.process.kill()


VEHICLE = "subsystem: 1\nnode: 1\nnode_name: vehicle\nbind: 127.0.0.1:{port}\nhost: [vehicle]\n"


@pytest.fixture(scope="module")
def vehicle(tmp_path_factory):
    """The demo vehicle hosted by `jaus node` (`host: [vehicle]`) on a free loopback
    port: its global waypoint driver is 1.1.45.1, its global pose sensor 1.1.38.1."""
    node = RunningNode(
        tmp_path_factory.mktemp("vehicle"), "vehicle", VEHICLE, "'GlobalWaypointDriver'"
    )
    yield node
    node.stop()
