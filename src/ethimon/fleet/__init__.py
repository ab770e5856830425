"""Fleet scale: many scenario files or ROS bags checked on a Ray cluster (``pip install 'ethimon[fleet]'``).

::

    from ethimon import fleet, scenario
    report = scenario.check_paths(["scenarios/"], executor=fleet.Ray(num_cpus=2))  # a local Ray instance
    records = fleet.replay_records(bags, spec="spec.yaml", mapping="map.yaml", address="auto")

``fleet.Ray`` is an executor of :func:`ethimon.run` (``Serial()`` runs the same units here).

One file (a scenario file, a bag) is one unit of work; a worker returns the file's
results as plain data (dicts, lists, str, int, float, bool, None) and the driver
puts them back in input order, so a run gives the same rows, in the same order,
as the serial run. A file whose worker raises or dies, or (with
``file_timeout=S``) has not returned within S seconds, is one error row (a
timed-out task is cancelled); the others are still reported. Ray moves the
results between processes with its own object transport (pickle inside the
cluster); ethimon never loads a pickle from a file. Ray is imported only when a
run starts: ``import ethimon`` and ``import ethimon.fleet`` never import it.

The workers open the files by the paths given, relative to the driver's working
folder: on a cluster every node must see the files (and ethimon must be
installed) at the same paths, e.g. a shared file system.
"""

from __future__ import annotations

from ._executor import Ray
from ._ray import DEFAULT_LOCAL_CPUS, Failure, check_address, check_file_timeout, map_files, plain  # noqa: F401
from ._run import check_paths, replay_records

__all__ = ["Ray", "check_paths", "plain", "replay_records"]
