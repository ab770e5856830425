"""ROS 2 message types as Cyclone DDS types, built from the rosbags type store (and ``.msg`` files).

The standard messages come from rosbags' ROS 2 Humble type store (the same
definitions a bag of those types carries); others are read from ``.msg``
files with rosbags' parser. Each type becomes a ``cyclonedds.idl.IdlStruct``
named as ROS 2 names it on the wire (``sensor_msgs::msg::dds_::JointState_``),
final extensibility, serialised as XCDR1 (plain CDR with the CDR_LE
encapsulation header), so a sample's bytes are the bytes rosbags'
``serialize_cdr`` gives for the same message (tested).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from ..errors import DependencyNotInstalled, Ros2Error
from ._names import dds_type, normalize_type

__all__ = ["MessageTypes", "cyclonedds_modules"]

_NUMERIC = {"bool", "byte", "octet", "char", "int8", "uint8", "int16", "uint16", "int32", "uint32", "int64",
            "uint64", "float32", "float64"}


def cyclonedds_modules():
    """``(cyclonedds.idl, cyclonedds.idl.types)``, or :class:`DependencyNotInstalled` naming the extra."""
    try:
        import cyclonedds.idl as idl
        import cyclonedds.idl.types as types
    except ImportError as exc:
        raise DependencyNotInstalled(f"ethimon ros2 talks DDS with cyclonedds, which is not installed ({exc}); "
                                     "pip install 'ethimon[ros2]'") from None
    return idl, types


def _rosbags_typesys():
    try:
        from rosbags.typesys import Stores, get_types_from_msg, get_typestore
        from rosbags.typesys.base import Nodetype
    except ImportError as exc:
        raise DependencyNotInstalled(f"ethimon ros2 reads message definitions with rosbags, which is not "
                                     f"installed ({exc}); pip install 'ethimon[ros2]'") from None
    return Stores, get_types_from_msg, get_typestore, Nodetype


class MessageTypes:
    """Message definitions (rosbags' ROS 2 Humble store plus ``.msg`` files) and their DDS classes.

    Args:
        msg_files: ``.msg`` files (or folders searched for them); a file
            ``<pkg>/msg/<Name>.msg`` defines ``<pkg>/msg/<Name>``.
    """

    def __init__(self, msg_files: list[str | os.PathLike] | tuple = ()) -> None:
        Stores, get_types_from_msg, get_typestore, self._nt = _rosbags_typesys()
        self.store = get_typestore(Stores.ROS2_HUMBLE)
        extra: dict[str, Any] = {}
        for f in _msg_paths(msg_files):
            name = _type_of_path(f)
            try:
                extra.update(get_types_from_msg(f.read_text(encoding="utf-8"), name))
            except Exception as exc:  # noqa: BLE001 - the parser raises several kinds
                raise Ros2Error(f"{f}: cannot read this message definition: {exc}"[:400]) from None
        if extra:
            self.store.register(extra)
        self._classes: dict[str, type] = {}

    #: ``sensor_msgs/JointState`` → ``sensor_msgs/msg/JointState`` (what a mapping's ``type:`` may say)
    normalize = staticmethod(normalize_type)
    #: ``sensor_msgs/msg/JointState`` → ``sensor_msgs::msg::dds_::JointState_`` (the DDS type name, also rmw_zenoh's)
    dds_name = staticmethod(dds_type)

    def known(self, msgtype: str) -> bool:
        return normalize_type(msgtype) in self.store.fielddefs

    def fields(self, msgtype: str) -> list[tuple[str, Any]]:
        """The ``(name, node)`` field definitions of ``msgtype`` (rosbags' form)."""
        t = normalize_type(msgtype)
        if t not in self.store.fielddefs:
            raise KeyError(t)
        return list(self.store.fielddefs[t][1])

    def idl(self, msgtype: str) -> type:
        """The ``IdlStruct`` class of ``msgtype`` (built once)."""
        t = normalize_type(msgtype)
        cls = self._classes.get(t)
        if cls is None:
            if t not in self.store.fielddefs:
                raise Ros2Error(f"unknown message type {t}: not in the ROS 2 Humble type store",
                                ) from None
            idl, _ = cyclonedds_modules()
            fields = {n: self._conv(node) for n, node in self.fields(t)}
            if not fields:  # ROS 2's IDL gives an empty message one placeholder member
                fields = {"structure_needs_at_least_one_member": self._base("uint8")}
            cls = idl.make_idl_struct(t.replace("/", "_"), dds_type(t).replace("::", "."), fields)
            self._classes[t] = cls
        return cls

    def _base(self, name: str) -> Any:
        _, T = cyclonedds_modules()
        return {"bool": bool, "byte": T.uint8, "octet": T.uint8, "char": T.uint8, "int8": T.int8,
                "uint8": T.uint8, "int16": T.int16, "uint16": T.uint16, "int32": T.int32, "uint32": T.uint32,
                "int64": T.int64, "uint64": T.uint64, "float32": T.float32, "float64": T.float64}[name]

    def _conv(self, node: Any) -> Any:
        _, T = cyclonedds_modules()
        kind, arg = node
        NT = self._nt
        if kind == NT.BASE:
            name, bound = arg
            if name in ("string", "wstring"):
                return T.bounded_str[bound] if bound else str
            return self._base(name)
        if kind == NT.NAME:
            return self.idl(arg)
        if kind == NT.ARRAY:
            sub, n = arg
            return T.array[self._conv(sub), n]
        if kind == NT.SEQUENCE:
            sub, n = arg
            return T.sequence[self._conv(sub), n] if n else T.sequence[self._conv(sub)]
        raise Ros2Error(f"message field kind {node!r} is not supported")

    def resolve(self, msgtype: str, path: tuple[str | int, ...]) -> tuple[str, Any]:
        """What a field path points at: ``("number"|"text"|"array"|"vector"|"message", detail)``.

        Raises:
            KeyError: with the reason, when the path does not exist in the type.
        """
        NT = self._nt
        node: Any = (NT.NAME, normalize_type(msgtype))
        for i, part in enumerate(path):
            kind, arg = node
            if isinstance(part, int):
                if kind not in (NT.ARRAY, NT.SEQUENCE):
                    raise KeyError(f"[{part}] indexes a field that is not an array")
                sub, n = arg
                if kind == NT.ARRAY and part >= n:
                    raise KeyError(f"[{part}] is past the end of an array of {n}")
                node = sub
                continue
            if kind != NT.NAME:
                raise KeyError(f"{part!r}: the field before it is not a message")
            names = dict(self.fields(arg))
            if part not in names:
                import difflib
                close = difflib.get_close_matches(part, list(names), n=1)
                have = f"did you mean {close[0]!r}?" if close else "fields here: " + ", ".join(names)
                raise KeyError(f"{arg} has no field {part!r} ({have})")
            node = names[part]
        kind, arg = node
        if kind == NT.BASE:
            return ("text", arg[0]) if arg[0] in ("string", "wstring") else ("number", arg[0])
        if kind in (NT.ARRAY, NT.SEQUENCE):
            sub = arg[0]
            if sub[0] == NT.BASE and sub[1][0] in _NUMERIC:
                return "array", sub[1][0]
            return "message", "an array of messages or texts"
        fields = self.fields(arg)
        if fields and all(f[1][0] == NT.BASE and f[1][1][0] in _NUMERIC for f in fields):
            return "vector", arg
        return "message", arg


def _msg_paths(items: list | tuple) -> list[Path]:
    out: list[Path] = []
    for it in items:
        p = Path(it)
        if p.is_dir():
            out.extend(sorted(p.rglob("*.msg")))
        elif p.is_file():
            out.append(p)
        else:
            raise Ros2Error(f"{p}: no such .msg file or folder")
    return out


def _type_of_path(p: Path) -> str:
    parts = p.resolve().parts
    if p.suffix != ".msg" or len(parts) < 3 or parts[-2] != "msg":
        raise Ros2Error(f"{p}: a message definition lives at <package>/msg/<Name>.msg")
    return f"{parts[-3]}/msg/{p.stem}"
