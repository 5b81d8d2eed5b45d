#!/bin/sh
# The course's checks, the same steps in CI and on an instructor's machine:
#   ci/run-checks.sh [K/N]
# K/N: check only part K of N of the figures (a CI matrix job); default: all of them.
# Needs `shadelab` on PATH (the workflows install the version the course pins).
set -eu
cd "$(dirname "$0")/.."
shard="${1:-1/1}"
part=$(echo "$shard" | tr / -)
mkdir -p reports
# 1. Every lesson validates; each error lands on its line in the pull request (GitHub:
#    automatic; GitLab: SHADELAB_ANNOTATIONS=gitlab writes its code-quality report).
shadelab check lessons/ ${SHADELAB_ANNOTATIONS:+--annotations "$SHADELAB_ANNOTATIONS"}
# 2. Every figure matches its blessed snapshot: a JUnit file for the test tab and a review
#    page (blessed | actual | difference) for the artifact, whatever the outcome (GitHub: a
#    failing figure is also annotated on its `name` line).
shadelab snapshot lessons/ -o snapshots --shard "$shard" \
    --junit "reports/junit-$part.xml" --report "reports/review-$part"
