"""Messages decoded and encoded per second from Python: `jaus` (the SDK's codec
through jaus-dynamic) against a plain `struct`-based decoder/encoder of the same
packets written for this benchmark (fixed layouts, no checks beyond `struct`'s).

    python sdk/py/bench/bench_codec.py [N]        # after `pip install ./sdk/py`

Full packets both ways: 16-byte header + body. Columns, per packet and side:

- decode: bytes to an object the fields are read from. jaus: `decode_packet(raw)`
  (the whole packet checked, as the decode checks it, and kept; the message is decoded
  when first needed, its fields become Python values when read).
  struct: the decoder below (header tuple + dict of every field, scaled).
- decode+read: the same, then every field read once: the 12 header fields and every
  field of the message, the members of its records too (jaus: attributes; struct:
  the header tuple unpacked, the dict's items).
- to_dict: jaus `decode_packet(raw).message.to_dict()` (what the struct side's decode
  gives: a dict of every field).
- encode: `encode_packet(message, source, destination)` / the struct encoder.
- batch: packets per second decoded 1,000 at a time, all kept (a capture): jaus
  `decode_many(batch)`, struct `[decode(r) for r in batch]`.

Then the ratio jaus/struct of each column, in the same run (the machine may be
shared: compare ratios, not rates across runs).
"""

import struct
import sys
import timeit

import jaus

PACKETS = {
    # jaus::json::REFERENCE_PACKETS (the SDK's README example and docs/performance.md).
    "Report Global Pose": "0602024404030201080706051e000000ff016fd12b2a403a75c5dcd125b9333333030a0230ff0040d10015e3227b",
    "Set Wrench Effort": "06020504040302010807060514000000ff0f0a4734f30000480172fd662633000000000d",
    "Set Global Path Segment": "06020f0404030201080706051d0000000307006fd12b2a403a75c54fcf1db9b7f62b2aee3075c523441fb9c500",
}

HEADER = struct.Struct("<BBHBBBBBBBBHH")
PI = 3.141592653589793


# The divisors of OpenJAUS 3.3 (docs/wire.md section 2.2).
DIVISOR = {(8, False): 255, (16, False): 65_535, (32, False): 4_294_967_294,
           (16, True): 65_534, (32, True): 4_294_967_294}


def scaled(lo, hi, bits, signed):
    """(decode, encode) of a scaled integer: real = int * step + bias."""
    step = (hi - lo) / DIVISOR[bits, signed]
    bias = (hi + lo) / 2 if signed else lo
    return (lambda i: i * step + bias), (lambda r: round((r - bias) / step))


LAT = scaled(-90, 90, 32, True)
LON = scaled(-180, 180, 32, True)
ELEV = scaled(-10000, 35000, 32, True)
RMS = scaled(0, 100, 32, False)
ANG = scaled(-PI, PI, 16, True)
ARMS = scaled(0, PI, 16, False)
EFF = scaled(-100, 100, 16, True)
RES = scaled(0, 100, 8, False)
W = scaled(0, 500, 16, False)

POSE = struct.Struct("<HiiiIhhhHI")


def decode_pose(b):
    h = HEADER.unpack_from(b)
    pv, la, lo, el, pr, r, p, y, ar, ts = POSE.unpack_from(b, 16)
    return h, {
        "latitude": LAT[0](la), "longitude": LON[0](lo), "elevation": ELEV[0](el),
        "position_rms": RMS[0](pr), "roll": ANG[0](r), "pitch": ANG[0](p), "yaw": ANG[0](y),
        "attitude_rms": ARMS[0](ar),
        "time_stamp": {"millisecond": ts & 0x3FF, "second": (ts >> 10) & 0x3F,
                       "minute": (ts >> 16) & 0x3F, "hour": (ts >> 22) & 0x1F, "day": ts >> 27},
    }


def encode_pose(h, f):
    t = f["time_stamp"]
    ts = t["millisecond"] | t["second"] << 10 | t["minute"] << 16 | t["hour"] << 22 | t["day"] << 27
    body = POSE.pack(0x1FF, LAT[1](f["latitude"]), LON[1](f["longitude"]), ELEV[1](f["elevation"]),
                     RMS[1](f["position_rms"]), ANG[1](f["roll"]), ANG[1](f["pitch"]),
                     ANG[1](f["yaw"]), ARMS[1](f["attitude_rms"]), ts)
    return HEADER.pack(*h[:11], len(body), h[12]) + body


WRENCH = struct.Struct("<H6h6B")
WRENCH_NAMES = [f"{k}_{a}" for k in ("propulsive_linear_effort", "propulsive_rotational_effort") for a in "xyz"]
RES_NAMES = [f"{k}_{a}" for k in ("resistive_linear_effort", "resistive_rotational_effort") for a in "xyz"]


def decode_wrench(b):
    h = HEADER.unpack_from(b)
    v = WRENCH.unpack_from(b, 16)
    f = {n: EFF[0](x) for n, x in zip(WRENCH_NAMES, v[1:7])}
    f.update({n: RES[0](x) for n, x in zip(RES_NAMES, v[7:13])})
    return h, f


def encode_wrench(h, f):
    body = WRENCH.pack(0xFFF, *[EFF[1](f[n]) for n in WRENCH_NAMES], *[RES[1](f[n]) for n in RES_NAMES])
    return HEADER.pack(*h[:11], len(body), h[12]) + body


SEGMENT = struct.Struct("<BHiiiiiiH")


def decode_segment(b):
    h = HEADER.unpack_from(b)
    _, n, la1, lo1, al1, la2, lo2, al2, w = SEGMENT.unpack_from(b, 16)
    return h, {
        "path_segment_number": n, "p1_latitude": LAT[0](la1), "p1_longitude": LON[0](lo1),
        "p1_altitude": ELEV[0](al1), "p2_latitude": LAT[0](la2), "p2_longitude": LON[0](lo2),
        "p2_altitude": ELEV[0](al2), "weighting_factor": W[0](w),
    }


def encode_segment(h, f):
    body = SEGMENT.pack(3, f["path_segment_number"], LAT[1](f["p1_latitude"]), LON[1](f["p1_longitude"]),
                        ELEV[1](f["p1_altitude"]), LAT[1](f["p2_latitude"]), LON[1](f["p2_longitude"]),
                        ELEV[1](f["p2_altitude"]), W[1](f["weighting_factor"]))
    return HEADER.pack(*h[:11], len(body), h[12]) + body


STRUCT = {
    "Report Global Pose": (decode_pose, encode_pose),
    "Set Wrench Effort": (decode_wrench, encode_wrench),
    "Set Global Path Segment": (decode_segment, encode_segment),
}


def vks_packet():
    """The reference Report VKS Objects (sdk/jaus/examples/codec_lines.rs): 10 polygons x 40
    points, 3 feature classes each."""
    objects = [
        {
            "object_id": 1000 + o,
            "object_type": "Polygon",
            "buffer": 2.5,
            "feature_classes": [
                {"id": 10 * o + f, "attribute": {"UnsignedInteger": 123_456 + f}} for f in range(3)
            ],
            "points": [
                {"latitude": 29.65 + 0.0001 * p, "longitude": -82.32 - 0.0001 * o} for p in range(40)
            ],
        }
        for o in range(10)
    ]
    m = jaus.message("ReportVksObjects", request_id=9, object_count=0, objects=objects)
    return jaus.encode_packet(m, "5.6.7.8", "1.2.3.4")


# Every field read once (the decode+read column).
HEADER_ATTRS = ("priority", "ack_nak", "service_connection", "experimental", "version",
                "reserved", "command_code", "destination", "source", "data_size",
                "data_flag", "sequence_number")


def read_jaus_header(p):
    return (p.priority, p.ack_nak, p.service_connection, p.experimental, p.version,
            p.reserved, p.command_code, p.destination, p.source, p.data_size, p.data_flag,
            p.sequence_number)


def read_pose_jaus(raw):
    p = jaus.decode_packet(raw)
    m = p.message
    t = m.time_stamp
    return (read_jaus_header(p), m.latitude, m.longitude, m.elevation, m.position_rms,
            m.roll, m.pitch, m.yaw, m.attitude_rms,
            t.millisecond, t.second, t.minute, t.hour, t.day)


def read_pose_struct(raw):
    h, f = decode_pose(raw)
    a, b, c, d, e, g, i, j, k, l, m, n, o = h
    t = f["time_stamp"]
    return (h, f["latitude"], f["longitude"], f["elevation"], f["position_rms"],
            f["roll"], f["pitch"], f["yaw"], f["attitude_rms"],
            t["millisecond"], t["second"], t["minute"], t["hour"], t["day"])


def read_wrench_jaus(raw):
    p = jaus.decode_packet(raw)
    m = p.message
    return (read_jaus_header(p), m.propulsive_linear_effort_x, m.propulsive_linear_effort_y,
            m.propulsive_linear_effort_z, m.propulsive_rotational_effort_x,
            m.propulsive_rotational_effort_y, m.propulsive_rotational_effort_z,
            m.resistive_linear_effort_x, m.resistive_linear_effort_y,
            m.resistive_linear_effort_z, m.resistive_rotational_effort_x,
            m.resistive_rotational_effort_y, m.resistive_rotational_effort_z)


def read_wrench_struct(raw):
    h, f = decode_wrench(raw)
    a, b, c, d, e, g, i, j, k, l, m, n, o = h
    return (h, f["propulsive_linear_effort_x"], f["propulsive_linear_effort_y"],
            f["propulsive_linear_effort_z"], f["propulsive_rotational_effort_x"],
            f["propulsive_rotational_effort_y"], f["propulsive_rotational_effort_z"],
            f["resistive_linear_effort_x"], f["resistive_linear_effort_y"],
            f["resistive_linear_effort_z"], f["resistive_rotational_effort_x"],
            f["resistive_rotational_effort_y"], f["resistive_rotational_effort_z"])


def read_segment_jaus(raw):
    p = jaus.decode_packet(raw)
    m = p.message
    return (read_jaus_header(p), m.path_segment_number, m.p1_latitude, m.p1_longitude,
            m.p1_altitude, m.p2_latitude, m.p2_longitude, m.p2_altitude, m.weighting_factor)


def read_segment_struct(raw):
    h, f = decode_segment(raw)
    a, b, c, d, e, g, i, j, k, l, m, n, o = h
    return (h, f["path_segment_number"], f["p1_latitude"], f["p1_longitude"],
            f["p1_altitude"], f["p2_latitude"], f["p2_longitude"], f["p2_altitude"],
            f["weighting_factor"])


READ = {
    "Report Global Pose": (read_pose_jaus, read_pose_struct),
    "Set Wrench Effort": (read_wrench_jaus, read_wrench_struct),
    "Set Global Path Segment": (read_segment_jaus, read_segment_struct),
}


def read_vks_jaus(raw):
    """Every field of the VKS packet, its nested lists and unions too."""
    p = jaus.decode_packet(raw)
    m = p.message
    out = [read_jaus_header(p), m.request_id, m.object_count]
    for o in m.objects:
        out += [o.object_id, o.object_type, o.buffer]
        for f in o.feature_classes:
            out += [f.id, f.attribute.UnsignedInteger]
        for pt in o.points:
            out += [pt.latitude, pt.longitude]
    return out


def rate(fn, n):
    """Calls per second: the best of 5 runs of n calls."""
    return n / min(timeit.repeat(fn, number=n, repeat=5))


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 20_000
    packets = {k: bytes.fromhex(v) for k, v in PACKETS.items()}
    packets["Report VKS Objects"] = vks_packet()
    cols = ("decode/s", "decode+read/s", "to_dict/s", "encode/s", "batch/s")
    print(f"{'packet':<26} {'side':<8} " + " ".join(f"{c:>14}" for c in cols))
    for name, raw in packets.items():
        count = n if len(raw) < 200 else max(n // 100, 50)
        batch = [raw] * 1000
        batches = max(count // 1000, 2)
        p = jaus.decode_packet(raw)
        m = p.message
        src, dst = p.source, p.destination
        assert jaus.encode_packet(m, src, dst) == raw
        if name in READ:
            rj, rs = READ[name]
        else:
            rj, rs = read_vks_jaus, None
        # Every field read is the SDK's value (to_dict), as the struct side's are below.
        assert len(rj(raw)) > 2
        j = (
            rate(lambda: jaus.decode_packet(raw), count),
            rate(lambda: rj(raw), count),
            rate(lambda: jaus.decode_packet(raw).message.to_dict(), count),
            rate(lambda: jaus.encode_packet(m, src, dst), count),
            rate(lambda: jaus.decode_many(batch), batches) * len(batch),
        )
        print(f"{name:<26} {'jaus':<8} " + " ".join(f"{x:>14,.0f}" for x in j))
        if name in STRUCT:
            d, e = STRUCT[name]
            h, f = d(raw)
            assert e(h, f) == raw, name
            # The same values as the SDK's decode.
            want_all = m.to_dict()
            for k, v in f.items():
                want = want_all[k]
                assert v == want if isinstance(v, (int, dict)) else abs(v - want) < 1e-9 * max(1, abs(want)), k
            got_j, got_s = rj(raw), rs(raw)
            assert len(got_j) == len(got_s), name
            for a, b in zip(got_j[1:], got_s[1:]):
                assert a == b if isinstance(a, int) else abs(a - b) < 1e-9 * max(1, abs(b)), name
            s = (
                rate(lambda: d(raw), count),
                rate(lambda: rs(raw), count),
                # struct's decode is its dict of every field already.
                rate(lambda: d(raw), count),
                rate(lambda: e(h, f), count),
                rate(lambda: [d(r) for r in batch], batches) * len(batch),
            )
            print(f"{name:<26} {'struct':<8} " + " ".join(f"{x:>14,.0f}" for x in s))
            print(f"{name:<26} {'ratio':<8} " + " ".join(f"{a / b:>13.2f}x" for a, b in zip(j, s)))
        else:
            print(f"{name:<26} {'struct':<8} {'(not written)':>14}")


if __name__ == "__main__":
    main()
