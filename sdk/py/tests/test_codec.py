"""The codec from Python: every OpenJAUS reference vector, the CLI's JSON form,
building messages, and the errors."""

import json

import pytest

import jaus


def test_every_reference_vector_decodes_and_reencodes_byte_identically(vectors):
    assert len(vectors) > 1000
    codes = set()
    for v in vectors:
        raw = bytes.fromhex(v["hex"])
        packet = jaus.decode_packet(raw)
        m = packet.message
        assert m is not None, v["hex"]
        assert m.code == int(v["command_code"], 16)
        # The body straight back, and the whole packet.
        assert jaus.encode(m) == raw[16:], v["hex"]
        assert packet.encode() == raw
        again = jaus.encode_packet(
            m,
            packet.source,
            packet.destination,
            priority=packet.priority,
            ack_nak=packet.ack_nak,
            service_connection=packet.service_connection,
            experimental=packet.experimental,
            sequence_number=packet.sequence_number,
        )
        assert again == raw, v["hex"]
        # Through the dict form, as a script edits a message.
        rebuilt = jaus.Message.from_dict(m.name, m.to_dict())
        assert rebuilt == m
        assert jaus.encode(rebuilt) == raw[16:], v["hex"]
        # And the body alone.
        assert jaus.decode(raw[16:], m.code) == m
        codes.add(m.code)
    assert len(codes) >= 158


def test_header_fields_are_attributes(vectors):
    v = vectors[0]
    p = jaus.decode_packet(bytes.fromhex(v["hex"]))
    h = v["header"]
    assert p.priority == h["priority"]
    assert p.ack_nak == ["none", "request", "nak", "ack"][h["ack_nak"]]
    assert p.service_connection == bool(h["sc_flag"])
    assert p.experimental == bool(h["exp_flag"])
    assert p.version == h["version"]
    assert p.command_code == h["command_code"]
    assert p.destination == tuple(h["destination"])
    assert p.source == tuple(h["source"])
    assert p.data_size == h["data_size"]
    assert p.data_flag == "single"
    assert p.sequence_number == h["sequence_number"]
    assert p.body == bytes.fromhex(v["hex"])[16:]


def test_to_dict_and_to_json_are_the_cli_line(cli_lines):
    assert len(cli_lines) >= 5
    for case in cli_lines:
        p = jaus.decode_packet(bytes.fromhex(case["hex"]))
        # Text for text.
        assert p.to_json() == case["cli"]
        line = json.loads(case["cli"])
        assert p.to_dict() == line
        assert p.header_dict() == line["header"]
        assert p.name == line["message"]
        assert p.message.to_dict() == line["fields"]
        assert json.loads(p.message.to_json()) == line["fields"]
        # Dict order is wire order, as in the CLI's text.
        assert list(p.message.to_dict()) == list(line["fields"])


def test_attribute_access_reads_fields_in_the_cli_units(cli_lines):
    case = next(c for c in cli_lines if '"ReportGlobalPose"' in c["cli"])
    fields = json.loads(case["cli"])["fields"]
    m = jaus.decode_packet(bytes.fromhex(case["hex"])).message
    assert m.name == "ReportGlobalPose"
    assert m.code == 0x4402
    assert m.latitude == fields["latitude"]
    assert m["longitude"] == fields["longitude"]
    assert m.fields == list(fields)
    # A nested record is an object with attributes, and equals its dict.
    ts = m.time_stamp
    assert isinstance(ts, jaus.Record)
    assert ts.hour == fields["time_stamp"]["hour"]
    assert ts == fields["time_stamp"]
    assert ts.to_dict() == fields["time_stamp"]
    assert list(ts) == list(fields["time_stamp"])
    assert "latitude" in dir(m)
    with pytest.raises(AttributeError, match="no field `nope`.*latitude"):
        m.nope


def test_lists_of_records_are_lists_of_objects(cli_lines):
    case = next(c for c in cli_lines if '"ReportServices"' in c["cli"])
    fields = json.loads(case["cli"])["fields"]
    m = jaus.decode_packet(bytes.fromhex(case["hex"])).message
    key = next(k for k, v in fields.items() if isinstance(v, list) and v and isinstance(v[0], dict))
    items = getattr(m, key)
    assert isinstance(items, list) and len(items) == len(fields[key])
    assert all(isinstance(i, jaus.Record) for i in items)
    assert [i.to_dict() for i in items] == fields[key]


def test_absent_optional_field_reads_none(vectors):
    v = next(
        v for v in vectors if v["message"] == "ReportGlobalPose" and v["variant"] == "pv_all_off"
    )
    m = jaus.decode_packet(bytes.fromhex(v["hex"])).message
    assert m.fields == []
    assert m.latitude is None
    assert "latitude" not in m


def test_message_builds_from_keywords_and_encodes():
    m = jaus.message("SetTravelSpeed", speed=2.0)
    assert m.name == "SetTravelSpeed" and m.code == 0x040A
    assert jaus.encode(m) == bytes([13, 0])
    assert m.encode() == bytes([13, 0])
    back = jaus.decode(bytes([13, 0]), 0x040A)
    assert abs(back.speed - 2.0) < 10_000 / 65_535
    pkt = jaus.encode_packet(m, (1, 2, 3, 4), "5.6.7.8", priority=7)
    p = jaus.decode_packet(pkt)
    assert p.source == (1, 2, 3, 4) and p.destination == (5, 6, 7, 8)
    assert p.priority == 7 and p.name == "SetTravelSpeed"
    assert p.message == back


def test_messages_and_docs():
    names = jaus.messages()
    assert len(names) >= 160
    assert "ReportGlobalPose" in names and len(set(names)) == len(names)
    text = jaus.doc("ReportGlobalPose")
    assert "0x4402" in text and "latitude" in text
    assert jaus.decode(bytes([13, 0]), 0x040A).doc().startswith("SetTravelSpeed (0x040A)")
    with pytest.raises(jaus.JausError, match="SetTravelSpeed"):
        jaus.doc("SetTravelSped")


def test_bad_bytes_raise_decode_error_naming_message_field_and_offset(vectors):
    v = next(
        v for v in vectors if v["message"] == "ReportGlobalPose" and v["variant"] == "pv_all_on"
    )
    body = bytes.fromhex(v["hex"])[16:]
    with pytest.raises(jaus.DecodeError) as e:
        jaus.decode(body[:-3], 0x4402)
    err = e.value
    assert isinstance(err, jaus.JausError) and isinstance(err, ValueError)
    assert err.message == "ReportGlobalPose"
    assert err.field == "ReportGlobalPose.time_stamp"
    assert err.offset == len(body) - 4
    assert "ReportGlobalPose" in str(err) and f"at byte {len(body) - 4}" in str(err)
    # Trailing bytes, an unknown code, a short header.
    with pytest.raises(jaus.DecodeError, match="trailing"):
        jaus.decode(body + b"\x00", 0x4402)
    with pytest.raises(jaus.DecodeError, match="unknown command code 0xD0D0") as e:
        jaus.decode(b"", 0xD0D0)
    assert e.value.offset is None
    with pytest.raises(jaus.DecodeError, match="header"):
        jaus.decode_packet(b"\x06\x02")


def test_bad_fields_raise_encode_error_naming_the_field():
    with pytest.raises(jaus.EncodeError) as e:
        jaus.message("SetTravelSpeed", speed=20_000.0).encode()
    assert e.value.message == "SetTravelSpeed"
    assert e.value.field == "SetTravelSpeed.speed"
    assert "outside" in str(e.value)
    with pytest.raises(jaus.EncodeError, match="unknown field `sped`"):
        jaus.message("SetTravelSpeed", sped=2.0)
    with pytest.raises(jaus.EncodeError, match="SetTravelSpeed.speed") as e:
        jaus.message("SetTravelSpeed", speed="fast")
    assert e.value.field == "SetTravelSpeed.speed"
    with pytest.raises(jaus.JausError, match="did you mean SetTravelSpeed"):
        jaus.message("SetTravelSped", speed=2.0)
    with pytest.raises(TypeError):
        jaus.message("SetTravelSpeed", speed=object())
