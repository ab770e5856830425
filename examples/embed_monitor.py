"""Embedding the monitor in a control loop (python examples/embed_monitor.py).

The arm and the classifier are stand-ins: replace FakeArm with your arm's driver and
classifier_probs with your estimator (e.g. ethimon.risk.load_estimator().probs).
"""

from pathlib import Path

import ethimon


class FakeArm:
    """A stand-in arm moving at 0.6 m/s while a person walks toward it at 1 m/s."""

    def __init__(self):
        self.human_distance, self.ee_speed, self.mode = 3.0, 0.6, "task"

    def signals(self):
        return {"human_distance": self.human_distance, "ee_speed": self.ee_speed,
                "contact_force": 0.0, "joint_speed_max": self.ee_speed / 0.6}

    def execute(self, response, safe_pose):  # stop_* halts the arm; safe_pose moves slowly there
        self.mode, self.ee_speed = str(response), 0.2 if response == ethimon.Response.SAFE_POSE else 0.0

    def execute_task_step(self):
        self.mode, self.ee_speed = "task", 0.6

    def tick(self, dt):  # the world moves on: the person comes closer
        self.human_distance = max(0.3, self.human_distance - 1.0 * dt)


def classifier_probs(text):
    return (0.95, 0.05)  # (p_safe, p_unsafe) of the task text: a fixed, harmless reading


def main(cycles=60, dt=0.05):
    spec = ethimon.load_spec(Path(__file__).resolve().parents[1] / "specs" / "cobot_cell.yaml")
    monitor = ethimon.Monitor(spec)  # compiled once, ready to step
    arm, probs, modes = FakeArm(), classifier_probs("wipe the table"), []
    for cycle in range(cycles):
        decision = monitor.step({"p": probs, **arm.signals()})  # or "p_unsafe": q, or "risk": R_e
        if decision.override:  # same cycle: leave the task
            arm.execute(decision.response, spec.safe_pose)
        else:
            arm.execute_task_step()
        if not modes or modes[-1][1] != arm.mode:
            modes.append((cycle, arm.mode, arm.human_distance, decision.violations))
        arm.tick(dt)
    monitor.reset()  # a fresh trace: cycle 0, no latch, empty temporal history
    return modes


if __name__ == "__main__":
    for cycle, mode, distance, why in main():
        print(f"cycle {cycle:3d}  person at {distance:.2f} m  arm: {mode:<9}  violations: {', '.join(why) or '-'}")
