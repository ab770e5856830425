"""What :class:`~._arm.ArmSim` shows: the status text of the GUI and rendered frames."""

from __future__ import annotations

import numpy as np

__all__ = ["_Rendering"]


class _Rendering:
    """Status text and frames (a part of :class:`~._arm.ArmSim`)."""

    # ------------------------------------------------------------ rendering

    def show_status(self, text: str) -> None:
        """GUI only: show ``text`` above the arm (replaces the previous status)."""
        if not self.gui:
            return
        p = self._p
        kw = {"replaceItemUniqueId": self._status_id} if self._status_id is not None else {}
        self._status_id = p.addUserDebugText(text, (0.0, 0.0, 1.2), textColorRGB=(0.8, 0.1, 0.1),
                                             textSize=1.6, physicsClientId=self.cid, **kw)

    def render(self, width: int = 480, height: int = 360) -> np.ndarray:
        """An RGB frame (H×W×3 uint8) from PyBullet's software TinyRenderer (headless)."""
        p, cid = self._p, self.cid
        view = p.computeViewMatrixFromYawPitchRoll((0.6, 0.3, 0.35), 2.7, -40, -25, 0, 2,
                                                   physicsClientId=cid)
        proj = p.computeProjectionMatrixFOV(50, width / height, 0.05, 10, physicsClientId=cid)
        _, _, rgba, _, _ = p.getCameraImage(width, height, view, proj, lightDirection=(1, 1, 2),
                                            renderer=p.ER_TINY_RENDERER, physicsClientId=cid)
        return np.asarray(rgba, dtype=np.uint8).reshape(height, width, 4)[:, :, :3]
