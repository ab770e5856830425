"""Walks: the rooms (modules of ``src/ethimon``) one real operation passes through, in order (issue 33).

A *walk* runs one operation under ``sys.setprofile`` and keeps the tree of the calls whose code lives in
``src/ethimon`` (a call through a library, numpy or a generated ``__init__``, hangs under the nearest
ethimon call; module and class bodies run by an import are left out: a walk is taken after a warm-up run).

- A call *enters* a room when its module is not its caller's. A **stay** is what one entry does in its
  room: the entering call and every call it makes in the same room; consecutive entries of one caller
  into the same room (a loop over messages) are one stay. ``stays`` counts them over the whole tree.
- A stay's **flow** is the rooms its calls enter, in order, collapsed (a helper of its own room is part
  of the stay: its calls are in the flow). Coming back from a call is not leaving: a call down into a
  helper that returns is one step of the flow.
- A **return** is a room entered again after the walk had left it for another one, at one level of the
  flow: (1) a room that reappears in one stay's flow after another room (``A`` calls ``B``, then ``C``,
  then ``B`` again), or (2) a bounce: a call entering a room that is still open below it
  (``A → B → A``: ``B`` calls back into the room that called it), unless that call goes down a floor
  (``ARCHITECTURE.md``'s floors: a unit of ``replay`` run by ``_batch`` may use ``_batch.plain``, a helper
  that returns; ``_batch`` calling back up into the replay room that called it is a bounce).

A walk *passes each room once* when it makes no return. ``python -m tests.house.walks`` prints both walks
of ``tests/house/test_walks.py`` (a bag through the batch runner into replay, one live sample through a
``MemoryChannel`` into ``LiveMonitor``).
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable
from dataclasses import dataclass, field
from inspect import CO_NEWLOCALS
from pathlib import Path
from typing import Any



@dataclass
class Call:
    """One call whose code is in ``src/ethimon`` (``room``: its module's path under ``src/ethimon``)."""

    room: str
    name: str
    children: list[Call] = field(default_factory=list)


def trace(fn: Callable[[], Any], scope: tuple[str, ...] = ("",)) -> tuple[Any, Call]:
    """Run ``fn()`` and return its result and the tree of its calls in the rooms of ``scope`` (paths under
    ``src/ethimon`` a room's path starts with; others are looked through), under a root named ``<entry>``."""
    import ethimon
    src = os.fspath(Path(ethimon.__file__).parent) + os.sep  # the ethimon imported (PYTHONPATH), not only this tree's
    root = Call("<entry>", "<entry>")
    stack: list[tuple[Any, Call]] = [(None, root)]
    rooms: dict[str, str | None] = {}

    def room_of(code: Any) -> str | None:
        f = code.co_filename
        r = rooms.get(f, "")
        if r == "":
            r = Path(f[len(src):]).as_posix() if f.startswith(src) else None
            r = rooms[f] = r if r is not None and r.startswith(scope) else None
        return r

    def prof(frame: Any, event: str, arg: Any) -> None:
        if event == "call":
            code = frame.f_code
            room = room_of(code) if code.co_flags & CO_NEWLOCALS else None  # not a module or class body
            parent = stack[-1][1]
            if room is None:
                stack.append((frame, parent))
            else:
                node = Call(room, code.co_qualname)
                parent.children.append(node)
                stack.append((frame, node))
        elif event == "return":
            if len(stack) > 1 and stack[-1][0] is frame:
                stack.pop()

    old = sys.getprofile()
    sys.setprofile(prof)
    try:
        out = fn()
    finally:
        sys.setprofile(old)
    return out, root


@dataclass
class Stay:
    """One stay: a room, the calls that entered it (first one's name), and the stays its flow entered."""

    room: str
    name: str
    entries: int = 1
    inner: list[Stay] = field(default_factory=list)


def stays_of(call: Call) -> list[Stay]:
    """The stays ``call``'s flow enters (its same-room calls looked through), consecutive ones of one room merged."""
    out: list[Stay] = []

    def visit(c: Call) -> None:
        for ch in c.children:
            if ch.room == call.room:
                visit(ch)  # a helper of the same room: part of this stay
                continue
            inner = stays_of(ch)
            if out and out[-1].room == ch.room:
                last = out[-1]
                last.entries += 1
                last.inner = _merge(last.inner, inner)
            else:
                out.append(Stay(ch.room, ch.name, 1, inner))

    visit(call)
    return out


def _merge(a: list[Stay], b: list[Stay]) -> list[Stay]:
    """Two stays of one room, one after the other, as one: their flows joined (collapsed)."""
    out = list(a)
    for s in b:
        if out and out[-1].room == s.room:
            out[-1] = Stay(s.room, out[-1].name, out[-1].entries + s.entries, _merge(out[-1].inner, s.inner))
        else:
            out.append(s)
    return out


@dataclass
class Walk:
    """A walk: its entry stay, every stay, and its returns (one line each)."""

    top: Stay
    stays: int
    returns: list[str]

    def lines(self) -> list[str]:
        out = [f"{self.stays} stays, {len(self.returns)} returns"]

        def show(s: Stay, depth: int) -> None:
            times = f" x{s.entries}" if s.entries > 1 else ""
            out.append(f"{'  ' * depth}{s.room}  {s.name}{times}")
            for t in s.inner:
                show(t, depth + 1)

        show(self.top, 0)
        out += [f"return: {r}" for r in self.returns]
        return out

    def text(self) -> str:
        return "\n".join(self.lines())


def package_of(room: str) -> str:
    """``replay/_unit.py`` → ``replay``; ``_batch.py`` → ``_batch``."""
    return room.split("/", 1)[0] if "/" in room else room.removesuffix(".py")


def calls_down(caller: str, callee: str) -> bool:
    """Whether a call from room ``caller`` into room ``callee`` goes down a floor (ARCHITECTURE.md: the
    callee's package is one the caller's may import): a helper that returns, never a bounce."""
    from tests.house.test_import_direction import ALLOWED
    a, b = package_of(caller), package_of(callee)
    return a != b and b in ALLOWED.get(a, set())


def walk(root: Call) -> Walk:
    """The walk of a traced tree (:func:`trace`): the stays and returns of its entry's flow."""
    top = Stay(root.room, root.name, 1, stays_of(root))
    returns: list[str] = []
    count = 0

    def visit(s: Stay, open_: tuple[str, ...]) -> None:
        nonlocal count
        count += s is not top
        seen: list[str] = []
        for t in s.inner:
            if t.room in seen:
                returns.append(f"{t.room} again in the flow of {s.room} ({s.name}), after "
                               f"{', '.join(seen[seen.index(t.room) + 1:])}")
            seen.append(t.room)
            if t.room in open_ and not calls_down(s.room, t.room):
                returns.append(f"{t.room} ({t.name}) entered from {s.room} ({s.name}) while it is open below: "
                               + " → ".join((*open_[open_.index(t.room):], s.room, t.room)))
            visit(t, (*open_, s.room))

    visit(top, ())
    return Walk(top, count, returns)


# ----------------------------------------------------------------------------- the two walks of issue 33

BAG_SPEC = """
ethimon: 1
name: walk
signals:
  human_distance:  {unit: m,     range: [0, 10]}
  ee_speed:        {unit: m/s,   range: [0, 3]}
  joint_speed_max: {unit: rad/s, range: [0, 10]}
risk: {threshold: 0.5, release: {mode: auto, hysteresis: 0.05, hold_cycles: 4}}
on_fault: stop_1
obligations:
  - {id: separation, require: human_distance >= 0.5, response: stop_2}
  - {id: slow_near, when: human_distance < 1.5, require: ee_speed <= 0.25, within_cycles: 3}
"""

BAG_MAPPING = """
ethimon: 1
rate_hz: 50
max_age_s: 0.08
samples: latest
signals:
  joint_speed_max: {topic: /joint_states, field: velocity, reduce: max_abs}
  human_distance:  {topic: /human/distance_cm, field: data, scale: 0.01, max_age_s: 0.15}
  ee_speed:        {topic: /ee/twist, field: twist.linear, reduce: norm}
task: {topic: /task}
"""

TEXTS = {"Stack the boxes.": (0.9, 0.1), "Throw the box at the person.": (0.2, 0.8)}


def _score(text: str) -> tuple[float, float]:
    return TEXTS[text]


def bag_operation(folder: Path) -> Callable[[], Any]:
    """A small MCAP bag written into ``folder`` (1 s, with a task text) and the operation that replays it:
    :func:`ethimon.replay.replay_paths` (one unit of :func:`ethimon.run`), its task texts scored by a
    function."""
    from ethimon import load_spec
    from ethimon.replay import load_mapping, replay_paths
    from tests.replay.test_replay import make_messages, write_bag

    spec_path, map_path = folder / "spec.yaml", folder / "mapping.yaml"
    spec_path.write_text(BAG_SPEC, encoding="utf-8")
    map_path.write_text(BAG_MAPPING, encoding="utf-8")
    msgs = [m for m in make_messages(n_js=40) if m[0] < 1_001 * 10**9]
    bag = write_bag(folder / "bag", "mcap", msgs)
    spec, mapping = load_spec(spec_path), load_mapping(map_path)
    return lambda: replay_paths([bag], spec, mapping, score=_score)


RECORDS_MAPPING = """
ethimon: 1
rate_hz: 50
max_age_s: 0.08
samples: latest
signals:
  joint_speed_max: {topic: /joint_states, field: velocity, reduce: max_abs}
  human_distance:  {topic: /human/distance_cm, field: data, scale: 0.01, max_age_s: 0.15}
  ee_speed:        {topic: /ee/twist, field: twist.linear, reduce: norm}
  p_unsafe:        {topic: /p, field: data, max_age_s: 0.5}
"""


def records_operation(folder: Path) -> Callable[[], Any]:
    """The bag of :func:`bag_operation`, its risk from a ``p_unsafe`` topic (no model to load), and the
    operation ``fleet.replay_records`` runs, on :class:`ethimon.Serial` instead of Ray: each bag a
    ``replay_unit`` of :func:`ethimon.run`, from the spec and mapping files."""
    from ethimon import Serial
    from ethimon.replay._record import replay_records
    from tests.replay.test_replay import make_messages, write_bag

    spec_path, map_path = folder / "spec.yaml", folder / "mapping.yaml"
    spec_path.write_text(BAG_SPEC, encoding="utf-8")
    map_path.write_text(RECORDS_MAPPING, encoding="utf-8")
    msgs = [m for m in make_messages(n_js=40) if m[0] < 1_001 * 10**9 and m[1] != "/task"]
    msgs += [(1_000 * 10**9 + k * 100_000_000, "/p", "f64", 0.1) for k in range(10)]
    bag = write_bag(folder / "bag", "mcap", sorted(msgs, key=lambda m: m[0]))
    return lambda: replay_records([bag], spec=str(spec_path), mapping=str(map_path), executor=Serial())


LIVE_SPEC = """
ethimon: 1
name: walk_live
signals:
  speed: {unit: rad/s, range: [-1000, 1000]}
risk: {threshold: 0.5}
obligations:
  - {id: slow, require: "speed <= 2.0", response: stop_1}
"""

LIVE_MAPPING = """
ethimon: 1
rate_hz: 100
max_age_s: 0.05
signals:
  speed: {topic: /speed, field: data}
  p_unsafe: {topic: /p, field: data, max_age_s: 0.2}
"""


def live_operation(whole: bool = True) -> Callable[[], Any]:
    """A :class:`~ethimon.io.LiveMonitor` on a :class:`~ethimon.io.MemoryChannel` (a fake clock) and the
    operation that takes one sample of each mapped signal through one cycle of its loop (``whole=False``:
    only their way in, the cycle's :meth:`~ethimon.io.LiveMonitor.frame`)."""
    import ethimon
    from ethimon.io import LiveMonitor, MemoryChannel, load_mapping_text
    from ethimon.loop import GovernedLoop, LoopConfig
    from tests._estimators import FakeClock

    spec, mapping = ethimon.load_spec_text(LIVE_SPEC), load_mapping_text(LIVE_MAPPING)
    clock = FakeClock(100.0)
    ch = MemoryChannel(clock=clock)
    loop = GovernedLoop(ethimon.Monitor(spec), clock=clock,
                        config=LoopConfig(period_s=0.01, deadline_s=1e6, stall_s=1e6))
    live = LiveMonitor(loop, mapping, ch)

    def one_cycle() -> Any:
        ch.publish("speed", 1.0, clock.t)
        ch.publish("p_unsafe", 0.1, clock.t)
        d = loop.cycle() if whole else live.frame()
        clock.t += 0.01
        return d

    one_cycle.live, one_cycle.clock = live, clock  # type: ignore[attr-defined]
    return one_cycle


#: the rooms each walk follows: the operation's own packages; a call into another package (the spine,
#: ``io``'s mapping from replay, ``runtime`` from the loop) is a call down into a helper that returns.
#: A bag: the batch runner, fleet's drivers and replay. A live sample: the seam ``io``; the pacer it is
#: plugged into (``loop``) calls it twice a cycle (its source, then its decision callback), which is the
#: loop's flow, not the sample's (``LOOP_SCOPE`` shows it)
BAG_SCOPE = ("replay/", "fleet/", "_batch.py")
LIVE_SCOPE = ("io/",)
LOOP_SCOPE = ("io/", "loop/")


def walk_of(op: Callable[[], Any], scope: tuple[str, ...]) -> tuple[Any, Walk]:
    """``op`` run once to warm up (lazy imports, loaded models), then traced in ``scope``: its result and walk."""
    op()
    out, root = trace(op, scope)
    return out, walk(root)


def main(argv: list[str] | None = None) -> int:
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        _, w = walk_of(bag_operation(Path(tmp)), BAG_SCOPE)
        print("walk of a bag:", w.text(), sep="\n")
        (Path(tmp) / "fleet").mkdir()
        _, w = walk_of(records_operation(Path(tmp) / "fleet"), BAG_SCOPE)
        print("\nwalk of a bag as fleet runs it (replay_records, on Serial):", w.text(), sep="\n")
    _, w = walk_of(live_operation(), LIVE_SCOPE)
    print("\nwalk of a live sample:", w.text(), sep="\n")
    _, w = walk_of(live_operation(whole=False), LIVE_SCOPE)
    print("\nits way in (LiveMonitor.frame):", w.text(), sep="\n")
    _, w = walk_of(live_operation(), LOOP_SCOPE)
    print("\nthe same with the loop's rooms:", w.text(), sep="\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
