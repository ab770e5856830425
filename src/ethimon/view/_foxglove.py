"""A live Foxglove view: a Foxglove WebSocket server (``foxglove-sdk``, imported when one starts) serving
the verdict channels of :mod:`._channels` (the ``--mcap`` file's names and schemas), fed without blocking.

:class:`FoxgloveView` is the server; its :meth:`~FoxgloveView.put` (the per-cycle sink of a
``GovernedLoop``) appends a cycle to a bounded queue and returns: a worker thread turns cycles into
messages and logs them; when the queue is full the oldest cycle is dropped and counted
(:attr:`~FoxgloveView.dropped`). The control loop never waits for a viewer.
"""

from __future__ import annotations

import threading
import time
from collections import deque
from collections.abc import Mapping
from typing import Any

from ..errors import DependencyNotInstalled
from ._channels import VerdictChannels

__all__ = ["DEFAULT_HOST", "DEFAULT_PORT", "FoxgloveView", "parse_address"]

DEFAULT_HOST = "127.0.0.1"
DEFAULT_PORT = 8765


def parse_address(text: str | int | None) -> tuple[str, int]:
    """``"[HOST:]PORT"`` (or a port number; ``None``: the default) → ``(host, port)``; loopback unless a
    host is named. Port 0 picks a free port.

    Raises:
        ValueError: not ``[HOST:]PORT`` with a port in 0..65535 (the message says what was given).

    Example:
        >>> parse_address("9000"), parse_address("0.0.0.0:8765"), parse_address(None)
        (('127.0.0.1', 9000), ('0.0.0.0', 8765), ('127.0.0.1', 8765))
    """
    if text is None:
        return DEFAULT_HOST, DEFAULT_PORT
    if isinstance(text, int) and not isinstance(text, bool):
        host, port_s = DEFAULT_HOST, str(text)
    elif isinstance(text, str):
        host, sep, port_s = text.strip().rpartition(":")
        host = host.strip("[]") if sep else DEFAULT_HOST
        if not host:
            host = DEFAULT_HOST
    else:
        raise ValueError(f"foxglove address {text!r}: expected [HOST:]PORT, e.g. 8765 or 127.0.0.1:8765")
    if not port_s.isdigit() or not 0 <= int(port_s) <= 65535:
        raise ValueError(f"foxglove address {text!r}: expected [HOST:]PORT with a port in 0..65535, "
                         "e.g. 8765 or 127.0.0.1:8765")
    return host, int(port_s)


class FoxgloveView:
    """A Foxglove WebSocket server publishing a monitor's verdict channels (``pip install 'ethimon[foxglove]'``).

    Args:
        channels: the :class:`VerdictChannels` to serve (a spec's ids, inputs, τ, τ_confirm).
        address: ``"[HOST:]PORT"`` or a port (default ``127.0.0.1:8765``; port 0: a free one, see :attr:`port`).
        queue: the most cycles waiting for the worker (then the oldest is dropped and counted).
        name: the server's name, shown by Foxglove.

    Raises:
        DependencyNotInstalled: ``foxglove-sdk`` is not installed.
        OSError: the server cannot listen there (the port is taken).
    """

    def __init__(self, channels: VerdictChannels, address: str | int | None = None, *, queue: int = 256,
                 name: str = "ethimon") -> None:
        try:
            import foxglove
        except ImportError as exc:
            raise DependencyNotInstalled(f"a live Foxglove view needs foxglove-sdk, which is not installed ({exc}); "
                                         "pip install 'ethimon[foxglove]'") from None
        if not (isinstance(queue, int) and queue >= 1):
            raise ValueError(f"queue={queue!r}; expected a positive number of cycles")
        self.channels = channels
        self.host, port = parse_address(address)
        self._ctx = foxglove.Context()
        #: channel subscriptions made by clients so far (:meth:`wait_subscribed`)
        self.subscriptions = 0
        self._last_subscribed = 0.0
        self._subscribed = threading.Condition()
        view = self

        class _Listener(getattr(foxglove, "ServerListener", object)):  # type: ignore[misc]
            # the SDK's base class gives every other callback (unsubscribe, parameters ...) its no-op default
            def on_subscribe(self, client: Any, channel: Any) -> None:
                with view._subscribed:
                    view.subscriptions += 1
                    view._last_subscribed = time.monotonic()
                    view._subscribed.notify_all()

            def on_unsubscribe(self, client: Any, channel: Any) -> None:
                return None

        try:
            self._server = foxglove.start_server(name=name, host=self.host, port=port, context=self._ctx,
                                                 server_listener=_Listener())
        except RuntimeError as exc:  # the SDK reports a bind failure as a RuntimeError
            raise OSError(f"cannot serve Foxglove on {self.host}:{port}: {exc}") from None
        self.port: int = int(self._server.port)
        self._ch = {topic: foxglove.Channel(topic, schema=foxglove.Schema(name=title, encoding="jsonschema", data=data),
                                            message_encoding="json", context=self._ctx)
                    for topic, title, data in channels.schemas()}
        self._q: deque = deque()
        self._max = queue
        self._wake = threading.Event()
        self._closed = False
        #: cycles dropped because the queue was full (the oldest first); cycles and messages published
        self.dropped = 0
        self.cycles = 0
        self.messages = 0
        #: the first error the worker met (it keeps going), or ``None``
        self.error: str | None = None
        self._worker = threading.Thread(target=self._run, name="ethimon-foxglove", daemon=True)
        self._worker.start()

    def wait_subscribed(self, count: int = 1, timeout: float | None = None, settle_s: float = 0.0) -> bool:
        """Wait until clients have made ``count`` channel subscriptions (at most ``timeout`` s; ``None``:
        no limit); whether they have. What is published before a client subscribes reaches no one.

        ``settle_s`` > 0: after that, also wait until no further subscription has come for ``settle_s``
        (still within ``timeout``), so that a client subscribing to several channels in one request has all
        of them before the first message (the SDK reports each channel of a request separately)."""
        end = None if timeout is None else time.monotonic() + timeout
        with self._subscribed:
            if not self._subscribed.wait_for(lambda: self.subscriptions >= count, timeout):
                return False
            while settle_s > 0:
                now = time.monotonic()
                quiet_until = self._last_subscribed + settle_s
                if now >= quiet_until or (end is not None and now >= end):
                    break
                self._subscribed.wait(min(quiet_until, end if end is not None else quiet_until) - now)
            return True

    @property
    def url(self) -> str:
        """Where a Foxglove client connects: ``ws://HOST:PORT``."""
        return f"ws://{self.host}:{self.port}"

    # -- the producer side: the control loop's thread --------------------------------------------
    def put(self, decision: Any, inputs: Mapping[str, Any], t_ns: int | None = None) -> None:
        """Queue one live cycle (a :class:`~ethimon.runtime.Decision` and the inputs the monitor read);
        never blocks. ``t_ns``: its log time (now by default)."""
        self._push(("d", decision, inputs, time.time_ns() if t_ns is None else t_ns))

    def put_messages(self, messages: list[tuple[str, dict]], t_ns: int) -> None:
        """Queue the ready messages of one cycle (a replay's verdicts) at log time ``t_ns``; never blocks."""
        self._push(("m", messages, None, t_ns))

    def _push(self, item: tuple) -> None:
        if self._closed:
            return
        q = self._q
        if len(q) >= self._max:
            try:
                q.popleft()
                self.dropped += 1
            except IndexError:  # the worker took it meanwhile
                pass
        q.append(item)
        self._wake.set()

    @property
    def pending(self) -> int:
        """Cycles waiting for the worker."""
        return len(self._q)

    # -- the worker --------------------------------------------------------------------------------
    def _run(self) -> None:
        q, wake, ch = self._q, self._wake, self.channels
        while True:
            wake.wait(0.2)
            wake.clear()
            while q:
                try:
                    kind, a, b, t = q.popleft()
                except IndexError:
                    break
                try:
                    msgs = ch.of_decision(a, b) if kind == "d" else a
                    for topic, obj in msgs:
                        c = self._ch.get(topic)
                        if c is not None:
                            c.log(obj, log_time=t)
                            self.messages += 1
                    self.cycles += 1
                except Exception as exc:  # noqa: BLE001 - a viewer never stops the loop; kept for the summary
                    if self.error is None:
                        self.error = f"{type(exc).__name__}: {exc}"
            if self._closed and not q:
                return

    def flush(self, timeout: float = 2.0) -> bool:
        """Wait until the queue is empty (at most ``timeout`` s); whether it is."""
        end = time.monotonic() + timeout
        while self._q and time.monotonic() < end:
            self._wake.set()
            time.sleep(0.005)
        return not self._q

    def close(self, timeout: float = 2.0, linger_s: float = 0.5) -> None:
        """Publish what is queued (at most ``timeout`` s), then stop the server.

        ``linger_s``: when a client is subscribed and messages were published, how long the server stays up
        after the last one so the SDK's per-client send queues reach the sockets (the SDK has no flush;
        stopping at once dropped the tail of a replay)."""
        if self._closed:
            return
        self._closed = True
        self._wake.set()
        self._worker.join(timeout)
        if linger_s > 0 and self.subscriptions and self.messages:
            time.sleep(linger_s)
        try:
            self._server.stop()
        except Exception:  # noqa: BLE001 - already stopped
            pass

    def __enter__(self) -> FoxgloveView:
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    def summary(self) -> str:
        """One line: where it served, cycles and messages published, cycles dropped."""
        s = f"foxglove {self.url}: {self.cycles} cycles, {self.messages} messages, {self.dropped} cycles dropped"
        return s + (f" (first error: {self.error})" if self.error else "")

    def __repr__(self) -> str:
        return f"FoxgloveView({self.url!r}, cycles={self.cycles}, dropped={self.dropped})"
