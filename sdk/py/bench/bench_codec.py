"""Messages decoded and encoded per second from Python: `jaus` (the SDK's codec
through jaus-dynamic) against a plain `struct`-based decoder/encoder of the same
packets written for this benchmark (fixed layouts, no checks beyond `struct`'s).

    python sdk/py/bench/bench_codec.py            # after `pip install ./sdk/py`

Full packets both ways: 16-byte header + body. Prints one line per packet and side.
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
    """The reference Report VKS Objects (sdk/examples/codec_lines.rs): 10 polygons x 40
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


def rate(fn, n):
    """Calls per second: the best of 5 runs of n calls."""
    return n / min(timeit.repeat(fn, number=n, repeat=5))


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 20_000
    packets = {k: bytes.fromhex(v) for k, v in PACKETS.items()}
    packets["Report VKS Objects"] = vks_packet()
    print(f"{'packet':<26} {'side':<8} {'decode/s':>12} {'encode/s':>12}")
    for name, raw in packets.items():
        count = n if len(raw) < 200 else max(n // 100, 50)
        p = jaus.decode_packet(raw)
        m = p.message
        src, dst = p.source, p.destination
        assert jaus.encode_packet(m, src, dst) == raw
        # Decoding reads the fields into Python values (to_dict), as the struct side does.
        dec = rate(lambda: jaus.decode_packet(raw).message.to_dict(), count)
        enc = rate(lambda: jaus.encode_packet(m, src, dst), count)
        print(f"{name:<26} {'jaus':<8} {dec:>12,.0f} {enc:>12,.0f}")
        if name in STRUCT:
            d, e = STRUCT[name]
            h, f = d(raw)
            assert e(h, f) == raw, name
            # The same values as the SDK's decode.
            for k, v in f.items():
                want = m.to_dict()[k]
                assert v == want if isinstance(v, (int, dict)) else abs(v - want) < 1e-9 * max(1, abs(want)), k
            dec = rate(lambda: d(raw), count)
            enc = rate(lambda: e(h, f), count)
            print(f"{name:<26} {'struct':<8} {dec:>12,.0f} {enc:>12,.0f}")
        else:
            print(f"{name:<26} {'struct':<8} {'(not written)':>12}")


if __name__ == "__main__":
    main()
