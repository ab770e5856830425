"""Our templated robot-command minimal pairs: make_robot_pairs.py writes robot_pairs.csv."""
