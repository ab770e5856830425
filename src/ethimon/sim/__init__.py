"""ethimon.sim."""
