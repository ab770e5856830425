#!/bin/sh
# Rebuild train.csv from the hand-written chunk scripts, then apply the two hand-written detail passes.
set -e
cd "$(dirname "$0")"
rm -f ../train.csv
for i in 01 02 03 04 05 06 07 08 09; do python3 train_$i.py; done
python3 amend_scenes.py
python3 amend_scenes_2.py
python3 check.py ../train.csv
