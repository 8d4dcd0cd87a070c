#!/usr/bin/python3
"""The card's example renderer with one defect injected, for vri-verify's tests (tests/tools/verify.sh):

    buggy_renderer.py BUG CARD OUTPUT     BUG: none, flip, entry-placement, no-opacity-correction,
                                               jitter-other-seeds, jitter-ignores-seed, jitter-half

flip: row 0 at the bottom. entry-placement: the entry placement whatever the card asks.
no-opacity-correction: each sample's opacity as if the step were one voxel, as a renderer does that reads
a transfer function's per-sample alpha without correcting it for the step (tau scaled by 1 / step).
jitter-other-seeds: no defect, but random numbers of its own (the seed + 1000): the same expectation, not the
same bits. With VRI_TEST_PAIRED_RUNS=DIR the run on seed s leaves a mark in DIR and waits (60 s at most) for
the mark of the run on seed s ^ 1 at the same step, failing if it never comes: the two must run at once. jitter-ignores-seed: every frame with the seed 1. jitter-half: the first sample in the first half of
the step only (a fraction in [0, 1/2))."""
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.environ["VRI_SOURCE"], "examples", "scene_card"))
import render_from_card  # noqa: E402

bug, card_path, out = sys.argv[1:]
card = render_from_card.load_card(card_path)
if os.environ.get("VRI_TEST_PAIRED_RUNS"):
    import time
    marks, method = os.environ["VRI_TEST_PAIRED_RUNS"], card["method"]
    seed, step = method["jitter"]["seed"], repr(method["step"])
    open(os.path.join(marks, f"{step}-{seed}"), "w").close()
    partner = os.path.join(marks, f"{step}-{seed ^ 1}")
    for _ in range(600):
        if os.path.exists(partner):
            break
        time.sleep(0.1)
    else:
        sys.exit(f"seed {seed} ran alone: seed {seed ^ 1} at step {step} never started beside it")
if bug == "entry-placement":
    card["method"]["placement"] = "entry"
elif bug == "no-opacity-correction":
    for point in card["transfer_function"]["points"]:
        point["tau"] *= card["method"]["samples_per_voxel"]
elif bug.startswith("jitter-"):
    fraction = render_from_card.jitter_fraction
    seed_of = {"jitter-other-seeds": lambda seed: seed + 1000, "jitter-ignores-seed": lambda seed: 1,
               "jitter-half": lambda seed: seed}[bug]
    scale = 0.5 if bug == "jitter-half" else 1.0
    render_from_card.jitter_fraction = lambda card, seed: scale * fraction(card, seed_of(seed))
elif bug not in ("none", "flip"):
    sys.exit("unknown bug " + bug)
image = render_from_card.render(card, os.path.dirname(os.path.abspath(card_path)))
if bug == "flip":
    image = image[::-1]
np.ascontiguousarray(image, dtype="<f4").tofile(out)
