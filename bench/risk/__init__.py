"""The risk model: data splits, training, evaluation, averaging, latency (results in bench/results/risk/)."""
