"""A vendor's overlay loaded at run time (the vendor-rover example)."""

import pytest

import jaus


def test_vendor_message_round_trips(vendor_overlay):
    schema = jaus.Schema.load([vendor_overlay])
    assert "ReportTankLevels" in schema.messages()
    assert "ReportTankLevels" not in jaus.messages()
    assert schema.code("ReportTankLevels") == 0xD101
    assert schema.name(0xD101) == "ReportTankLevels"
    assert schema.fields("ReportTankLevels") == ["time_stamp", "levels"]
    m = schema.message(
        "ReportTankLevels",
        time_stamp={"millisecond": 5, "second": 6, "minute": 7, "hour": 8, "day": 9},
        levels=[0.0, 50.0, 100.0],
    )
    body = schema.encode(m)
    assert jaus.encode(m) == body  # a message encodes by the schema it was made with
    back = schema.decode(body, 0xD101)
    assert back.time_stamp.hour == 8
    assert [round(x) for x in back.levels] == [0, 50, 100]
    assert schema.encode(back) == body
    pkt = schema.encode_packet(back, (1, 1, 210, 1), (1, 1, 1, 1))
    p = schema.decode_packet(pkt)
    assert p.name == "ReportTankLevels" and p.message == back
    assert schema.from_dict("ReportTankLevels", back.to_dict()) == back
    assert "Tank" in schema.doc("ReportTankLevels")
    # The SDK's schema does not know the code: the packet is raw.
    raw = jaus.decode_packet(pkt)
    assert raw.message is None and raw.name == "Raw"
    assert raw.to_dict()["fields"]["code"] in (0xD101, "0xD101")


def test_bad_overlay_raises_spec_error(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("group: bad\nmessages:\n  - name: Broken\n    code: 0xD200\n    fields:\n      - { name: x, type: nonesuch }\n")
    with pytest.raises(jaus.SpecError, match="bad.yaml"):
        jaus.Schema.load([bad])
