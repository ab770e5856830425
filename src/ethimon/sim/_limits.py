"""Franka Panda rated joint limits and the brake model (no PyBullet, no numpy needed to import).

The rated-limit table lives in :mod:`ethimon._robot` (``verify`` and ``lint`` check a safe pose
against it without importing ``sim``); it is re-exported here for the simulator. Rated limits:
Franka Emika, FCI documentation, "Robot and interface specifications", section "Limits for Panda" (https://frankaemika.github.io/docs/control_parameters.html):
``q_min``/``q_max``, ``dq_max``, ``ddq_max`` and ``dddq_max`` per joint. Commands outside
them abort a motion on the real robot; every controller of the simulation keeps inside them
(the URDF's hard limits are wider: e.g. joint 1 ±2.9671 rad against the rated ±2.8973 rad).

Brake model: **assumed**, not from a Franka document (Franka publishes no engagement time,
braking deceleration or holding torque for the Panda's brakes in the FCI documents): after
motor power is removed the joints coast freely for :data:`BRAKE_ENGAGE_S`, then the brakes
decelerate every joint at :data:`BRAKE_DECEL_RAD_S2` (the rated acceleration limit, an
assumption) with a friction torque of at most :data:`BRAKE_TORQUE_N_M` (a larger
external torque slips the brake). The holding torques are data with a source per number
(:data:`ethimon._robot.BRAKE_TABLE`: estimates, stated as such), and before any power-off the
simulator checks the gravity load of arm + payload against them with the project's safety factor
:data:`BRAKE_SAFETY_FACTOR` (1.5, a decision of the lead, issue 32): less margin escalates the stop
0/1 to a powered stop 2.

Example:
    >>> from ethimon.sim._limits import RATED_DQ_MAX, out_of_range
    >>> RATED_DQ_MAX[0], RATED_DQ_MAX[6]
    (2.175, 2.61)
    >>> out_of_range((0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785))
    []
    >>> out_of_range((0.0, -0.785, 0.0, 0.2, 0.0, 1.571, 0.785))[0][0]
    4
"""

from __future__ import annotations

from .._robot import (BRAKE_HOLDING_N_M, BRAKE_SAFETY_FACTOR, BRAKE_TABLE, RATED_PAYLOAD_KG, brake_problem,
                      gravity_torque,
                      RATED_DDDQ_MAX, RATED_DDQ_MAX, RATED_DQ_MAX, RATED_Q_MAX, RATED_Q_MIN,
                      RATED_SOURCE, out_of_range, safe_pose_problem)

__all__ = ["RATED_Q_MIN", "RATED_Q_MAX", "RATED_DQ_MAX", "RATED_DDQ_MAX", "RATED_DDDQ_MAX",
           "RATED_SOURCE", "LIMIT_MARGIN_RAD", "BRAKE_ENGAGE_S", "BRAKE_DECEL_RAD_S2", "BRAKE_TORQUE_N_M",
           "BRAKE_SAFETY_FACTOR", "BRAKE_TABLE", "RATED_PAYLOAD_KG", "brake_problem", "gravity_torque",
           "out_of_range", "safe_pose_problem"]

#: the servo keeps its reference this far inside every rated position limit (rad), and a
#: stop plans each joint to rest inside it: the tracking error near a limit (0.015 mrad
#: measured with the arm stretched against gravity) never carries a joint past its rating
LIMIT_MARGIN_RAD = 0.001
#: ASSUMED: time from power removal to brake engagement (s); the joints coast meanwhile
BRAKE_ENGAGE_S = 0.03
#: ASSUMED: deceleration of an engaged brake per joint (rad/s²): the rated acceleration limit
BRAKE_DECEL_RAD_S2 = RATED_DDQ_MAX
#: ESTIMATED holding torque per joint (N·m): :data:`ethimon._robot.BRAKE_TABLE` (the joint's
#: torque limit; before issue 32 an unsourced 60/10 N·m, under the 68.6 N·m a 2.9 kg payload needs)
BRAKE_TORQUE_N_M = BRAKE_HOLDING_N_M

