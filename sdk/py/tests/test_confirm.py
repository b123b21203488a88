"""`Client.send(..., confirm=True)`: a command confirmed by its effect. The demo
vehicle (`jaus node`) acknowledges; a driver hand-rolled here never does (as OpenJAUS
3.3's components), so its commands are confirmed by reading the value back, and a
Resume that leaves it in Standby raises, saying so."""

import socket
import threading

import pytest

import jaus

GWD = "1.1.45.1"  # the demo vehicle's Global Waypoint Driver
DRIVER = "30.1.45.1"  # the silent driver


def judp(packet):
    return b"\x01\x00\x00" + len(packet).to_bytes(2, "big") + packet


class SilentDriver:
    """Grants control, keeps a travel speed and stays in Standby whatever it is told
    (Resume does nothing); answers Query Travel Speed and Query Component Status;
    never sends ACK/NAK."""

    def __init__(self):
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.bind(("127.0.0.1", 0))
        self.sock.settimeout(0.05)
        self.peer = "127.0.0.1:%d" % self.sock.getsockname()[1]
        self.speed = 0.0
        self.running = True
        self.thread = threading.Thread(target=self.run, daemon=True)
        self.thread.start()

    def reply(self, message, to, addr):
        packet = jaus.encode_packet(message, source=DRIVER, destination=to)
        self.sock.sendto(judp(packet), addr)

    def run(self):
        while self.running:
            try:
                data, addr = self.sock.recvfrom(9000)
            except socket.timeout:
                continue
            if len(data) < 21 or data[0] != 1:
                continue
            try:
                p = jaus.decode_packet(data[5:])
            except jaus.JausError:
                continue
            if ".".join(map(str, p.destination)) != DRIVER or p.message is None:
                continue
            m = p.message
            if m.name == "RequestComponentControl":
                self.reply(
                    jaus.message("ConfirmComponentControl", response_code="ControlAccepted"),
                    p.source,
                    addr,
                )
            elif m.name == "SetTravelSpeed":
                self.speed = m.speed
            elif m.name == "QueryTravelSpeed":
                self.reply(jaus.message("ReportTravelSpeed", speed=self.speed), p.source, addr)
            elif m.name == "QueryComponentStatus":
                self.reply(
                    jaus.message(
                        "ReportComponentStatus",
                        primary_status_code="Standby",
                        secondary_status_code=0,
                    ),
                    p.source,
                    addr,
                )

    def stop(self):
        self.running = False
        self.thread.join()
        self.sock.close()


@pytest.fixture
def driver():
    d = SilentDriver()
    yield d
    d.stop()


def test_an_acknowledging_component_is_acknowledged(vehicle):
    with jaus.Client(peer=vehicle.peer, bind="127.0.0.1:0") as c:
        with c.control(GWD, authority=10):
            done = c.send(GWD, jaus.SetTravelSpeed(speed=1.0), confirm=True)
            assert done.outcome == "acknowledged"
            assert done.detail == ""
            assert str(done) == "acknowledged"
            with pytest.raises(jaus.ClientError) as e:
                c.send(GWD, jaus.SetTravelSpeed(speed=50.0), confirm=True)
            assert e.value.outcome == "refused"
            assert "[0, 2] m/s" in e.value.detail


def test_a_silent_component_is_confirmed_by_read_back_or_not(vehicle, driver):
    # The vehicle lets the client settle; the driver is reached through the peers.
    with jaus.Client(peer=[vehicle.peer, driver.peer], bind="127.0.0.1:0") as c:
        control = jaus.message("RequestComponentControl", authority_code=10)
        done = c.send(DRIVER, control, confirm=True, timeout=2)
        assert done.outcome == "confirmed_by_readback"
        assert done.detail == "Confirm Component Control ControlAccepted"
        done = c.send(DRIVER, jaus.SetTravelSpeed(speed=2.5), confirm=True, timeout=2)
        assert done.outcome == "confirmed_by_readback", done
        assert done.detail == "Report Travel Speed 2.44 m/s"
        assert str(done) == "confirmed by read-back: Report Travel Speed 2.44 m/s"
        assert abs(driver.speed - 2.44) < 0.01
        # A Resume that leaves it in Standby is reported, not ignored.
        with pytest.raises(jaus.ClientError) as e:
            c.send(DRIVER, jaus.message("Resume"), confirm=True, timeout=1)
        assert e.value.outcome == "not_confirmed"
        assert e.value.address == DRIVER and e.value.message == "Resume"
        text = str(e.value)
        assert "still Standby after Resume (Ready expected)" in text, text
        # Learnt from the commands before: it never acknowledges.
        assert "30.1.45.1 never acknowledges (OpenJAUS 3.3 components send no ACK/NAK)" in text
