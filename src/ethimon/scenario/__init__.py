"""ethimon.scenario."""
