"""GSPro Open Connect v1 live: the messages on the wire, replies split from a byte stream, every failure said.

A small GSPro Connect stands in for the real one (:class:`FakeGSPro`): a TCP server on 127.0.0.1,
port 0, that reads a byte stream, splits it into JSON objects with its own parser
(``json.JSONDecoder.raw_decode``, not the code under test's brace counter), records each message and
answers as told: 200, 501, two replies in one packet, nothing, text that is not JSON, or a closed
connection. The protocol as documented: the vendor's page https://gsprogolf.com/GSProConnectV1.html
and PinPoint-Golf/libgspro docs/protocol.md §2-5 (no framing; 200 accepts a shot; 201-203 arrive
unsolicited; 501/5XX fail; Speed mph, angles deg, spins rpm, carry yd; SpinAxis and SideSpin
positive to the right, a right-hander's fade). Expected values are computed here from the
definitions (1 mph = 0.44704 m/s, 1 yd = 0.9144 m, both exact) and trigonometry, not by the code.
"""

import json
import math
import socket
import threading

import numpy as np
import pytest
import xarray as xr

import impactlab
from impactlab.cli import main
from impactlab.io.gspro_connect import (GSProConnectError, JsonStreamSplitter, NotJsonError, parse_address,
                                        send_shots)
from impactlab.io.interchange import gspro_shots

OK = b'{"Code":200,"Message":"Shot received successfully"}'
PLAYER = b'{"Code":201,"Message":"GSPro Player Information","Player":{"Handed":"RH","Club":"DR"}}'
FAILURE = b'{"Code":501,"Message":"Failure occurred"}'
CLOSE = object()
WAIT = 30.0  # seconds the fake server waits for anything: generous, only a hang reaches it

#: how the fake server answers message number i (from 0): bytes to send in one write, None for nothing,
#: CLOSE to close the connection
ANSWERS = {
    "ok": lambda i: OK,
    "reject": lambda i: FAILURE,
    "double": lambda i: OK + PLAYER,                     # two replies in one packet, as GSPro sends them
    "silent": lambda i: None,
    "close": lambda i: CLOSE,
    "not_json": lambda i: b"HTTP/1.1 400 Bad Request\r\n\r\n",
    "bad_object": lambda i: b'{"Code": two hundred}',
    "second_rejected": lambda i: OK if i == 0 else FAILURE,
}


class FakeGSPro:
    """A GSPro Connect on 127.0.0.1 (a free port) that records each message and answers as ``mode`` says.

    ``mode`` names an entry of :data:`ANSWERS` or is itself such a function of the message's number; ``greeting``
    is sent on connect; ``close_after`` closes the connection after that many messages (the client's wait for late
    replies then ends on the close, not on a clock). It splits the client's stream with
    ``json.JSONDecoder.raw_decode``, not the code under test's splitter. tests/test_trust_outside.py uses it too."""

    def __init__(self, mode="ok", greeting=b"", close_after=None):
        self.answer = ANSWERS[mode] if isinstance(mode, str) else mode
        self.greeting = greeting
        self.close_after = close_after
        self.messages = []          # each message as parsed JSON
        self.raw = bytearray()      # every byte received
        self.done = threading.Event()
        self.error = None
        self.listener = socket.create_server(("127.0.0.1", 0))
        self.listener.settimeout(WAIT)
        self.port = self.listener.getsockname()[1]
        self.address = f"127.0.0.1:{self.port}"
        self.thread = threading.Thread(target=self._serve, daemon=True)

    def __enter__(self):
        self.thread.start()
        return self

    def __exit__(self, *exc_info):
        self.thread.join(WAIT)
        self.listener.close()
        assert not self.thread.is_alive(), "the fake GSPro Connect did not finish"
        if self.error is not None:
            raise self.error

    def _serve(self):
        try:
            connection, _ = self.listener.accept()
            with connection:
                connection.settimeout(WAIT)
                if self.greeting:
                    connection.sendall(self.greeting)
                decoder, text = json.JSONDecoder(), ""
                while True:
                    data = connection.recv(4096)
                    if not data:
                        return  # the client closed
                    self.raw += data
                    text += data.decode("utf-8")
                    while True:
                        text = text.lstrip(" \t\r\n")
                        try:
                            message, end = decoder.raw_decode(text)
                        except ValueError:
                            break  # incomplete: wait for more
                        text = text[end:]
                        answer = self.answer(len(self.messages))
                        self.messages.append(message)
                        if answer is CLOSE:
                            return
                        if answer is not None:
                            connection.sendall(answer)
                        if self.close_after is not None and len(self.messages) == self.close_after:
                            return
        except Exception as exc:  # noqa: BLE001 - re-raised in the test thread
            self.error = exc
        finally:
            self.done.set()


def closed_port() -> int:
    """A port nothing listens on: bound, then closed (the kernel refuses connections to it)."""
    with socket.create_server(("127.0.0.1", 0)) as probe:
        return probe.getsockname()[1]


def hand_dataset(handedness=1.0):
    """A delivery result written by hand: two cases of one model, face angle swept, the rest in the base scene."""
    values = {"ball_speed": [70.0, 65.0], "vertical_launch_angle": [12.5, 13.0],
              "horizontal_launch_angle": [-1.0, 3.0], "spin_rate": [3000.0, 2500.0], "spin_axis": [-10.0, 20.0],
              "carry_distance": [200.0, 180.0]}
    units = {"ball_speed": "m/s", "spin_rate": "rpm", "carry_distance": "m"}
    data = {name: (("model", "face_angle"), [column], {"units": units.get(name, "deg")})
            for name, column in values.items()}
    scene = {"speed": 44.704, "attack_angle": math.radians(-3.0), "dynamic_loft": math.radians(15.0),
             "path": math.radians(2.0), "face_angle": 0.0, "handedness": handedness, "friction": 0.4}
    return xr.Dataset(data, coords={
        "model": ["hand"],
        "face_angle": ("face_angle", [-2.0, 4.0], {"units": "deg", "study_path": "delivery.face_angle"}),
    }, attrs={"base_scene_si": json.dumps(scene)})


def expected_messages():
    """The two messages of hand_dataset() as GSPro must receive them, from the definitions."""
    mph, yard = 0.44704, 0.9144
    messages = []
    for number, (speed, vla, hla, spin, axis, carry, face) in enumerate(
            [(70.0, 12.5, -1.0, 3000.0, -10.0, 200.0, -2.0), (65.0, 13.0, 3.0, 2500.0, 20.0, 180.0, 4.0)], start=1):
        messages.append({
            "DeviceID": "impactlab", "Units": "Yards", "ShotNumber": number, "APIversion": "1",
            "BallData": {"Speed": round(speed / mph, 2), "SpinAxis": axis, "TotalSpin": spin,
                         "BackSpin": round(spin * math.cos(math.radians(axis)), 1),
                         "SideSpin": round(spin * math.sin(math.radians(axis)), 1),
                         "HLA": hla, "VLA": vla, "CarryDistance": round(carry / yard, 1)},
            "ClubData": {"Speed": 100.0, "AngleOfAttack": -3.0, "FaceToTarget": face, "Loft": 15.0, "Path": 2.0},
            "ShotDataOptions": {"ContainsBallData": True, "ContainsClubData": True, "LaunchMonitorIsReady": True,
                                "LaunchMonitorBallDetected": True, "IsHeartBeat": False},
        })
    return messages


def test_each_shot_reaches_gspro_as_the_documented_v1_message():
    with FakeGSPro("ok") as server:
        replies = send_shots(gspro_shots(hand_dataset()), "127.0.0.1", server.port, timeout=WAIT)
    assert [reply.code for reply in replies] == [200, 200]
    assert server.messages == expected_messages()
    first = server.messages[0]["BallData"]
    assert first["Speed"] == 156.59  # 70 m/s / 0.44704 = 156.5855 mph
    assert (first["BackSpin"], first["SideSpin"], first["CarryDistance"]) == (2954.4, -520.9, 218.7)
    # the vendor's key spellings byte for byte (clients also send APIVersion, Backspin), no trace block
    assert b'"APIversion":"1"' in server.raw and b'"BackSpin"' in server.raw and b'"impactlab":' not in server.raw


def test_spin_axis_and_side_spin_share_their_sign_positive_right():
    shots = gspro_shots(hand_dataset())
    draw, fade = shots[0]["BallData"], shots[1]["BallData"]
    assert draw["SpinAxis"] < 0 and draw["SideSpin"] < 0      # tilted left: a right-hander's draw
    assert fade["SpinAxis"] > 0 and fade["SideSpin"] > 0      # tilted right: a fade
    for ball in (draw, fade):
        assert math.hypot(ball["BackSpin"], ball["SideSpin"]) == pytest.approx(ball["TotalSpin"], abs=0.1)


def test_a_left_handers_club_angles_are_sent_right_positive_like_the_ball():
    right, left = gspro_shots(hand_dataset(1.0)), gspro_shots(hand_dataset(-1.0))
    for rh, lh in zip(right, left):
        assert lh["ClubData"]["FaceToTarget"] == -rh["ClubData"]["FaceToTarget"]
        assert lh["ClubData"]["Path"] == -rh["ClubData"]["Path"]
        assert lh["ClubData"]["AngleOfAttack"] == rh["ClubData"]["AngleOfAttack"]


def test_a_result_without_carry_or_handedness_leaves_those_out_rather_than_guess():
    dataset = hand_dataset().drop_vars("carry_distance")
    scene = json.loads(dataset.attrs["base_scene_si"])
    del scene["handedness"]
    dataset.attrs["base_scene_si"] = json.dumps(scene)
    shot = gspro_shots(dataset)[0]
    assert "CarryDistance" not in shot["BallData"]
    assert set(shot["ClubData"]) == {"Speed", "AngleOfAttack", "Loft"}
    assert shot["ShotDataOptions"]["ContainsClubData"] is True


def test_two_replies_in_one_packet_answer_one_shot_and_note_the_player():
    lines = []
    with FakeGSPro("double") as server:
        replies = send_shots(gspro_shots(hand_dataset()), "127.0.0.1", server.port, timeout=WAIT,
                             progress=lines.append)
    assert [reply.code for reply in replies] == [200, 200] and len(server.messages) == 2
    # the 201 that came with the first 200 is read before the second shot's 200, and said, not taken as its answer
    assert len(lines) == 2 and all("Code 201" in line and "Club DR" in line for line in lines)


def test_the_greeting_gspro_may_send_is_skipped():
    with FakeGSPro("ok", greeting=b"GSPro ready") as server:
        replies = send_shots(gspro_shots(hand_dataset()), "127.0.0.1", server.port, timeout=WAIT)
    assert len(replies) == 2


@pytest.mark.parametrize("mode, words", [
    ("reject", "did not accept shot 1 of 2 (ShotNumber 1; model hand, face_angle -2.0): Code 501: Failure occurred"),
    ("second_rejected", "did not accept shot 2 of 2"),
    ("silent", "sent no reply to shot 1 of 2"),
    ("close", "closed the connection"),
    ("not_json", "text that is not a JSON object: b'HTTP/1.1 400"),
    ("bad_object", "a reply that is not JSON: b'{\"Code\": two hundred}'"),
])
def test_every_failure_is_said_with_how_many_shots_got_through(mode, words):
    with FakeGSPro(mode) as server:
        with pytest.raises(GSProConnectError) as caught:
            send_shots(gspro_shots(hand_dataset()), "127.0.0.1", server.port,
                       timeout=0.5 if mode == "silent" else WAIT)
    text = str(caught.value)
    assert f"GSPro Connect at 127.0.0.1:{server.port}" in text
    assert words in text
    accepted = 1 if mode == "second_rejected" else 0
    assert text.endswith(f"{accepted} of 2 shot(s) were accepted before it")
    assert caught.value.exit_code == 3


def test_splitting_a_stream_does_not_depend_on_how_it_was_cut():
    stream = b' {"Message":"a } and a { in a string","Code":200}\r\n{"Code":201,"Player":{"Club":"DR"}}' \
             b'{"Message":"an escaped \\" quote }","Code":202}'
    objects = [b'{"Message":"a } and a { in a string","Code":200}', b'{"Code":201,"Player":{"Club":"DR"}}',
               b'{"Message":"an escaped \\" quote }","Code":202}']
    assert JsonStreamSplitter().feed(stream) == objects
    splitter, found = JsonStreamSplitter(), []
    for byte in stream:  # one byte per read
        found += splitter.feed(bytes([byte]))
    assert found == objects and not splitter.pending
    assert [json.loads(text)["Code"] for text in found] == [200, 201, 202]


def test_splitting_refuses_what_is_not_an_object_and_what_is_too_long():
    with pytest.raises(NotJsonError, match="HTTP"):
        JsonStreamSplitter().feed(b"HTTP/1.1 200 OK")
    with pytest.raises(NotJsonError):
        JsonStreamSplitter().feed(b"GSPro readyX")
    assert JsonStreamSplitter().feed(b"GSPro ready" + OK) == [OK]
    with pytest.raises(NotJsonError, match="longer than 64 bytes"):
        JsonStreamSplitter(limit=64).feed(b'{"Message":"' + b"x" * 100)


@pytest.mark.parametrize("text, address", [("127.0.0.1:921", ("127.0.0.1", 921)), ("gspro-pc", ("gspro-pc", 921)),
                                           ("[::1]:922", ("::1", 922)), (" localhost:4000 ", ("localhost", 4000))])
def test_addresses(text, address):
    assert parse_address(text) == address


@pytest.mark.parametrize("text", ["host:0", "host:65536", "host:abc", "a:b:c", "", "[::1"])
def test_bad_addresses_are_refused(text):
    with pytest.raises(impactlab.errors.FieldError, match="--gspro: expected HOST:PORT"):
        parse_address(text)


# ---- the command line: exit status and one message, no traceback ----

STUDY = {
    "name": "gspro_live",
    "ball": {"preset": "urethane_tour"}, "face": {"preset": "steel", "mass": "200 g"},
    "contact": {"friction": 0.4, "restitution": 0.78},
    "delivery": {"club_speed": "90 mph", "attack_angle": "-4 deg", "dynamic_loft": "24 deg", "path": "1 deg",
                 "face_angle": "0 deg", "handedness": "left"},
    "sweep": {"delivery.face_angle": ["-3 deg", "3 deg"]},
    "models": ["rigid_coulomb"],
    "outputs": ["ball_speed", "vertical_launch_angle", "horizontal_launch_angle", "spin_rate", "spin_axis"],
}


@pytest.fixture(scope="module")
def result_file(tmp_path_factory):
    from impactlab.io.results import write_results

    path = tmp_path_factory.mktemp("gspro") / "live.h5"
    write_results(impactlab.run_study(impactlab.load_study(STUDY), executor="serial"), path)
    return path


def test_cli_sends_what_the_file_export_writes(result_file, tmp_path, capsys):
    with FakeGSPro("ok") as server:
        assert main(["export", str(result_file), "--gspro", server.address]) == 0
    assert main(["export", str(result_file), "-o", str(tmp_path / "shots.json")]) == 0
    written = json.loads((tmp_path / "shots.json").read_text())
    assert server.messages == [{key: value for key, value in shot.items() if key != "impactlab"} for shot in written]
    err = capsys.readouterr().err
    assert "sent 2 shot(s)" in err and "every one accepted" in err
    # the study's own delivery, in GSPro's units and signs (left-handed: an open face and in-to-out path go left)
    for message, face in zip(server.messages, (-3.0, 3.0)):
        club = message["ClubData"]
        assert club == {"Speed": 90.0, "AngleOfAttack": -4.0, "FaceToTarget": -face, "Loft": 24.0, "Path": -1.0}
        assert np.sign(message["BallData"]["HLA"]) == -np.sign(face)


@pytest.mark.parametrize("mode, status, words", [
    ("refused", 3, "refused the connection: nothing listens there"),
    ("silent", 3, "sent no reply to shot 1 of 2 (ShotNumber 1; model rigid_coulomb, face_angle -3.0) within 0.5 s"),
    ("reject", 3, "did not accept shot 1 of 2 (ShotNumber 1; model rigid_coulomb, face_angle -3.0): "
                  "Code 501: Failure occurred; 0 of 2 shot(s) were accepted before it"),
])
def test_cli_failures_end_with_one_line_and_status_3(result_file, capsys, mode, status, words):
    if mode == "refused":
        code = main(["export", str(result_file), "--gspro", f"127.0.0.1:{closed_port()}", "--timeout", "5"])
    else:
        with FakeGSPro(mode) as server:
            code = main(["export", str(result_file), "--gspro", server.address, "--timeout", "0.5"])
    err = capsys.readouterr().err
    assert code == status
    assert words in err and "Traceback" not in err and len(err.strip().splitlines()) == 1


def test_cli_bad_address_or_timeout_is_bad_input(result_file, capsys):
    assert main(["export", str(result_file), "--gspro", "127.0.0.1:99999"]) == 2
    assert "--gspro: expected HOST:PORT" in capsys.readouterr().err
    with pytest.raises(SystemExit) as stopped:
        main(["export", str(result_file), "--gspro", "127.0.0.1:921", "--timeout", "0"])
    assert stopped.value.code == 2 and "seconds > 0" in capsys.readouterr().err
    with pytest.raises(SystemExit) as stopped:
        main(["export", str(result_file)])
    assert stopped.value.code == 2 and "one of the arguments -o/--output --gspro is required" in capsys.readouterr().err
