#!/usr/bin/env python3
"""A ROS 2 robot without ROS: a unicycle on Cyclone DDS (the `cyclonedds` package).

It speaks ROS 2's DDS conventions (topics `rt/<name>`, types
`<pkg>::msg::dds_::<Type>_`, plain little-endian CDR, fields in `.msg` order):

* reads `rt/cmd_vel` (geometry_msgs/Twist) and keeps the latest (a robot that
  trusts its last command: only a zero twist stops it);
* integrates linear.x and angular.z into its pose in an ENU odometry frame;
* publishes `rt/odom` (nav_msgs/Odometry, frames odom/base_link) at --rate Hz with
  header.stamp = the wall clock just before the write, and `rt/fix`
  (sensor_msgs/NavSatFix) at 5 Hz around --origin;
* with --sensors, a lidar and a camera: `rt/scan` (sensor_msgs/LaserScan) at 10 Hz,
  181 beams from -90° to +90° (counter-clockwise, REP-103), nothing in range but an
  object to the right (ROS -32°..-28°, nearest 2.0 m at -30°), one farther to the left
  (+55°..+65°, 5 m) and, at +45°, a 0.05 m return below range_min and, at +10°, a NaN;
  `rt/image_raw` (sensor_msgs/Image) at 5 Hz, 8x6 pixels of `pattern` in rgb8 (or
  bgr8), each row padded with 2 bytes of 0xEE; `rt/image_raw/compressed`
  (sensor_msgs/CompressedImage, format png) of the same pattern.

Standard output: one JSON object a line, flushed:
  {"ready": true}
  {"odom": seq, "t_ns": publish wall time, "x": m, "y": m, "yaw": rad}
  {"cmd": [lx, ly, lz, ax, ay, az], "t_ns": arrival wall time}
  {"ros_node": name, "namespace": ns, "readers": n, "writers": n}  (ros_discovery_info)
Standard input: `pause` stops publishing odom, `resume` starts again; `encoding bgr8`
(or rgb8) switches the camera's encoding (bgr8 also sets pixel (7, 5) to BGR_MARK);
`bad` publishes, three times each, a scan of 5000 beams, an image in encoding yuv422
and a compressed image in format jpeg; EOF ends.
"""

import argparse
import json
import math
import struct
import sys
import threading
import time
import zlib
from dataclasses import dataclass, field

from cyclonedds.core import Policy, Qos
from cyclonedds.domain import DomainParticipant
from cyclonedds.idl import IdlStruct
from cyclonedds.idl.types import (
    array, float32, float64, int8, int32, sequence, uint8, uint16, uint32,
)
from cyclonedds.pub import DataWriter
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic


@dataclass
class Time(IdlStruct, typename="builtin_interfaces::msg::dds_::Time_"):
    sec: int32 = 0
    nanosec: uint32 = 0


@dataclass
class Header(IdlStruct, typename="std_msgs::msg::dds_::Header_"):
    stamp: Time = field(default_factory=Time)
    frame_id: str = ""


@dataclass
class Vector3(IdlStruct, typename="geometry_msgs::msg::dds_::Vector3_"):
    x: float64 = 0.0
    y: float64 = 0.0
    z: float64 = 0.0


@dataclass
class Point(IdlStruct, typename="geometry_msgs::msg::dds_::Point_"):
    x: float64 = 0.0
    y: float64 = 0.0
    z: float64 = 0.0


@dataclass
class Quaternion(IdlStruct, typename="geometry_msgs::msg::dds_::Quaternion_"):
    x: float64 = 0.0
    y: float64 = 0.0
    z: float64 = 0.0
    w: float64 = 1.0


@dataclass
class Pose(IdlStruct, typename="geometry_msgs::msg::dds_::Pose_"):
    position: Point = field(default_factory=Point)
    orientation: Quaternion = field(default_factory=Quaternion)


@dataclass
class PoseWithCovariance(IdlStruct, typename="geometry_msgs::msg::dds_::PoseWithCovariance_"):
    pose: Pose = field(default_factory=Pose)
    covariance: array[float64, 36] = field(default_factory=lambda: [0.0] * 36)


@dataclass
class Twist(IdlStruct, typename="geometry_msgs::msg::dds_::Twist_"):
    linear: Vector3 = field(default_factory=Vector3)
    angular: Vector3 = field(default_factory=Vector3)


@dataclass
class TwistWithCovariance(IdlStruct, typename="geometry_msgs::msg::dds_::TwistWithCovariance_"):
    twist: Twist = field(default_factory=Twist)
    covariance: array[float64, 36] = field(default_factory=lambda: [0.0] * 36)


@dataclass
class Odometry(IdlStruct, typename="nav_msgs::msg::dds_::Odometry_"):
    header: Header = field(default_factory=Header)
    child_frame_id: str = ""
    pose: PoseWithCovariance = field(default_factory=PoseWithCovariance)
    twist: TwistWithCovariance = field(default_factory=TwistWithCovariance)


@dataclass
class NavSatStatus(IdlStruct, typename="sensor_msgs::msg::dds_::NavSatStatus_"):
    status: int8 = 0
    service: uint16 = 1


@dataclass
class NavSatFix(IdlStruct, typename="sensor_msgs::msg::dds_::NavSatFix_"):
    header: Header = field(default_factory=Header)
    status: NavSatStatus = field(default_factory=NavSatStatus)
    latitude: float64 = 0.0
    longitude: float64 = 0.0
    altitude: float64 = 0.0
    position_covariance: array[float64, 9] = field(default_factory=lambda: [0.0] * 9)
    position_covariance_type: uint8 = 0


@dataclass
class LaserScan(IdlStruct, typename="sensor_msgs::msg::dds_::LaserScan_"):
    header: Header = field(default_factory=Header)
    angle_min: float32 = 0.0
    angle_max: float32 = 0.0
    angle_increment: float32 = 0.0
    time_increment: float32 = 0.0
    scan_time: float32 = 0.0
    range_min: float32 = 0.0
    range_max: float32 = 0.0
    ranges: sequence[float32] = field(default_factory=list)
    intensities: sequence[float32] = field(default_factory=list)


@dataclass
class Image(IdlStruct, typename="sensor_msgs::msg::dds_::Image_"):
    header: Header = field(default_factory=Header)
    height: uint32 = 0
    width: uint32 = 0
    encoding: str = ""
    is_bigendian: uint8 = 0
    step: uint32 = 0
    data: sequence[uint8] = field(default_factory=list)


@dataclass
class CompressedImage(IdlStruct, typename="sensor_msgs::msg::dds_::CompressedImage_"):
    header: Header = field(default_factory=Header)
    format: str = ""
    data: sequence[uint8] = field(default_factory=list)


W, H = 8, 6
BGR_MARK = (250, 10, 60)


def pattern(x, y):
    """The camera's pixel (x, y) as RGB."""
    return (x * 30, y * 40, 200 - x * 10)


def scan_ranges():
    """181 beams, -90° to +90°; see the module's doc."""
    out = []
    for i in range(181):
        deg = i - 90
        if -32 <= deg <= -28:
            r = 2.0 + 0.02 * abs(deg + 30)
        elif 55 <= deg <= 65:
            r = 5.0
        elif deg == 45:
            r = 0.05
        elif deg == 10:
            r = float("nan")
        else:
            r = float("inf")
        out.append(r)
    return out


def image_msg(encoding, t_ns):
    rows = []
    for y in range(H):
        row = []
        for x in range(W):
            r, g, b = pattern(x, y)
            if encoding == "bgr8" and (x, y) == (W - 1, H - 1):
                r, g, b = BGR_MARK
            row += [b, g, r] if encoding == "bgr8" else [r, g, b]
        rows += row + [0xEE, 0xEE]
    m = Image(height=H, width=W, encoding=encoding, step=W * 3 + 2, data=rows)
    m.header.frame_id = "camera"
    m.header.stamp = stamp(t_ns)
    return m


def png_file():
    raw = b"".join(
        b"\x00" + bytes(c for x in range(W) for c in pattern(x, y)) for y in range(H)
    )

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    return (
        b"\x89PNG\r\n\x1a\n"
        + chunk(b"IHDR", struct.pack(">IIBBBBB", W, H, 8, 2, 0, 0, 0))
        + chunk(b"IDAT", zlib.compress(raw))
        + chunk(b"IEND", b"")
    )


@dataclass
class Gid(IdlStruct, typename="rmw_dds_common::msg::dds_::Gid_"):
    # 16 bytes since ROS 2 Iron (24 before: run with --gid 24 against a Humble build).
    data: array[uint8, 16] = field(default_factory=lambda: [0] * 16)


@dataclass
class Gid24(IdlStruct, typename="rmw_dds_common::msg::dds_::Gid_"):
    data: array[uint8, 24] = field(default_factory=lambda: [0] * 24)


def entities_types(gid_type):
    @dataclass
    class NodeEntitiesInfo(IdlStruct, typename="rmw_dds_common::msg::dds_::NodeEntitiesInfo_"):
        node_namespace: str = ""
        node_name: str = ""
        reader_gid_seq: sequence[gid_type] = field(default_factory=list)
        writer_gid_seq: sequence[gid_type] = field(default_factory=list)

    @dataclass
    class ParticipantEntitiesInfo(
        IdlStruct, typename="rmw_dds_common::msg::dds_::ParticipantEntitiesInfo_"
    ):
        gid: gid_type = field(default_factory=gid_type)
        node_entities_info_seq: sequence[NodeEntitiesInfo] = field(default_factory=list)

    return ParticipantEntitiesInfo


def say(obj):
    sys.stdout.write(json.dumps(obj) + "\n")
    sys.stdout.flush()


def stamp(t_ns):
    return Time(sec=t_ns // 1_000_000_000, nanosec=t_ns % 1_000_000_000)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--domain", type=int, default=0)
    ap.add_argument("--rate", type=float, default=20.0)
    ap.add_argument("--duration", type=float, default=120.0, help="exit after this many s")
    ap.add_argument("--origin", type=float, nargs=2, default=[29.65, -82.32])
    ap.add_argument("--gid", type=int, choices=[16, 24], default=16)
    ap.add_argument("--sensors", action="store_true", help="publish scan and images")
    args = ap.parse_args()

    # ROS 2's default QoS (reliable, volatile, keep last 10) and plain CDR (XCDR1), as
    # rmw_cyclonedds_cpp and rmw_fastrtps_cpp write it.
    qos = Qos(
        Policy.Reliability.Reliable(max_blocking_time=100_000_000),
        Policy.History.KeepLast(10),
        Policy.Durability.Volatile,
        Policy.DataRepresentation(use_cdrv0_representation=True),
    )
    dp = DomainParticipant(args.domain)
    odom_w = DataWriter(dp, Topic(dp, "rt/odom", Odometry), qos=qos)
    fix_w = DataWriter(dp, Topic(dp, "rt/fix", NavSatFix), qos=qos)
    cmd_r = DataReader(dp, Topic(dp, "rt/cmd_vel", Twist), qos=qos)
    if args.sensors:
        scan_w = DataWriter(dp, Topic(dp, "rt/scan", LaserScan), qos=qos)
        image_w = DataWriter(dp, Topic(dp, "rt/image_raw", Image), qos=qos)
        png_w = DataWriter(dp, Topic(dp, "rt/image_raw/compressed", CompressedImage), qos=qos)
        png = list(png_file())
    # The ROS 2 graph: what `ros2 node list` reads (rmw_dds_common's topic).
    graph_qos = Qos(
        Policy.Reliability.Reliable(max_blocking_time=100_000_000),
        Policy.History.KeepLast(16),
        Policy.Durability.TransientLocal,
        Policy.DataRepresentation(use_cdrv0_representation=True),
    )
    pei = entities_types(Gid if args.gid == 16 else Gid24)
    graph_r = DataReader(dp, Topic(dp, "ros_discovery_info", pei), qos=graph_qos)
    nodes_seen = set()

    state = {"paused": False, "done": False, "encoding": "rgb8", "bad": 0}

    def control():
        for line in sys.stdin:
            word = line.strip()
            if word in ("pause", "resume"):
                state["paused"] = word == "pause"
            elif word.startswith("encoding "):
                state["encoding"] = word.split()[1]
            elif word == "bad":
                state["bad"] = 3
        state["done"] = True

    threading.Thread(target=control, daemon=True).start()

    x = y = yaw = 0.0
    v = w = 0.0
    period = 1.0 / args.rate
    seq = 0
    start = time.monotonic()
    last = start
    next_tick = start
    say({"ready": True})
    while not state["done"] and time.monotonic() - start < args.duration:
        for s in cmd_r.take(N=64):
            t = [s.linear.x, s.linear.y, s.linear.z, s.angular.x, s.angular.y, s.angular.z]
            if all(math.isfinite(c) for c in t):
                v, w = s.linear.x, s.angular.z
            say({"cmd": t, "t_ns": time.time_ns()})
        for info in graph_r.take(N=16):
            for n in info.node_entities_info_seq:
                key = (n.node_namespace, n.node_name, len(n.reader_gid_seq), len(n.writer_gid_seq))
                if key not in nodes_seen:
                    nodes_seen.add(key)
                    say({"ros_node": n.node_name, "namespace": n.node_namespace,
                         "readers": len(n.reader_gid_seq), "writers": len(n.writer_gid_seq)})
        now = time.monotonic()
        dt = now - last
        last = now
        x += v * math.cos(yaw) * dt
        y += v * math.sin(yaw) * dt
        yaw = math.atan2(math.sin(yaw + w * dt), math.cos(yaw + w * dt))
        if not state["paused"]:
            seq += 1
            o = Odometry(child_frame_id="base_link")
            o.header.frame_id = "odom"
            o.pose.pose.position = Point(x=x, y=y, z=0.0)
            o.pose.pose.orientation = Quaternion(z=math.sin(yaw / 2), w=math.cos(yaw / 2))
            o.twist.twist.linear = Vector3(x=v)
            o.twist.twist.angular = Vector3(z=w)
            t_ns = time.time_ns()
            o.header.stamp = stamp(t_ns)
            odom_w.write(o)
            say({"odom": seq, "t_ns": t_ns, "x": x, "y": y, "yaw": yaw})
            if seq % max(1, int(args.rate / 5)) == 0:
                lat0, lon0 = args.origin
                lat = lat0 + math.degrees(y / 6_378_137.0)
                lon = lon0 + math.degrees(x / (6_378_137.0 * math.cos(math.radians(lat0))))
                f = NavSatFix(latitude=lat, longitude=lon, altitude=12.0)
                f.header.frame_id = "gps"
                f.header.stamp = stamp(time.time_ns())
                f.position_covariance = [0.25, 0, 0, 0, 0.25, 0, 0, 0, 1.0]
                f.position_covariance_type = 2
                fix_w.write(f)
        if args.sensors:
            t_ns = time.time_ns()
            tick = int((time.monotonic() - start) * 10)
            if tick != state.get("tick"):
                state["tick"] = tick
                s = LaserScan(
                    angle_min=math.radians(-90), angle_max=math.radians(90),
                    angle_increment=math.radians(1), scan_time=0.1,
                    range_min=0.1, range_max=20.0, ranges=scan_ranges(),
                )
                s.header.frame_id = "laser"
                s.header.stamp = stamp(t_ns)
                scan_w.write(s)
                if tick % 2 == 0:
                    image_w.write(image_msg(state["encoding"], t_ns))
                    c = CompressedImage(format="png", data=png)
                    c.header.stamp = stamp(t_ns)
                    png_w.write(c)
                if state["bad"] > 0:
                    state["bad"] -= 1
                    scan_w.write(LaserScan(angle_increment=0.001, range_min=0.1,
                                           range_max=20.0, ranges=[1.0] * 5000))
                    bad = image_msg("rgb8", t_ns)
                    bad.encoding = "yuv422"
                    image_w.write(bad)
                    png_w.write(CompressedImage(format="jpeg", data=[0xFF, 0xD8]))
                    say({"bad": state["bad"]})
        next_tick += period
        time.sleep(max(0.0, next_tick - time.monotonic()))


if __name__ == "__main__":
    main()
