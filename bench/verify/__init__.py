"""z3 proof and lint times per spec (results in bench/results/verify/)."""
