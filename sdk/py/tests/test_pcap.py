"""Captures: a pcap file of JUDP datagrams written here, read back into messages."""

import struct

import pytest

import jaus


def _udp_frame(src, dst, sport, dport, payload):
    """A raw IPv4/UDP packet (checksums zero: the reader does not check them)."""
    udp = struct.pack("!HHHH", sport, dport, 8 + len(payload), 0) + payload
    ip = struct.pack(
        "!BBHHHBBH4s4s",
        0x45, 0, 20 + len(udp), 1, 0, 64, 17, 0,
        bytes(src), bytes(dst),
    )
    return ip + udp


def _pcap(path, frames):
    """A classic pcap file, link type RAW (101), microsecond timestamps."""
    with open(path, "wb") as f:
        f.write(struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 101))
        for t, data in frames:
            sec, usec = int(t), int(round((t - int(t)) * 1e6))
            f.write(struct.pack("<IIII", sec, usec, len(data), len(data)))
            f.write(data)


def _judp(packet):
    return bytes([1, 0, 0]) + struct.pack("!H", len(packet)) + packet


def test_read_pcap_gives_time_sockets_and_packets(tmp_path):
    speed = jaus.encode_packet(
        jaus.message("SetTravelSpeed", speed=2.0), (1, 1, 1, 1), (1, 1, 2, 1)
    )
    query = jaus.encode_packet(
        jaus.message("QueryGlobalPose", presence_vector=0x1FF), (1, 1, 2, 1), (1, 1, 1, 1)
    )
    path = tmp_path / "judp.pcap"
    _pcap(path, [
        (1000.25, _udp_frame([10, 0, 0, 1], [10, 0, 0, 2], 3794, 3794, _judp(speed))),
        (1000.5, _udp_frame([10, 0, 0, 2], [10, 0, 0, 1], 3794, 3794, _judp(query))),
    ])
    got = jaus.read_pcap(str(path))
    assert len(got) == 2
    t, src, dst, p = got[0]
    assert t == pytest.approx(1000.25)
    assert src == ("10.0.0.1", 3794) and dst == ("10.0.0.2", 3794)
    assert p.name == "SetTravelSpeed" and p.source == (1, 1, 1, 1)
    assert p.encode() == speed
    assert got[1][3].name == "QueryGlobalPose"


def test_read_pcap_strict_raises_on_a_datagram_that_is_not_jaus(tmp_path):
    speed = jaus.encode_packet(
        jaus.message("SetTravelSpeed", speed=2.0), (1, 1, 1, 1), (1, 1, 2, 1)
    )
    path = tmp_path / "mixed.pcap"
    _pcap(path, [
        (1.0, _udp_frame([10, 0, 0, 1], [10, 0, 0, 2], 5000, 5001, b"hello, not jaus")),
        (2.0, _udp_frame([10, 0, 0, 1], [10, 0, 0, 2], 3794, 3794, _judp(speed))),
    ])
    with pytest.raises(jaus.DecodeError, match="datagram 1"):
        jaus.read_pcap(path)
    got = jaus.read_pcap(path, strict=False)
    assert [p.name for _, _, _, p in got] == ["SetTravelSpeed"]


def test_read_pcap_names_a_file_that_is_not_a_capture(tmp_path):
    path = tmp_path / "not.pcap"
    path.write_bytes(b"this is not a capture file")
    with pytest.raises(OSError, match="not a pcap"):
        jaus.read_pcap(path)
