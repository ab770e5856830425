"""No consumer reads the Spec for what the Plan resolved (issue 33: "a frozen Plan holding the whole risk
rule and the tiers, so no consumer reads Spec").

``compile_plan`` resolves the risk rule (:class:`~ethimon.compiler.RiskPlan`: τ, the cut, the weights,
the hysteresis, ...), the tiers (:class:`~ethimon.compiler.Tiers`, with every judge's settings), the
estimator settings (``Plan.estimator``) and the restart block (``Plan.restart``) once; every later
consumer reads those, never ``spec.risk`` again, and never goes back from a plan to its spec.

Each module of ``src/ethimon`` is parsed (``ast``, nothing of it imported) and three kinds of read are
counted:

- ``spec.risk``: ``X.risk`` where ``X`` names a spec (``spec``, ``u.spec``, ``full_spec``,
  ``monitor.spec``, ...), or ``X.risk.<a RiskConfig field>`` on anything but a plan (``old.risk.allow``);
- ``plan.spec``: ``X.spec`` where ``X`` names a plan (``plan``, ``self.plan``, ``u.full_plan``,
  ``plan_of(...)``);
- ``plan.risk``: ``X.risk`` where ``X`` names a plan: the spec's raw ``risk:`` block, which the Plan
  carried (``Plan.risk``, now gone: the rule is ``risk_plan``, the tiers ``tiers``); kept at zero.

A module outside the allowed tables below reading any of them fails the test, and an allowed module
may not read more than its count. (A spec's risk block bound to a name first, ``r = spec.risk``, is
counted where it is read: at ``spec.risk``.)
"""

from __future__ import annotations

import ast
import functools
import re
from collections import Counter
from pathlib import Path

import pytest

from ethimon.language import RiskConfig

SRC = Path(__file__).resolve().parents[2] / "src" / "ethimon"

#: the fields (and helpers) of a spec's ``risk:`` block: ``X.risk.<one of these>`` reads a RiskConfig
_RISK_FIELDS = frozenset(RiskConfig.model_fields) | {"judge_list", "judge_cuts"}

#: a module that could make one of the reads (a superset of what :func:`reads` counts: only these are parsed)
_MAYBE = re.compile(r"(spec|plan|\))\s*\.\s*(risk|spec)\b|\.risk\s*\.\s*(" + "|".join(sorted(_RISK_FIELDS)) + r")\b")

#: folders whose modules build or are the spec: they may read it freely
FREE = ("compiler/", "language/")

#: module -> the most reads of each kind it may make, with the reason
ALLOWED: dict[str, dict[str, tuple[int, str]]] = {
    "spec.risk": {
        "testing/_reference.py": (4, "the independent reference interpreter reads the spec by design"),
        "loop/_weakenings.py": (2, "old.risk.allow, new.risk.allow: the author's written opt-outs and reasons, compared as text "
                                   "on a reload (what they change is already in the two plans)"),
    },
    "plan.spec": {
        "testing/_reference.py": (1, "ReferenceMonitor.spec: the spec it interprets"),
        "risk/_judge_tier.py": (1, "the spec file's location (plan.spec.source), where a relative canary path "
                                   "is read from: where the spec came from, not what it says"),
        "runtime/_monitor.py": (1, "Monitor.spec, a public attribute: the source a monitor built from a Plan "
                                   "was compiled from (its name, what a reload compares)"),
    },
    "plan.risk": {},
}


def _tail(node: ast.AST) -> str | None:
    """The last name of an expression: ``u.full_spec`` -> ``full_spec``, ``plan_of(s)`` -> ``plan_of()``."""
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Attribute):
        return node.attr
    if isinstance(node, ast.Call):
        f = _tail(node.func)
        return None if f is None else f + "()"
    return None


def _is_spec(name: str | None) -> bool:
    return name is not None and (name == "spec" or name.endswith("_spec"))


def _is_plan(name: str | None) -> bool:
    return name is not None and (name == "plan" or name.endswith("_plan") or name == "plan_of()")


def reads(tree: ast.AST) -> Counter:
    """How many ``spec.risk``, ``plan.spec`` and ``plan.risk`` reads one module makes."""
    out: Counter = Counter()
    risks: list[ast.Attribute] = []
    of_config: set[int] = set()  # X.risk nodes read as a RiskConfig (X.risk.<field>)
    for node in ast.walk(tree):
        if not isinstance(node, ast.Attribute):
            continue
        if node.attr == "risk":
            risks.append(node)
        elif node.attr == "spec" and _is_plan(_tail(node.value)):
            out["plan.spec"] += 1
        elif node.attr in _RISK_FIELDS and isinstance(node.value, ast.Attribute) and node.value.attr == "risk":
            of_config.add(id(node.value))
    for node in risks:
        owner = _tail(node.value)
        if _is_plan(owner):
            out["plan.risk"] += 1
        elif _is_spec(owner) or id(node) in of_config:
            out["spec.risk"] += 1
    return out


@functools.lru_cache(maxsize=1)
def all_reads() -> dict[str, Counter]:
    """Per module (path under ``src/ethimon``), its reads; modules with none are left out (a module
    the cheap text test :data:`_MAYBE` finds nothing in is not parsed)."""
    found = {}
    for path in sorted(SRC.rglob("*.py")):
        text = path.read_text(encoding="utf-8")
        if not _MAYBE.search(text):
            continue
        c = reads(ast.parse(text))
        if c:
            found[path.relative_to(SRC).as_posix()] = c
    return found


@pytest.mark.slow  # parses the ~20 modules the text test finds (~0.3 s)
def test_no_consumer_reads_the_spec_for_what_the_plan_resolved():
    bad = []
    for rel, c in all_reads().items():
        if rel.startswith(FREE):
            continue
        for kind, n in sorted(c.items()):
            most, _ = ALLOWED[kind].get(rel, (0, ""))
            if n > most:
                bad.append(f"{rel}: {n} {kind} read(s)" + (f" (at most {most})" if most else ""))
    assert not bad, ("read the Plan (plan_of(spec).risk_plan / .tiers / .estimator / .restart), not the spec:\n"
                     + "\n".join(bad))


@pytest.mark.slow
def test_the_allowed_reads_are_still_made():
    """An allowed count that is no longer reached is lowered (the table says what is left)."""
    found = all_reads()
    stale = [f"{rel}: {kind} allowed {most}, reads {found.get(rel, Counter())[kind]}"
             for kind, table in ALLOWED.items() for rel, (most, _) in table.items()
             if found.get(rel, Counter())[kind] < most]
    assert not stale, "lower these counts in ALLOWED:\n" + "\n".join(stale)


def test_the_counter_sees_each_kind_of_read():
    src = ("def f(spec, u, plan, old, monitor):\n"
           "    a = spec.risk.threshold; b = u.full_spec.risk; c = old.risk.allow; d = monitor.spec.risk\n"
           "    e = plan.spec; f = self.plan.spec; g = plan_of(spec).spec; h = u.full_plan.risk\n"
           "    i = d.risk; j = plan.risk_plan.threshold; k = monitor.spec.name\n")
    assert reads(ast.parse(src)) == Counter({"spec.risk": 4, "plan.spec": 3, "plan.risk": 1})
