"""ethimon.spec."""
