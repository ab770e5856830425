"""PyBullet sim + monitor speed and time to the safe pose (results in bench/results/sim/)."""
