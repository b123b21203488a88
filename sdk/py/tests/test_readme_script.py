"""The README's Python script, as written there, drives the demo vehicle hosted by
`jaus node` to its waypoint: control taken, Resume, the waypoint, each command's
confirmation, pose reports until the vehicle stands at the waypoint."""

import re
import subprocess
import sys

from conftest import ROOT

MARK = "<!-- readme-script -->"


def readme_script():
    """The script under the README's marker (its fenced python block)."""
    text = (ROOT / "README.md").read_text()
    assert MARK in text, "the README lost its Python script"
    block = re.search(r"```python\n(.*?)```", text[text.index(MARK):], re.S)
    assert block, "no ```python block after the README's marker"
    return block.group(1)


def test_the_readme_script_is_short():
    lines = [line for line in readme_script().splitlines() if line.strip()]
    assert len(lines) <= 20, len(lines)


def test_the_readme_script_drives_the_vehicle_to_its_waypoint(vehicle):
    script = readme_script()
    # The README's node binds 127.0.0.1:3794; this test's node a free port.
    assert 'peer="127.0.0.1:3794"' in script
    script = script.replace('peer="127.0.0.1:3794"', f'peer="{vehicle.peer}", bind="127.0.0.1:0"')
    run = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, timeout=90
    )
    assert run.returncode == 0, run.stderr
    lines = run.stdout.splitlines()
    assert lines[-1] == "arrived", run.stdout[-2000:]
    # Our vehicle acknowledges each command.
    for name in ("SetGlobalWaypoint", "SetTravelSpeed"):
        assert f"{name} acknowledged" in lines, run.stdout[-2000:]
    poses = [
        tuple(float(x) for x in re.findall(r"-?\d+\.\d+", line)[:2])
        for line in lines
        if line.startswith("latitude")
    ]
    assert len(poses) >= 3
    # It moved north to the waypoint (29.64369, -82.3549) and stood within 2 m of it
    # (the script's own test: a robot whose driver stops short, as OpenJAUS's, arrives).
    first, last = poses[0], poses[-1]
    assert last[0] - first[0] > 7 / 111_000
    assert abs(last[0] - 29.64369) * 111_000 < 2.0, last
    assert abs(last[1] + 82.3549) * 96_700 < 2.0, last
