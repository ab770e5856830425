"""The Cyclone DDS configuration of the node: network interface, unicast peers, DDS Security.

Without options the node uses Cyclone's own configuration (``CYCLONEDDS_URI``,
else its defaults: the first multicast-capable interface). With an interface or
peers, :func:`cyclone_config` writes the XML for them: ``--interface lo --peer
127.0.0.1`` is loopback unicast discovery, for a machine (or a container)
without multicast.
"""

from __future__ import annotations

import ipaddress
import os
from pathlib import Path
from xml.sax.saxutils import escape, quoteattr

from ..errors import Ros2Error

__all__ = ["ENCLAVE_FILES", "cyclone_config", "security_available"]

#: the files of an SROS2 enclave (``ros2 security create_enclave``) that DDS Security reads
ENCLAVE_FILES = ("identity_ca.cert.pem", "cert.pem", "key.pem", "permissions_ca.cert.pem", "governance.p7s",
                 "permissions.p7s")


def _lib_dirs() -> list[Path]:
    dirs = []
    try:
        import cyclonedds
        base = Path(cyclonedds.__file__).resolve().parent
        dirs += [base / ".libs", base.parent / "cyclonedds.libs"]
    except ImportError:
        pass
    home = os.environ.get("CYCLONEDDS_HOME")
    if home:
        dirs += [Path(home) / "lib", Path(home) / "lib64"]
    return dirs


def security_available() -> bool:
    """Whether this Cyclone DDS build has the DDS Security plugins (``libdds_security_auth`` & co.)."""
    for d in _lib_dirs():
        if d.is_dir() and any(d.glob("libdds_security_auth*")):
            return True
    return False


def cyclone_config(*, interface: str | None = None, peers: tuple[str, ...] | list[str] = (),
                   multicast: bool | None = None, enclave: str | os.PathLike | None = None) -> str | None:
    """Cyclone DDS XML for these options, or ``None`` when none is given (Cyclone's own configuration).

    Args:
        interface: a network interface name (``eth0``, ``lo``) or its address.
        peers: unicast discovery peers (addresses); with peers, multicast is off unless ``multicast=True``.
        multicast: force multicast on or off.
        enclave: an SROS2 enclave folder (:data:`ENCLAVE_FILES`) for DDS Security.

    Raises:
        Ros2Error: an enclave without its files, or DDS Security missing from this Cyclone build.
    """
    if interface is None and not peers and multicast is None and enclave is None:
        return None
    general = []
    if interface is not None:
        try:
            ipaddress.ip_address(interface)
            attr = "address"
        except ValueError:
            attr = "name"
        general.append(f"<Interfaces><NetworkInterface {attr}={quoteattr(interface)}/></Interfaces>")
    if multicast is None and peers:
        multicast = False
    if multicast is not None:
        general.append(f"<AllowMulticast>{'true' if multicast else 'false'}</AllowMulticast>")
    disc = ""
    if peers:
        disc = ("<Discovery><ParticipantIndex>auto</ParticipantIndex><MaxAutoParticipantIndex>100"
                "</MaxAutoParticipantIndex><Peers>" + "".join(f"<Peer address={quoteattr(p)}/>" for p in peers)
                + "</Peers></Discovery>")
    sec = _security_xml(Path(enclave)) if enclave is not None else ""
    return ("<CycloneDDS><Domain Id=\"any\">" + (f"<General>{''.join(general)}</General>" if general else "")
            + disc + sec + "</Domain></CycloneDDS>")


def _security_xml(enc: Path) -> str:
    if not enc.is_dir():
        raise Ros2Error(f"{enc}: no such enclave folder (ros2 security create_enclave writes one)")
    missing = [f for f in ENCLAVE_FILES if not (enc / f).is_file()]
    if missing:
        raise Ros2Error(f"{enc}: this enclave lacks {', '.join(missing)}")
    if not security_available():
        raise Ros2Error("DDS Security was asked for (an enclave), but this Cyclone DDS build has no security "
                        "plugins (libdds_security_auth/ac/crypto): the PyPI wheel ships without them. Build "
                        "Cyclone DDS with -DENABLE_SECURITY=ON and OpenSSL, point CYCLONEDDS_HOME at it and "
                        "install the cyclonedds Python package from source against it")

    def uri(name: str) -> str:
        return escape("file:" + str((enc / name).resolve()))

    def lib(kind: str, init: str) -> str:
        return (f"<Library path=\"dds_security_{kind}\" initFunction=\"init_{init}\" "
                f"finalizeFunction=\"finalize_{init}\"/>")

    return ("<Security><Authentication>" + lib("auth", "authentication")
            + f"<IdentityCA>{uri('identity_ca.cert.pem')}</IdentityCA>"
            + f"<IdentityCertificate>{uri('cert.pem')}</IdentityCertificate>"
            + f"<PrivateKey>{uri('key.pem')}</PrivateKey></Authentication>"
            + "<AccessControl>" + lib("ac", "access_control")
            + f"<PermissionsCA>{uri('permissions_ca.cert.pem')}</PermissionsCA>"
            + f"<Governance>{uri('governance.p7s')}</Governance>"
            + f"<Permissions>{uri('permissions.p7s')}</Permissions></AccessControl>"
            + "<Cryptographic>" + lib("crypto", "crypto") + "</Cryptographic></Security>")
