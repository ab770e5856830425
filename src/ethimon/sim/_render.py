"""What :class:`~._arm.ArmSim` shows (``Renderer``, handed the ``World``): the status text of the GUI
and rendered frames."""

from __future__ import annotations

import numpy as np

from ._world import World

__all__ = ["Renderer"]


class Renderer:
    """Status text and frames (a part of :class:`~._arm.ArmSim`): handed the
    :class:`~._world.World`, owns the GUI's status text."""

    __slots__ = ("w", "_p", "_status_id")

    def __init__(self, world: World) -> None:
        self.w = world
        self._p = world.p
        self._status_id: int | None = None

    # ------------------------------------------------------------ rendering

    def show_status(self, text: str) -> None:
        """GUI only: show ``text`` above the arm (replaces the previous status)."""
        if not self.w.gui:
            return
        p = self._p
        kw = {"replaceItemUniqueId": self._status_id} if self._status_id is not None else {}
        self._status_id = p.addUserDebugText(text, (0.0, 0.0, 1.2), textColorRGB=(0.8, 0.1, 0.1),
                                             textSize=1.6, physicsClientId=self.w.cid, **kw)

    def render(self, width: int = 480, height: int = 360) -> np.ndarray:
        """An RGB frame (H×W×3 uint8) from PyBullet's software TinyRenderer (headless)."""
        p, cid = self._p, self.w.cid
        view = p.computeViewMatrixFromYawPitchRoll((0.6, 0.3, 0.35), 2.7, -40, -25, 0, 2,
                                                   physicsClientId=cid)
        proj = p.computeProjectionMatrixFOV(50, width / height, 0.05, 10, physicsClientId=cid)
        _, _, rgba, _, _ = p.getCameraImage(width, height, view, proj, lightDirection=(1, 1, 2),
                                            renderer=p.ER_TINY_RENDERER, physicsClientId=cid)
        return np.asarray(rgba, dtype=np.uint8).reshape(height, width, 4)[:, :, :3]
