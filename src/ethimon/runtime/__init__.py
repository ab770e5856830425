"""ethimon.runtime."""
