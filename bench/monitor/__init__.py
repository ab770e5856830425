"""Monitor.step, scaling, the 1 kHz loop and offline trace checking (results in bench/results/monitor/)."""
