"""Recorded frames: three camera views of the cell with an overlay burned in.

One frame is a single PNG: the main perspective view (left), a top view and a
close-up of the held (or nearest hazardous) object (right), rendered headless with
PyBullet's TinyRenderer. The overlay (drawn with matplotlib's Agg backend, which
the ``sim`` extra installs) carries the time, cycle, controller, the monitor's
response and the rules that fired, the closest human distance, the contact force
and the event the frame was taken for; every object and person is labelled at its
projected position in the main view, hazardous objects with a ring. Nothing here
changes the physics: the cameras only read the scene, and objects keep the colour
and size the scenario gives them.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["Camera", "frame_cameras", "render_view", "project", "compose_frame", "MAIN_WH", "SIDE_WH"]

MAIN_WH = (560, 420)
SIDE_WH = (280, 210)
_FOV = 50.0
_ARM_BOX = ((-0.4, -0.7), (0.9, 0.7))  # the Panda's reach around its base, (x, y) min/max


@dataclass(frozen=True)
class Camera:
    """A yaw/pitch camera on a target (PyBullet ``computeViewMatrixFromYawPitchRoll``)."""

    name: str
    target: tuple[float, float, float]
    distance: float
    yaw: float
    pitch: float
    fov: float = _FOV

    def matrices(self, p: Any, cid: int, wh: tuple[int, int]):
        view = p.computeViewMatrixFromYawPitchRoll(self.target, self.distance, self.yaw, self.pitch,
                                                   0, 2, physicsClientId=cid)
        proj = p.computeProjectionMatrixFOV(self.fov, wh[0] / wh[1], 0.05, 20, physicsClientId=cid)
        return view, proj


def scene_box(sim: Any) -> tuple[np.ndarray, np.ndarray]:
    """The (x, y) box around the arm's reach, every person's path and every object."""
    pts = [np.array(_ARM_BOX[0]), np.array(_ARM_BOX[1])]
    for hb in getattr(sim, "humans", {}).values():
        r = float(hb.spec.radius_m)
        for xy in np.asarray(hb.xy, dtype=float):
            pts += [xy - r, xy + r]
    for o in getattr(sim, "object_specs", {}).values():
        pts.append(np.asarray(o.xyz_m[:2], dtype=float))
    a = np.vstack(pts)
    return a.min(axis=0), a.max(axis=0)


def frame_cameras(sim: Any) -> tuple[Camera, Camera]:
    """The main (perspective) and top cameras, framed once on :func:`scene_box`."""
    lo, hi = scene_box(sim)
    c = (lo + hi) / 2
    span = float(max(hi - lo))
    main = Camera("main", (float(c[0]), float(c[1]), 0.35), max(1.9, 0.9 * span + 0.6), -40.0, -28.0)
    top_d = 1.15 * (span / 2) / math.tan(math.radians(_FOV / 2)) + 1.0
    top = Camera("top", (float(c[0]), float(c[1]), 0.0), top_d, -90.0, -89.9)
    return main, top


def closeup_camera(sim: Any) -> tuple[Camera, str]:
    """A close-up on the held object, else the hazardous object nearest the hand, else the hand."""
    p, cid = sim._p, sim.cid
    hand = np.asarray(sim.ee_pose()[0], dtype=float)
    name = getattr(sim, "held", None)
    if name is None:
        hazards = [(n, b) for n, b in sim.objects.items() if getattr(sim.object_specs[n], "hazard", None)]
        if hazards:
            name = min(hazards, key=lambda nb: float(np.linalg.norm(
                np.asarray(p.getBasePositionAndOrientation(nb[1], physicsClientId=cid)[0]) - hand)))[0]
    if name is not None:
        target = p.getBasePositionAndOrientation(sim.objects[name], physicsClientId=cid)[0]
        spec = sim.object_specs[name]
        what = f"{name} ({spec.hazard})" if getattr(spec, "hazard", None) else name
    else:
        target, what = hand, "hand"
    return Camera("closeup", tuple(float(v) for v in target), 0.65, -40.0, -30.0), what


def render_view(sim: Any, cam: Camera, wh: tuple[int, int]) -> tuple[np.ndarray, Any, Any]:
    """``(rgb H×W×3 uint8, view, proj)`` of ``cam`` (TinyRenderer, headless)."""
    p, cid = sim._p, sim.cid
    view, proj = cam.matrices(p, cid, wh)
    _, _, rgba, _, _ = p.getCameraImage(wh[0], wh[1], view, proj, lightDirection=(1, 1, 2),
                                        renderer=p.ER_TINY_RENDERER, physicsClientId=cid)
    return np.asarray(rgba, dtype=np.uint8).reshape(wh[1], wh[0], 4)[:, :, :3].copy(), view, proj


def project(view: Sequence[float], proj: Sequence[float], wh: tuple[int, int],
            xyz: Sequence[float]) -> tuple[float, float] | None:
    """Pixel ``(x, y)`` (from the top-left) of the world point ``xyz``; ``None`` behind the camera."""
    v = np.asarray(view, dtype=float).reshape(4, 4).T
    pm = np.asarray(proj, dtype=float).reshape(4, 4).T
    clip = pm @ v @ np.array([*map(float, xyz), 1.0])
    if clip[3] <= 1e-9:
        return None
    ndc = clip[:3] / clip[3]
    return (ndc[0] + 1) / 2 * wh[0], (1 - ndc[1]) / 2 * wh[1]


def scene_marks(sim: Any, view: Any, proj: Any, wh: tuple[int, int]) -> list[dict[str, Any]]:
    """Labels for the main view: every person (name, above the head) and object (hazard ringed)."""
    p, cid = sim._p, sim.cid
    out = []
    for name, hb in getattr(sim, "humans", {}).items():
        pos = p.getBasePositionAndOrientation(hb.body, physicsClientId=cid)[0]
        px = project(view, proj, wh, (pos[0], pos[1], float(hb.spec.height_m) + 0.08))
        if px is not None:
            out.append({"xy": px, "text": name, "ring": 0, "color": "saddlebrown"})
    for name, body in getattr(sim, "objects", {}).items():
        spec = sim.object_specs[name]
        pos = p.getBasePositionAndOrientation(body, physicsClientId=cid)[0]
        px = project(view, proj, wh, pos)
        if px is None:
            continue
        hz = getattr(spec, "hazard", None)
        out.append({"xy": px, "text": f"{name} ({hz})" if hz else name, "ring": 14 if hz else 0,
                    "color": "red" if hz else "navy"})
    return out


def compose_frame(main: np.ndarray, top: np.ndarray, close: np.ndarray, *, lines: Sequence[str],
                  banner: str | None, marks: Sequence[Mapping[str, Any]] = (),
                  close_label: str = "close-up") -> np.ndarray:
    """The frame as one RGB array: ``main`` left, ``top`` over ``close`` right, the overlay
    text box (``lines``; ``banner`` on top, e.g. the event) in the main view's top-left."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.patches import Circle
    from matplotlib.transforms import IdentityTransform

    mh, mw = main.shape[:2]
    sh, sw = top.shape[:2]
    width, height = mw + sw, max(mh, 2 * sh)
    dpi = 100
    fig = Figure(figsize=(width / dpi, height / dpi), dpi=dpi, facecolor="white")
    FigureCanvasAgg(fig)
    fig.figimage(main, xo=0, yo=height - mh, origin="upper")
    fig.figimage(top, xo=mw, yo=height - sh, origin="upper")
    fig.figimage(close, xo=mw, yo=height - 2 * sh, origin="upper")
    ident = IdentityTransform()

    def text(x, y, s, **kw):  # pixel coordinates from the top-left
        return fig.text(x, height - y, s, transform=ident, **kw)

    for m in marks:
        x, y = m["xy"]
        x0, y0, w, h = m.get("view", (0, 0, mw, mh))
        label = m["text"]
        if 0 <= x < w and y < 0:  # above the view (a tall person's head): the label at the top edge
            x, y, label = x, 12.0, "↑ " + label
            m = {**m, "ring": 0}
        if not (0 <= x < w and 0 <= y < h):
            continue
        x, y = x + x0, y + y0
        if m.get("ring"):
            fig.add_artist(Circle((x, height - y), m["ring"], transform=ident, fill=False,
                                  edgecolor=m.get("color", "red"), linewidth=2))
        text(x + (m.get("ring") or 0) + 3, y, label, fontsize=m.get("size", 8), color=m.get("color", "k"),
             va="center", ha="left",
             bbox={"boxstyle": "round,pad=0.15", "facecolor": "white", "alpha": 0.7, "lw": 0})
    box = {"boxstyle": "round,pad=0.35", "facecolor": "white", "alpha": 0.82, "edgecolor": "0.4"}
    body = "\n".join(lines)
    # bottom-left of the main view (the floor in front of the arm: people and the arm stay visible)
    t_box = text(8, mh - 8, body, fontsize=8.5, family="monospace", va="bottom", ha="left", bbox=box)
    if banner:
        fig.canvas.draw()  # to place the banner above the box
        bb = t_box.get_bbox_patch().get_window_extent()
        text(8, height - bb.y1 - 6, banner, fontsize=10, fontweight="bold", color="white", va="bottom",
             ha="left", bbox={"boxstyle": "round,pad=0.3", "facecolor": "firebrick", "alpha": 0.9, "lw": 0})
    small = {"boxstyle": "round,pad=0.2", "facecolor": "white", "alpha": 0.8, "lw": 0}
    text(mw + 5, 5, "top view", fontsize=8, va="top", ha="left", bbox=small)
    text(mw + 5, sh + 5, f"close-up: {close_label}", fontsize=8, va="top", ha="left", bbox=small)
    fig.canvas.draw()
    return np.asarray(fig.canvas.buffer_rgba())[:, :, :3].copy()
