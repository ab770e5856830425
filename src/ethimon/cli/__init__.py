"""ethimon.cli."""
