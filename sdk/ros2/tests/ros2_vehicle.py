#!/usr/bin/env python3
"""The ROS 2 side of a JAUS vehicle, without ROS: Cyclone DDS (the `cyclonedds` package)
with ROS 2's conventions (topics `rt/<name>`, types `<pkg>::msg::dds_::<Type>_`, plain
CDR). The message types are ros2_robot.py's.

* reads `rt/odom` (nav_msgs/Odometry), `rt/fix` (sensor_msgs/NavSatFix) and
  `rt/jaus/status` (std_msgs/String);
* publishes `rt/cmd_vel` (geometry_msgs/Twist) at 10 Hz while told to drive, and
  `rt/goal_pose` (geometry_msgs/PoseStamped) once when told.

Standard output: one JSON object a line, flushed:
  {"ready": true}
  {"odom": n, "t_ns": wall time taken, "x": m, "y": m, "yaw": rad, "vx": m/s, "wz": rad/s,
   "frame": ..., "child": ...}
  {"fix": n, "lat": deg, "lon": deg, "alt": m, "status": s}
  {"status": text}
  {"cmd_sent": n, "t_ns": wall time, "vx": m/s, "wz": rad/s}
Standard input: `drive VX WZ` publishes that twist at 10 Hz; `silent` stops publishing
(no zero twist: the bridge's watchdog must stop the vehicle); `goal X Y` publishes a
goal in frame odom; EOF ends.
"""

import argparse
import json
import math
import os
import sys
import threading
import time
from dataclasses import dataclass, field

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from cyclonedds.core import Policy, Qos  # noqa: E402
from cyclonedds.domain import DomainParticipant  # noqa: E402
from cyclonedds.idl import IdlStruct  # noqa: E402
from cyclonedds.pub import DataWriter  # noqa: E402
from cyclonedds.sub import DataReader  # noqa: E402
from cyclonedds.topic import Topic  # noqa: E402

from ros2_robot import Header, NavSatFix, Odometry, Pose, Twist, Vector3, say, stamp  # noqa: E402


@dataclass
class PoseStamped(IdlStruct, typename="geometry_msgs::msg::dds_::PoseStamped_"):
    header: Header = field(default_factory=Header)
    pose: Pose = field(default_factory=Pose)


@dataclass
class String(IdlStruct, typename="std_msgs::msg::dds_::String_"):
    data: str = ""


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--domain", type=int, default=0)
    ap.add_argument("--duration", type=float, default=120.0, help="exit after this many s")
    args = ap.parse_args()

    qos = Qos(
        Policy.Reliability.Reliable(max_blocking_time=100_000_000),
        Policy.History.KeepLast(10),
        Policy.Durability.Volatile,
        Policy.DataRepresentation(use_cdrv0_representation=True),
    )
    dp = DomainParticipant(args.domain)
    odom_r = DataReader(dp, Topic(dp, "rt/odom", Odometry), qos=qos)
    fix_r = DataReader(dp, Topic(dp, "rt/fix", NavSatFix), qos=qos)
    status_r = DataReader(dp, Topic(dp, "rt/jaus/status", String), qos=qos)
    cmd_w = DataWriter(dp, Topic(dp, "rt/cmd_vel", Twist), qos=qos)
    goal_w = DataWriter(dp, Topic(dp, "rt/goal_pose", PoseStamped), qos=qos)

    state = {"drive": None, "goal": None, "done": False}
    lock = threading.Lock()

    def control():
        for line in sys.stdin:
            words = line.split()
            with lock:
                if len(words) == 3 and words[0] == "drive":
                    state["drive"] = (float(words[1]), float(words[2]))
                elif words[:1] == ["silent"]:
                    state["drive"] = None
                elif len(words) == 3 and words[0] == "goal":
                    state["goal"] = (float(words[1]), float(words[2]))
        state["done"] = True

    threading.Thread(target=control, daemon=True).start()

    n_odom = n_fix = n_cmd = 0
    last_status = None
    start = time.monotonic()
    next_cmd = start
    say({"ready": True})
    while not state["done"] and time.monotonic() - start < args.duration:
        for o in odom_r.take(N=64):
            if not isinstance(o, Odometry):
                continue  # an InvalidSample: a writer's state changed
            n_odom += 1
            q = o.pose.pose.orientation
            yaw = math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))
            say({"odom": n_odom, "t_ns": time.time_ns(),
                 "x": o.pose.pose.position.x, "y": o.pose.pose.position.y, "yaw": yaw,
                 "vx": o.twist.twist.linear.x, "wz": o.twist.twist.angular.z,
                 "frame": o.header.frame_id, "child": o.child_frame_id})
        for f in fix_r.take(N=16):
            if not isinstance(f, NavSatFix):
                continue
            n_fix += 1
            say({"fix": n_fix, "lat": f.latitude, "lon": f.longitude, "alt": f.altitude,
                 "status": f.status.status})
        for s in status_r.take(N=16):
            if not isinstance(s, String):
                continue
            if s.data != last_status:
                last_status = s.data
                say({"status": s.data})
        now = time.monotonic()
        with lock:
            drive, goal = state["drive"], state["goal"]
            state["goal"] = None
        if drive is not None and now >= next_cmd:
            next_cmd = now + 0.1
            n_cmd += 1
            cmd_w.write(Twist(linear=Vector3(x=drive[0]), angular=Vector3(z=drive[1])))
            say({"cmd_sent": n_cmd, "t_ns": time.time_ns(), "vx": drive[0], "wz": drive[1]})
        if goal is not None:
            g = PoseStamped()
            g.header.frame_id = "odom"
            g.header.stamp = stamp(time.time_ns())
            g.pose.position.x, g.pose.position.y = goal
            goal_w.write(g)
            say({"goal_sent": list(goal)})
        time.sleep(0.005)


if __name__ == "__main__":
    main()
