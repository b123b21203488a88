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
