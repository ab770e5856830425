"""Walks pass through each room once (issue 33: "walks of a bag and of a live sample pass through each room
once").

A walk (``tests/house/walks.py``, which says it in full) runs one real operation under ``sys.setprofile``
and keeps, in call order, the calls whose code is in the rooms it follows (modules of ``src/ethimon``: the
operation's own packages; a call into another package is a helper call that returns and is looked through):

- a **stay** is what one entry into a room does there: the entering call with every call it makes in the
  same room; consecutive entries of one caller into one room (a loop) are one stay;
- a stay's **flow** is the rooms its calls enter, in order, collapsed; coming back from a call is not
  leaving (a call down into a helper that returns is one step of the caller's flow);
- a **return** is entering again a room the walk had left for another one: a room that reappears in one
  stay's flow after another room, or a bounce (``A → B → A``: a room entered while it is still open below),
  unless that call goes down a floor of ARCHITECTURE.md (a helper that returns).

The walk *passes each room once* when it has no return. The two walks: (a) a bag, one small MCAP bag
written here, through :func:`ethimon.replay.replay_paths` (one unit of :func:`ethimon.run`), following
``replay/``, ``fleet/`` and ``_batch.py``; (b) a live sample of each mapped signal through
``io.MemoryChannel`` into ``io.LiveMonitor`` for one cycle of its ``GovernedLoop``, following ``io/``.
``python -m tests.house.walks`` prints both.
"""

from __future__ import annotations

import pytest

import ethimon.loop  # noqa: F401 - imported at collection: a walk times its operation, not the imports
import tests._estimators  # noqa: F401
from ethimon.io import MemoryChannel
from tests.house.walks import (BAG_SCOPE, LIVE_SCOPE, Call, bag_operation, live_operation, records_operation, trace,
                               walk, walk_of)


def test_the_walk_counts_stays_and_returns():
    """The definition on a made-up tree: a call down that returns is no return, a room again after another
    one in a flow is, and so is a bounce back into a room still open below."""
    def c(room, *kids):
        return Call(room, room, list(kids))

    w = walk(c("<entry>", c("a", c("b"), c("a", c("c")), c("c"))))  # a calls b, its own helper calls c, then c
    assert (w.stays, w.returns) == (3, [])
    w = walk(c("<entry>", c("a", c("b"), c("c"), c("b"))))
    assert w.stays == 4 and len(w.returns) == 1 and "b again in the flow of a" in w.returns[0]
    w = walk(c("<entry>", c("a", c("b", c("a")))))
    assert w.stays == 3 and len(w.returns) == 1 and "a → b → a" in w.returns[0]
    # a runner calling its unit back up is a bounce; the unit using a helper of the runner's floor is not
    w = walk(c("<entry>", c("replay/_record.py", c("_batch.py", c("replay/_unit.py", c("_batch.py"))))))
    assert len(w.returns) == 0, w.text()
    w = walk(c("<entry>", c("replay/_record.py", c("_batch.py", c("replay/_record.py")))))
    assert len(w.returns) == 1 and "replay/_record.py → _batch.py → replay/_record.py" in w.returns[0]


def test_trace_follows_only_the_scope():
    ch = MemoryChannel()

    def op():
        ch.publish("x", 1.0, 0.0)

    _, root = trace(op, ("io/",))
    assert {k.room for k in root.children} == {"io/_channel.py"}
    assert root.children[-1].name == "MemoryChannel.publish"
    _, root = trace(op, ("replay/",))
    assert root.children == []


@pytest.mark.slow
def test_a_bag_passes_each_room_once(tmp_path):
    pytest.importorskip("rosbags")
    out, w = walk_of(bag_operation(tmp_path), BAG_SCOPE)
    assert out.passed + out.failed == 1 and not out.errors, out.results
    assert not w.returns, "the walk of a bag returns to a room it had left:\n" + w.text()
    rooms = [s.room for s in _stays(w.top)]
    assert {"replay/_replay.py", "replay/_bag.py", "replay/_columns.py", "replay/_verdicts.py", "_batch.py"} \
        <= set(rooms), w.text()


@pytest.mark.slow
def test_a_bag_run_as_fleet_runs_it_passes_each_room_once(tmp_path):
    """``fleet.replay_records``' path on ``Serial``: ``replay_unit`` from the spec and mapping files."""
    pytest.importorskip("rosbags")
    out, w = walk_of(records_operation(tmp_path), BAG_SCOPE)
    assert len(out) == 1 and "error" not in out[0], out
    assert not w.returns, "the walk of a bag (fleet's way) returns to a room it had left:\n" + w.text()
    assert "replay/_unit.py" in {s.room for s in _stays(w.top)}, w.text()


def test_a_live_sample_comes_in_through_each_room_once():
    """Its way in: channel → LiveMonitor.frame → the channel once (samples, clock, its own faults, the
    frame) → the holds (put, read)."""
    frame, w = walk_of(live_operation(whole=False), LIVE_SCOPE)
    assert set(frame) == {"speed", "p_unsafe"} and not frame.faults, frame
    assert not w.returns, "the walk of a live sample returns to a room it had left:\n" + w.text()
    assert {"io/_live.py", "io/_hold.py", "io/_channel.py"} <= {s.room for s in _stays(w.top)}, w.text()


def test_a_live_sample_passes_each_room_once():
    """One whole cycle: the channel (samples, clock, faults, acknowledgement requests: one visit), the holds,
    then the outlet (override, decision): what comes in and what goes out are two ports, not one room
    visited twice."""
    d, w = walk_of(live_operation(), LIVE_SCOPE)
    assert not d.override and d.cycle == 1, d
    assert not w.returns, "the walk of a live sample returns to a room it had left:\n" + w.text()
    rooms = [s.room for s in _stays(w.top)]
    assert {"io/_live.py", "io/_channel.py", "io/_hold.py", "io/_outlet.py"} <= set(rooms), w.text()


def _stays(s):
    for t in s.inner:
        yield t
        yield from _stays(t)


def test_the_way_in_keeps_the_order_of_faults():
    """Asking the channel for its faults before the holds (one visit) keeps the frame's faults in their order:
    the holds' first, then the channel's own."""
    from ethimon.runtime import Fault
    op = live_operation(whole=False)
    op()  # one sample of each signal, then 0.1 s later speed (max_age_s 0.05) is stale
    op.clock.t += 0.1
    op.live.channel.extra_faults = (Fault("external", "a foreign writer"),)
    frame = op.live.frame()
    assert [f.kind for f in frame.faults] == ["stale", "external"], frame.faults
