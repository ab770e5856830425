"""What a person watches: the monitor's verdicts as Foxglove channels.

One set of channel names and JSON Schemas (:class:`VerdictChannels`) serves the ``ethimon replay
--mcap`` verdict file and the live Foxglove WebSocket server (:class:`FoxgloveView`: ``ethimon ros2
--foxglove``, ``GovernedLoop(foxglove=...)``, ``ethimon replay --foxglove``), so one layout
(``examples/foxglove/ethimon-layout.json``) opens both. A floor beside ``audit`` and ``risk``: it reads
decisions as values and imports nothing above the spine; ``foxglove-sdk`` is imported when a server starts.
"""

from ._channels import DECISION, FAULTS, INPUTS, MARGINS, RISK, TOPICS, VerdictChannels
from ._foxglove import DEFAULT_HOST, DEFAULT_PORT, FoxgloveView, parse_address

__all__ = ["FoxgloveView", "TOPICS", "VerdictChannels"]
