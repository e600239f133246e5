#!/bin/bash
# Issue 15's table (src/parts/mod.rs, "State"): ordered part pairs found by the parts stage on
# the generated shapes, one line per size (icosphere level 4: 2.5k vertices, 5: 10k).
#
#   cargo build --release --example quadruped_report
#   bash bench/parts.sh [EXAMPLE_BINARY]
#
# Each field is `row:found/partials/unmatched`: ordered pairs whose best reported map has
# acc@0.1 >= 0.8, partial symmetries reported, and how many of those map no ordered pair
# right. Rows: the directed quadruped at rest, walking, walking with 0.5% noise (seeds 1-6);
# the spikes with 0.5% noise (seeds 1-3) and clean; for the lopsided blob and the ellipsoid
# (no repeated parts) only the partial symmetries reported (run the example with PARTS=0 for
# those the global stages report themselves).
#
# SEEDS and SPIKE_SEEDS choose the noise seeds (default 1-6 and 1-3, the seeds the stage was
# developed on); session 47 checks the stage on seeds it never saw with
#   SEEDS="7 8 9 10 11 12" SPIKE_SEEDS="4 5 6" bash bench/parts.sh
EX=${1:-target/release/examples/quadruped_report}
run() { "$@" 2>/dev/null | tail -1 | sed -E 's/ordered pairs found: ([0-9]+) of ([0-9]+).*reported: ([0-9]+), mapping no part pair right: ([0-9]+)/\1\/\3\/\4/'; }
for level in 4 5; do
    line="L$level rest:$(SHAPE=directed LEVEL=$level run "$EX" 0 rest)"
    line="$line walking:$(SHAPE=directed LEVEL=$level run "$EX" 0)"
    for seed in ${SEEDS:-1 2 3 4 5 6}; do line="$line noisy$seed:$(SHAPE=directed LEVEL=$level SEED=$seed run "$EX" 0.005)"; done
    for seed in ${SPIKE_SEEDS:-1 2 3}; do line="$line spikes-noisy$seed:$(SHAPE=spiked LEVEL=$level SEED=$seed run "$EX" 0.005)"; done
    line="$line spikes:$(SHAPE=spiked LEVEL=$level run "$EX" 0)"
    line="$line lopsided:$(SHAPE=lopsided LEVEL=$level run "$EX" 0 | cut -d/ -f2)"
    line="$line ellipsoid:$(SHAPE=ellipsoid LEVEL=$level run "$EX" 0 | cut -d/ -f2)"
    echo "$line"
done
