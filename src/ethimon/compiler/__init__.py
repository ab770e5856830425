"""ethimon.compiler."""
