"""Stage 2 of 3: check a spec (names, types, units, windows) and compile it."""

from ._check import ObligationPlan, Plan, SignalSlot, compile_plan
from ._closures import Machine, build_machine
from ._plans import plan_of, stateless_slots

__all__ = ["Machine", "ObligationPlan", "Plan", "SignalSlot", "build_machine", "compile_plan", "plan_of",
           "stateless_slots"]
