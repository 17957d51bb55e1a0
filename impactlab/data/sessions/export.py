"""A session's measured shots as GSPro Open Connect v1 messages (``impactlab export SESSION -o shots.json``).

Each shot the row rules and the flight keep (:func:`impactlab.data.sessions.flight.flight_rows`: a ball speed, a
launch angle and a spin rate, no rule broken, no launch value the monitor flags unless asked) becomes one message in
the units and signs :func:`impactlab.io.interchange.gspro_shots` writes (ball speed in mph, angles in deg, spins in
rpm, spin axis and HLA positive to the right); the monitor's club data ride along where the row has them. A shot
without a spin axis or launch direction is sent with 0 and said (GSPro needs both).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from impactlab.data.sessions.flight import flight_rows
from impactlab.data.sessions.json_records import JSON_SESSIONS
from impactlab.data.sessions.reader import DATASETS, Session
from impactlab.units import MPH

#: session field -> GSPro ClubData key (degrees, except the speed in mph)
CLUB_KEYS = {"club_speed": "Speed", "attack_angle": "AngleOfAttack", "path": "Path", "face_angle": "FaceToTarget",
             "dynamic_loft": "Loft", "face_to_path": "FaceToPath"}


def is_session(name: str) -> bool:
    """Whether ``name`` is a session (an export file or a shipped session dataset), not a result file."""
    path = Path(name)
    return (name in DATASETS and not path.exists()) or path.suffix.lower() in (".csv", ".gz", *JSON_SESSIONS)


def session_messages(session: Session, device_id: str = "impactlab", include_flagged: bool = False,
                     first_shot: int = 1) -> tuple[list[dict], list, int]:
    """(messages, ``(line, reason)`` of each row not sent, rows sent with a spin axis or launch direction of 0)."""
    fly, _, skipped = flight_rows(session, include_flagged)
    v = session.values
    messages, zeroed = [], 0
    for number, row in enumerate(np.flatnonzero(fly).tolist(), start=first_shot):
        axis, direction = v["spin_axis"][row], v["horizontal_launch_angle"][row]
        zeroed += int(not (np.isfinite(axis) and np.isfinite(direction)))
        axis, direction = np.nan_to_num(axis), np.nan_to_num(direction)
        spin = v["spin_rate"][row] * 30.0 / math.pi
        ball = {"Speed": round(v["ball_speed"][row] / MPH, 2), "SpinAxis": round(math.degrees(axis), 2),
                "TotalSpin": round(spin, 1), "BackSpin": round(spin * math.cos(axis), 1),
                "SideSpin": round(spin * math.sin(axis), 1), "HLA": round(math.degrees(direction), 2),
                "VLA": round(math.degrees(v["vertical_launch_angle"][row]), 2)}
        club = {key: round(v[field][row] / MPH if field == "club_speed" else math.degrees(v[field][row]), 2)
                for field, key in CLUB_KEYS.items() if np.isfinite(v[field][row])}
        message = {"DeviceID": device_id, "Units": "Yards", "ShotNumber": number, "APIversion": "1",
                   "BallData": ball}
        if club:
            message["ClubData"] = club
        message["ShotDataOptions"] = {"ContainsBallData": True, "ContainsClubData": bool(club),
                                      "LaunchMonitorIsReady": True, "LaunchMonitorBallDetected": True,
                                      "IsHeartBeat": False}
        message["impactlab"] = {"file": str(session.file), "line": int(session.lines[row])}
        messages.append(message)
    return messages, skipped, zeroed
