"""Stage 2 of 3: check a spec (names, types, units, windows) and compile it."""

from ._plan import JudgePlan, ObligationPlan, Plan, SignalSlot
from ._typecheck import compile_plan
from ._plans import plan_of, spec_without_tiers, stateless_slots

# the closures (compiler._closures: build_machine, Machine) are the runtime's to call, not a public API
__all__ = ["Plan", "compile_plan"]
