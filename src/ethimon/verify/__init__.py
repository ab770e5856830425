"""ethimon.verify."""
