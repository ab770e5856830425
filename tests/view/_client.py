"""A minimal Foxglove WebSocket protocol client for tests (subprotocol ``foxglove.websocket.v1``).

It speaks the protocol itself (websockets' sync client): it reads ``serverInfo`` and ``advertise``,
sends ``subscribe`` and decodes binary Message Data frames (opcode 0x01, u32 subscription id, u64 log
time, JSON payload). Loopback only; every wait is bounded.
"""

from __future__ import annotations

import json
import struct
import time
from typing import Any

from websockets.sync.client import connect

#: the Foxglove WebSocket protocol; foxglove-sdk 0.30 answers only its renamed subprotocol "foxglove.sdk.v1"
SUBPROTOCOLS = ["foxglove.sdk.v1", "foxglove.websocket.v1"]


class FoxgloveClient:
    def __init__(self, url: str, timeout: float = 5.0) -> None:
        self._cm = connect(url, subprotocols=SUBPROTOCOLS, open_timeout=timeout, close_timeout=1)
        self.ws = self._cm.__enter__()
        self.timeout = timeout
        self.server_info: dict | None = None
        self.channels: dict[str, dict] = {}  # topic -> advertised channel
        self._subs: dict[int, str] = {}  # subscription id -> topic

    def _recv(self, deadline: float) -> Any:
        return self.ws.recv(timeout=max(0.01, deadline - time.monotonic()))

    def handshake(self, topics: set[str]) -> None:
        """Read control messages until ``serverInfo`` and an advertisement of every topic in ``topics``."""
        deadline = time.monotonic() + self.timeout
        while self.server_info is None or not topics <= set(self.channels):
            msg = self._recv(deadline)
            if isinstance(msg, str):
                obj = json.loads(msg)
                if obj.get("op") == "serverInfo":
                    self.server_info = obj
                elif obj.get("op") == "advertise":
                    for ch in obj["channels"]:
                        self.channels[ch["topic"]] = ch

    def subscribe(self, topics: list[str]) -> None:
        subs = []
        for i, topic in enumerate(topics, start=len(self._subs) + 1):
            self._subs[i] = topic
            subs.append({"id": i, "channelId": self.channels[topic]["id"]})
        self.ws.send(json.dumps({"op": "subscribe", "subscriptions": subs}))

    def messages(self, count: int) -> list[tuple[str, int, dict]]:
        """The next ``count`` message data frames as ``(topic, log time ns, decoded JSON)``."""
        deadline = time.monotonic() + self.timeout
        out = []
        while len(out) < count:
            msg = self._recv(deadline)
            if isinstance(msg, bytes) and msg[:1] == b"\x01":
                sub, t = struct.unpack_from("<IQ", msg, 1)
                out.append((self._subs[sub], t, json.loads(msg[13:])))
        return out

    def close(self) -> None:
        self._cm.__exit__(None, None, None)
