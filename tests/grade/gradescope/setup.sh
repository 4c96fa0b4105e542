#!/usr/bin/env bash
# Gradescope's setup.sh: runs once when the autograder image is built. Gradescope
# unpacks the autograder zip into /autograder/source; make that zip from the
# instructor's tree (with solutions/ and the hidden tests):
#     git archive --format=zip -o autograder.zip HEAD
# then add tests/grade/gradescope/setup.sh and run_autograder at the zip's top level
# (Gradescope looks for them there).
set -euo pipefail
cd /autograder/source
bash lib/tools/deps.sh
make all
