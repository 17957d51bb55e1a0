"""Send shots live to GSPro Open Connect v1: one TCP connection, one JSON message per shot, one reply each.

The protocol (the vendor's page https://gsprogolf.com/GSProConnectV1.html; what it leaves out is
established in PinPoint-Golf/libgspro ``docs/protocol.md``, commit 543a801, from about sixteen
client implementations, and gathered in the project's notes on vendors):

- GSPro Connect is a TCP server on port 921 (922 with its ``OpenAPIUseAltPort`` setting); the
  launch monitor connects and sends; no authentication, no handshake.
- Messages are JSON objects with **no framing**: no delimiter, no length prefix. A read can hold
  part of a reply, one reply or several: GSPro itself sends ``{...200...}{...201...}`` in one
  segment. Replies are therefore split from the byte stream where the JSON decoder ends each object
  (:class:`JsonStreamSplitter`, on ``json.JSONDecoder.raw_decode``), never by newlines or by reads.
- Each shot is answered with ``{"Code": 200, "Message": ...}``; ``201`` (player information:
  handedness and club), ``202`` ("GSPro ready") and ``203`` ("GSPro round ended") arrive on their
  own, not as answers, and are noted; ``501`` / ``5XX`` is a failure. Clients key on ``Code``,
  never on ``Message`` (its text varies).

How replies are paired with shots (issue 35): a reply answers a shot only if it arrives after the shot
was sent and while the shot waits for its answer. Whatever arrived before a shot is sent (a stray
``{"Code":200}`` on connect, a second 200 after the previous shot's) is read first, set aside and said,
never taken as the next shot's answer; so is anything that arrives after the last shot's answer. The
notices (201-203) are counted: the first of each kind is said, repeats only in the closing count (a server
sending 201s for 2 s printed 7,194 lines). Every text of the server's is shown escaped
(:func:`impactlab.foreign.shown`).

Why the standard library: no package on PyPI speaks this protocol (none is named for GSPro in
PyPI's index), and a client is a socket and ``json``.
"""

from __future__ import annotations

import json
import re
import select
import socket
import time
from collections import Counter
from collections.abc import Callable, Sequence

import attrs

from impactlab.errors import EnvironmentFault, FieldError
from impactlab.foreign import MAX_NESTING, json_depth_exceeded, shown
from impactlab.io.interchange import wire_message
from impactlab.io.json_stream import JsonObjectStream, NotJsonError

#: GSPro Connect's port (the vendor writes "0921")
DEFAULT_PORT = 921
#: the reply that accepts a shot
ACCEPTED = 200
#: messages GSPro sends of its own accord (player information, ready, round ended): not answers to a shot
UNSOLICITED = {201: "player information", 202: "GSPro ready", 203: "GSPro round ended"}
#: a reply longer than this is not GSPro's (a message is normally 300-900 bytes; libgspro bounds at 64 KiB)
MAX_REPLY_BYTES = 64 * 1024
#: a bare greeting one client's notes say GSPro may send at connection (samiur/gc2-connect-desktop,
#: docs/GSPRO_TCP_PROTOCOL.md): tolerated, anything else outside a JSON object is not
GREETING = b"GSPro ready"


class GSProConnectError(EnvironmentFault):
    """GSPro Connect could not be reached, did not answer, or refused a shot (exit status 3)."""


class JsonStreamSplitter(JsonObjectStream):
    """GSPro's reply stream split into its JSON objects (:class:`~impactlab.io.json_stream.JsonObjectStream`:
    ``json.JSONDecoder.raw_decode``), the bare greeting :data:`GREETING` skipped, a reply over ``limit`` bytes
    refused. Whether a reply carries a Code is :func:`parse_reply`'s to decide."""

    def __init__(self, limit: int = MAX_REPLY_BYTES):
        super().__init__(limit, skip=GREETING)


@attrs.frozen
class Reply:
    """One message from GSPro Connect: its ``Code``, its ``Message`` and the whole object."""

    code: int
    message: str
    body: dict

    def describe(self) -> str:
        """``Code 501: Bad JSON data``, with the player of a 201."""
        # the server's words are foreign text: escaped (a Message holding ESC [2J cleared the user's screen, and a
        # CR LF forged a line of impactlab's own output), and cut to a line's length
        text = f"Code {self.code}: {_cut(shown(self.message)) if self.message else '(no Message)'}"
        player = self.body.get("Player")
        if isinstance(player, dict) and player:
            text += " (" + _cut(", ".join(f"{shown(key)} {shown(value)}" for key, value in player.items())) + ")"
        return text


#: the most characters of a server's Message shown (a reply may be 64 KiB long)
MAX_SHOWN = 200


def _cut(text: str) -> str:
    return text if len(text) <= MAX_SHOWN else f"{text[:MAX_SHOWN]}... ({len(text):,} characters)"


def parse_reply(text: bytes) -> Reply:
    """One object split from the stream, read as a reply; NotJsonError if it is not JSON or has no integer Code."""
    try:
        decoded = text.decode("utf-8")
    except UnicodeDecodeError:
        raise NotJsonError(text, "a reply that is not JSON") from None
    if json_depth_exceeded(decoded):  # json.loads recurses once per level: a reply 30,000 deep was a RecursionError
        raise NotJsonError(text, f"a reply whose JSON nests more than {MAX_NESTING} levels deep (GSPro's nest 2)")
    try:
        body = json.loads(decoded)
    except ValueError:
        raise NotJsonError(text, "a reply that is not JSON") from None
    code = body.get("Code") if isinstance(body, dict) else None
    if isinstance(code, float) and code.is_integer():
        code = int(code)
    if not isinstance(code, int) or isinstance(code, bool):
        raise NotJsonError(text, "a JSON reply without an integer Code")
    message = body.get("Message")
    return Reply(code, message if isinstance(message, str) else "", body)


def parse_address(text: str) -> tuple[str, int]:
    """``HOST:PORT`` (or ``HOST``, port 921; ``[::1]:921`` for IPv6) as (host, port).

    Raises
    ------
    FieldError
        At ``--gspro``, for text that is not such an address or a port outside 1-65535.
    """
    expected = "HOST:PORT, e.g. 127.0.0.1:921 (HOST alone means port 921; [ADDRESS]:PORT for IPv6)"
    match = re.fullmatch(r"\[([0-9A-Fa-f:.%\w]+)\](?::(\w*))?|([^:\[\]\s]+)(?::(\w*))?", text.strip())
    if not match:
        raise FieldError("--gspro", expected, text)
    host = match.group(1) or match.group(3)
    port_text = match.group(2) if match.group(1) else match.group(4)
    if port_text is None:
        return host, DEFAULT_PORT
    if not port_text.isdigit() or not 1 <= int(port_text) <= 65535:
        raise FieldError("--gspro", f"{expected}, with a port from 1 to 65535", text)
    return host, int(port_text)


class OpenConnectClient:
    """A connection to GSPro Connect that sends shots one at a time and waits for each one's reply.

    Parameters
    ----------
    host, port : str, int
        Where GSPro Connect listens (:func:`parse_address`).
    timeout : float
        Seconds to wait for the connection, and for the reply to each shot.

    on_notice : callable, optional
        Called with a line of text for the first message of each kind GSPro sends of its own accord (201, 202,
        203), and for each reply set aside (one that answered no shot); repeats are counted in
        :attr:`notice_counts` and :attr:`set_aside`, said once by :meth:`summary`.

    Every failure is a :class:`GSProConnectError` saying what happened: the connection refused or
    not answered, no reply within ``timeout``, the connection closed, a reply that is not JSON, or
    a reply other than 200 (its Code and Message).
    """

    #: the set-aside replies said one by one; beyond, only counted
    SAID_SET_ASIDE = 5

    def __init__(self, host: str, port: int, timeout: float, on_notice: Callable[[str], None] | None = None):
        self.host, self.port, self.timeout = host, port, timeout
        self.on_notice = on_notice
        self.where = f"GSPro Connect at {host}:{port}" if ":" not in host else f"GSPro Connect at [{host}]:{port}"
        self.notices: list[Reply] = []  # the first of each kind
        self.notice_counts: Counter[str] = Counter()  # each kind of notice (its words) -> how many came
        self.set_aside: list[str] = []  # replies that answered no shot, in words (when they came)
        self._splitter = JsonStreamSplitter()
        self._waiting: list[Reply] = []  # replies read but not yet consumed, in order
        self._socket: socket.socket | None = None

    def __enter__(self) -> OpenConnectClient:
        self.connect()
        return self

    def __exit__(self, *exc_info) -> None:
        self.close()

    def connect(self) -> None:
        """Open the connection (TCP_NODELAY: one message, one segment, as GSPro's clients send them)."""
        try:
            self._socket = socket.create_connection((self.host, self.port), timeout=self.timeout)
        except ConnectionRefusedError:
            raise GSProConnectError(
                f"{self.where} refused the connection: nothing listens there (start GSPro Connect, or check "
                f"the port: {DEFAULT_PORT}, or 922 with its OpenAPIUseAltPort setting)") from None
        except socket.gaierror as exc:
            raise GSProConnectError(f"cannot find the host {self.host!r} for GSPro Connect: {exc.strerror}") from None
        except TimeoutError:
            raise GSProConnectError(f"{self.where} did not answer the connection within {self.timeout:g} s "
                                    "(a firewall, or the wrong address? raise --timeout if the network is slow)"
                                    ) from None
        except OSError as exc:
            raise GSProConnectError(f"cannot connect to {self.where}: {exc.strerror or exc}") from None
        self._socket.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)

    def close(self) -> None:
        """Close the connection (a no-op when closed)."""
        if self._socket is not None:
            self._socket.close()
            self._socket = None

    def send(self, payload: bytes, what: str) -> Reply:
        """Send one message (``what`` names it in errors) and return GSPro's 200 reply to it.

        Whatever GSPro sent before the message goes out is read first and set aside (:meth:`settle`): a reply that
        came before its shot answers another, or none.

        Raises
        ------
        GSProConnectError
            On a closed connection, no reply within the timeout, a reply that is not JSON, or a
            Code other than 200 (and the unsolicited 201-203).
        """
        if self._socket is None:
            raise GSProConnectError(f"{self.where}: not connected")
        self.settle(f"before {what} was sent", wait=0.0)
        try:
            self._socket.settimeout(self.timeout)
            self._socket.sendall(payload)
        except TimeoutError:
            raise GSProConnectError(f"{self.where} took none of {what} within {self.timeout:g} s "
                                    "(raise --timeout if GSPro is busy)") from None
        except OSError as exc:  # a reset or broken pipe: the peer went away
            raise GSProConnectError(f"{self.where} closed the connection before {what} was sent "
                                    f"({exc.strerror or exc})") from None
        reply = self._next_answer(what)
        if reply.code != ACCEPTED:
            raise GSProConnectError(f"{self.where} did not accept {what}: {reply.describe()}")
        return reply

    def settle(self, when: str, wait: float = 0.0) -> None:
        """Read what has arrived (waiting up to ``wait`` s for more), noting notices and setting replies aside.

        Called before each shot is sent (``wait`` 0: only what is there) and after the last one's answer (a short
        wait, so that a second 200 to the last shot is seen too).
        """
        if self._socket is None:
            return
        self._take_waiting(when)
        deadline = time.monotonic() + wait
        for _ in range(64):  # at most 256 KiB here: a server that never stops sending is read by the next wait
            remaining = max(deadline - time.monotonic(), 0.0)
            try:
                ready, _, _ = select.select([self._socket], [], [], remaining)
            except (OSError, ValueError):
                return
            if not ready:
                return
            try:
                data = self._socket.recv(4096)
            except (BlockingIOError, TimeoutError):
                return
            except OSError:
                return  # the connection went away: the next send says so
            if not data:
                return
            self._feed(data, f"text {when}")
            self._take_waiting(when)

    def _take_waiting(self, when: str) -> None:
        for reply in self._waiting:
            if reply.code in UNSOLICITED:
                self._note(reply)
            else:
                self._set_aside(reply, when)
        self._waiting.clear()

    def _set_aside(self, reply: Reply, when: str) -> None:
        self.set_aside.append(f"{reply.describe()} {when}")
        if self.on_notice is not None and len(self.set_aside) <= self.SAID_SET_ASIDE:
            self.on_notice(f"{self.where} sent {reply.describe()} {when}: it answers no shot sent, so it is set "
                           "aside (not taken as the next shot's answer)")

    def _feed(self, data: bytes, what: str) -> None:
        try:
            self._waiting.extend(parse_reply(text) for text in self._splitter.feed(data))
        except NotJsonError as exc:
            raise GSProConnectError(f"{self.where} answered {what} with {exc} (is {self.host}:{self.port} "
                                    "GSPro Connect?)") from None

    def _next_answer(self, what: str) -> Reply:
        """The next reply that answers a message, unsolicited ones noted on the way, read before the deadline."""
        deadline = time.monotonic() + self.timeout
        while True:
            while self._waiting:
                reply = self._waiting.pop(0)
                if reply.code in UNSOLICITED:
                    self._note(reply)
                    continue
                return reply
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                raise self._timeout(what)
            assert self._socket is not None, "connected before a reply is awaited"
            self._socket.settimeout(remaining)
            try:
                data = self._socket.recv(4096)
            except TimeoutError:
                raise self._timeout(what) from None
            except OSError as exc:
                raise GSProConnectError(f"{self.where} closed the connection before answering {what} "
                                        f"({exc.strerror or exc})") from None
            if not data:
                partial = " in the middle of a reply" if self._splitter.pending else ""
                raise GSProConnectError(f"{self.where} closed the connection{partial} before answering {what}")
            self._feed(data, what)

    def note_read(self) -> None:
        """Note the unsolicited messages already read (a 201 in the packet of the last 200), without waiting; a reply
        there answers no shot and is set aside."""
        self._take_waiting("after the last shot's answer")

    def _note(self, reply: Reply) -> None:
        words = reply.describe()
        self.notice_counts[words] += 1
        if self.notice_counts[words] == 1:  # the first of its kind said; repeats counted (summary)
            self.notices.append(reply)
            if self.on_notice is not None:
                self.on_notice(f"{self.where} says: {words}")

    def summary(self) -> list[str]:
        """Lines counting what was not said one by one: repeated notices, replies set aside beyond the first few."""
        lines = []
        repeated = {words: count for words, count in self.notice_counts.items() if count > 1}
        if repeated:
            total = sum(self.notice_counts.values())
            lines.append(f"{self.where} sent {total:,} notice(s) of its own (each kind said once above): "
                         + "; ".join(f"{count:,} x {words}" for words, count in repeated.items()))
        if len(self.set_aside) > self.SAID_SET_ASIDE:
            lines.append(f"{self.where} sent {len(self.set_aside):,} replies that answered no shot (set aside; the "
                         f"first {self.SAID_SET_ASIDE} said above)")
        return lines

    def _timeout(self, what: str) -> GSProConnectError:
        partial = " (part of a reply came, not the rest)" if self._splitter.pending else ""
        return GSProConnectError(f"{self.where} sent no reply to {what} within {self.timeout:g} s{partial} "
                                 "(raise --timeout if GSPro is busy)")


#: seconds to wait, after the last shot's answer, for a second reply to it (one that answers no shot)
SETTLE_SECONDS = 0.1


class Replies(list):
    """GSPro's 200 reply to each shot, in order, with what else the connection brought: ``set_aside`` (replies that
    answered no shot, in words) and ``notice_count`` (messages GSPro sent of its own accord)."""

    set_aside: list[str]
    notice_count: int


def send_shots(shots: Sequence[dict], host: str, port: int, timeout: float = 5.0,
               progress: Callable[[str], None] | None = None, settle: float = SETTLE_SECONDS) -> Replies:
    """Send GSPro Open Connect messages one at a time, each after the previous one is accepted.

    Parameters
    ----------
    shots : sequence of dict
        Messages of :func:`impactlab.io.interchange.gspro_shots` (their ``"impactlab"`` block is
        not sent: :func:`impactlab.io.interchange.wire_message`).
    host, port : str, int
        Where GSPro Connect listens.
    timeout : float
        Seconds to wait for the connection and for each reply.
    progress : callable, optional
        Called with a line of text about the first unsolicited message of each kind GSPro sends (201-203), each
        reply set aside (it came when no shot awaited an answer), and at the end the counts of repeats.
    settle : float
        Seconds to wait after the last shot's answer for a reply that answers no shot (at most ``timeout``; the
        wait ends early when GSPro closes the connection).

    Returns
    -------
    Replies
        GSPro's 200 reply to each shot, in order; its ``set_aside`` lists the replies that answered no shot.

    Raises
    ------
    GSProConnectError
        The first failure, saying which shot it stopped at and how many were accepted before it.
    """
    accepted = Replies()
    client = OpenConnectClient(host, port, timeout, on_notice=progress)
    with client:  # a failure to connect is said as it is
        try:
            for index, shot in enumerate(shots):
                accepted.append(client.send(wire_message(shot), _name(shot, index, len(shots))))
            client.note_read()
            client.settle("after the last shot's answer", wait=min(settle, timeout))
        except GSProConnectError as exc:
            raise GSProConnectError(f"{exc}; {len(accepted)} of {len(shots)} shot(s) were accepted before it"
                                    ) from None
        finally:
            if progress is not None:
                for line in client.summary():
                    progress(line)
    accepted.set_aside = list(client.set_aside)
    accepted.notice_count = sum(client.notice_counts.values())
    return accepted


def _name(shot: dict, index: int, total: int) -> str:
    """``shot 3 of 6 (ShotNumber 3; model maw, face_angle 3.0)``."""
    trace = shot.get("impactlab") or {}
    case = ", ".join(f"{key} {value}" for key, value in trace.items())
    number = shot.get("ShotNumber")
    return f"shot {index + 1} of {total} (ShotNumber {number}" + (f"; {case})" if case else ")")
