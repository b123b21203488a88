"""Decoding checks the whole packet at once; a message's fields become Python objects
as they are read (then kept): every field read that way equals the eager form
(`to_dict()`), errors still come from `decode_packet`, and `decode_many` decodes a
batch."""

import json

import pytest

import jaus


def plain(v):
    """A field's value as `to_dict()` gives it (Records as dicts)."""
    if isinstance(v, jaus.Record):
        return {k: plain(v[k]) for k in v}
    if isinstance(v, list):
        return [plain(x) for x in v]
    return v


def same(a, b):
    # JSON text: floats compare by value, and a NaN would equal itself.
    return json.dumps(a, sort_keys=False) == json.dumps(b, sort_keys=False)


def test_every_field_read_lazily_equals_the_eager_form(vectors):
    for v in vectors:
        raw = bytes.fromhex(v["hex"])
        eager = jaus.decode_packet(raw).message.to_dict()
        m = jaus.decode_packet(raw).message
        assert m.fields == list(eager), v["hex"]
        for name in m.fields:
            # By item (any name) and, for names that are not members, by attribute.
            assert same(plain(m[name]), eager[name]), (v["hex"], name)
            if name not in ("name", "code", "fields", "to_dict", "to_json", "encode", "doc", "from_dict"):
                assert same(plain(getattr(m, name)), eager[name]), (v["hex"], name)
        # Reading the fields first changes nothing the message gives afterwards.
        assert m.to_dict() == eager
        assert m == jaus.decode(raw[16:], m.code)
        assert jaus.encode(m) == raw[16:]


def test_the_packet_line_is_the_same_before_and_after_the_message_is_read(cli_lines):
    for case in cli_lines:
        raw = bytes.fromhex(case["hex"])
        # Not read: the line straight from the decoded packet.
        assert jaus.decode_packet(raw).to_json() == case["cli"]
        assert jaus.decode_packet(raw).to_dict() == json.loads(case["cli"])
        p = jaus.decode_packet(raw)
        m = p.message
        for name in m.fields:
            m[name]
        assert p.to_json() == case["cli"]
        assert p.to_dict() == json.loads(case["cli"])
        assert p.message is m
        assert p.encode() == raw
        assert repr(p).startswith(f"<jaus.Packet {p.name} ")


def test_read_fields_are_kept_lists_are_made_anew(cli_lines, vendor_overlay):
    case = next(c for c in cli_lines if '"ReportGlobalPose"' in c["cli"])
    m = jaus.decode_packet(bytes.fromhex(case["hex"])).message
    assert m.time_stamp is m.time_stamp and m.time_stamp is m["time_stamp"]
    assert m.latitude is m.latitude
    assert m.time_stamp.hour == m.time_stamp["hour"] == m.to_dict()["time_stamp"]["hour"]
    # A list is the caller's to change: each read is a new one.
    schema = jaus.Schema.load([vendor_overlay])
    tanks = schema.message(
        "ReportTankLevels",
        time_stamp={"millisecond": 5, "second": 6, "minute": 7, "hour": 8, "day": 9},
        levels=[0.0, 50.0, 100.0],
    )
    back = schema.decode_packet(schema.encode_packet(tanks, (1, 1, 210, 1), (1, 1, 1, 1))).message
    levels = back.levels
    levels.append(7.0)
    assert len(back.levels) == 3 and back.levels is not back.levels


def test_members_win_over_fields_and_unknown_names_raise(cli_lines, vectors):
    case = next(c for c in cli_lines if '"ReportGlobalPose"' in c["cli"])
    m = jaus.decode_packet(bytes.fromhex(case["hex"])).message
    assert m.name == "ReportGlobalPose" and m.code == 0x4402
    assert callable(m.to_dict) and callable(m.to_json) and callable(m.encode)
    assert m.__class__ is jaus.Message
    with pytest.raises(AttributeError, match="no field `nope`.*latitude"):
        m.nope
    with pytest.raises(KeyError, match="no field `nope`"):
        m["nope"]
    assert getattr(m, "nope", 5) == 5 and not hasattr(m, "nope")
    ts = m.time_stamp
    assert callable(ts.keys) and ts.keys() == list(ts)
    with pytest.raises(AttributeError, match="no entry `nope`"):
        ts.nope
    # An optional field that is absent reads as None, lazily too.
    v = next(v for v in vectors if v["message"] == "ReportGlobalPose" and v["variant"] == "pv_all_off")
    empty = jaus.decode_packet(bytes.fromhex(v["hex"])).message
    assert empty.latitude is None and empty["time_stamp"] is None


def test_bad_packets_raise_at_decode_not_on_first_read(vectors):
    v = next(v for v in vectors if v["message"] == "ReportGlobalPose" and v["variant"] == "pv_all_on")
    raw = bytes.fromhex(v["hex"])
    body = raw[16:]
    # A packet whose body is three bytes short (its data size says so): the same error
    # as decoding the body alone, raised by decode_packet.
    header = bytearray(raw[:16])
    size = len(body) - 3
    header[12:14] = (size | (int.from_bytes(raw[12:14], "little") & 0xF000)).to_bytes(2, "little")
    short = bytes(header) + body[:-3]
    with pytest.raises(jaus.DecodeError) as e:
        jaus.decode_packet(short)
    with pytest.raises(jaus.DecodeError) as alone:
        jaus.decode(body[:-3], 0x4402)
    assert str(e.value) == str(alone.value)
    assert e.value.message == "ReportGlobalPose"
    assert e.value.field == "ReportGlobalPose.time_stamp"
    assert e.value.offset == len(body) - 4
    # The header's data size disagreeing with the body, a short header.
    with pytest.raises(jaus.DecodeError, match="data size"):
        jaus.decode_packet(raw + b"\x00")
    with pytest.raises(jaus.DecodeError, match="header"):
        jaus.decode_packet(raw[:10])


def test_decode_many_strict_and_not(vectors):
    raws = [bytes.fromhex(v["hex"]) for v in vectors[:200]]
    got = jaus.decode_many(raws)
    assert len(got) == len(raws)
    for raw, p in zip(raws, got):
        assert isinstance(p, jaus.Packet)
        assert p.to_json() == jaus.decode_packet(raw).to_json()
    # Any iterable of bytes, a generator too; nothing gives an empty list.
    assert [p.name for p in jaus.decode_many(r for r in raws[:3])] == [p.name for p in got[:3]]
    assert jaus.decode_many([]) == []

    bad = raws[:3] + [raws[3][:-1], raws[4], b"\x06\x02"]
    with pytest.raises(jaus.DecodeError) as e:
        jaus.decode_many(bad)
    assert e.value.index == 3
    with pytest.raises(jaus.DecodeError) as alone:
        jaus.decode_packet(raws[3][:-1])
    assert str(e.value) == str(alone.value)

    mixed = jaus.decode_many(bad, strict=False)
    assert len(mixed) == len(bad)
    assert [type(x) for x in mixed] == [jaus.Packet] * 3 + [jaus.DecodeError, jaus.Packet, jaus.DecodeError]
    assert mixed[3].index == 3 and str(mixed[3]) == str(alone.value)
    assert mixed[5].index == 5 and "header" in str(mixed[5])
    assert mixed[4].to_json() == jaus.decode_packet(raws[4]).to_json()
    # Not bytes: a TypeError, strict or not.
    with pytest.raises(TypeError, match="packet 1 is a str"):
        jaus.decode_many([raws[0], "0602"], strict=False)


def test_a_schema_with_overlays_decodes_the_same_way(vendor_overlay, vectors):
    schema = jaus.Schema.load([vendor_overlay])
    m = schema.message(
        "ReportTankLevels",
        time_stamp={"millisecond": 5, "second": 6, "minute": 7, "hour": 8, "day": 9},
        levels=[0.0, 50.0, 100.0],
    )
    pkt = schema.encode_packet(m, (1, 1, 210, 1), (1, 1, 1, 1))
    p = schema.decode_packet(pkt)
    eager = schema.decode(pkt[16:], 0xD101).to_dict()
    assert same({k: plain(getattr(p.message, k)) for k in p.message.fields}, eager)
    assert p.message.time_stamp is p.message.time_stamp
    with pytest.raises(jaus.DecodeError) as e:
        schema.decode_packet(pkt[:-1])
    assert "data size" in str(e.value)
    many = schema.decode_many([pkt, pkt[:-1], bytes.fromhex(vectors[0]["hex"])], strict=False)
    assert many[0].name == "ReportTankLevels" and many[0].message == p.message
    assert isinstance(many[1], jaus.DecodeError) and many[1].index == 1
    assert many[2].name == vectors[0]["message"]
    # The SDK's schema does not know the vendor's code: a raw packet, not an error.
    assert jaus.decode_many([pkt])[0].message is None


def test_a_message_never_read_decodes_on_first_need(vectors):
    # Each use below comes first on a message of its own: the message is decoded from
    # the packet's checked bytes by whichever needs it first.
    for v in vectors[::7]:
        raw = bytes.fromhex(v["hex"])
        body, eager = raw[16:], jaus.decode(raw[16:], int.from_bytes(raw[2:4], "little"))
        fresh = lambda: jaus.decode_packet(raw).message  # noqa: E731
        assert fresh() == eager and eager == fresh(), v["hex"]
        assert jaus.encode(fresh()) == body and fresh().encode() == body
        assert repr(fresh()) == repr(eager)
        assert fresh().to_json() == eager.to_json()
        assert fresh().fields == eager.fields
        assert all(name in fresh() for name in eager.fields)
        assert fresh().name == eager.name and fresh().code == eager.code
