"""scripts/model_turn.py on cameras with known turns: a camera that only drives forward turns
0 deg, one that turns 1.5 deg a frame has turned 1.5 (n - 1) deg by frame n."""

import math
import os
import subprocess
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "scripts"))
import model_turn  # noqa: E402
from test_compare_models import rotation_about, write_model  # noqa: E402

SCRIPT = os.path.join(os.path.dirname(__file__), "..", "..", "scripts", "model_turn.py")


def drive(count, degrees_per_frame):
    return [(f"{i:04d}.png", rotation_about([0, 1, 0], degrees_per_frame * i),
             np.array([0.0, 0.0, 1.0 * i])) for i in range(count)]


def as_model(cameras):
    return {name: (rotation, centre) for name, rotation, centre in cameras}


def test_a_straight_drive_does_not_turn_and_a_turning_one_does():
    names, turns = model_turn.turns_from_first([as_model(drive(10, 0.0)),
                                                as_model(drive(10, 1.5))])
    assert names[0] == "0000.png" and len(names) == 10
    assert max(turns[0]) == pytest.approx(0.0, abs=1e-9)
    assert turns[1][9] == pytest.approx(13.5, abs=1e-9)
    assert turns[1][4] == pytest.approx(6.0, abs=1e-9)


def test_only_the_frames_every_model_holds_are_compared():
    a = as_model(drive(10, 1.0))
    b = {name: pose for name, pose in as_model(drive(10, 1.0)).items() if name >= "0003.png"}
    names, turns = model_turn.turns_from_first([a, b])
    assert names[0] == "0003.png" and len(names) == 7
    assert turns[0][6] == pytest.approx(6.0, abs=1e-9)
    with pytest.raises(ValueError):
        model_turn.turns_from_first([a, {"x.png": a["0000.png"]}])


def test_the_command_prints_the_largest_turn_and_fails_cleanly(tmp_path):
    write_model(str(tmp_path / "straight"), drive(6, 0.0))
    write_model(str(tmp_path / "turning"), drive(6, 2.0))
    out = subprocess.run([sys.executable, SCRIPT, str(tmp_path / "straight"),
                          str(tmp_path / "turning"), "--every", "2"],
                         capture_output=True, text=True, check=True).stdout
    largest = [line for line in out.splitlines() if line.startswith("largest")][0].split()
    assert float(largest[1]) == pytest.approx(0.0, abs=0.05)
    assert float(largest[2]) == pytest.approx(10.0, abs=0.05)
    missing = subprocess.run([sys.executable, SCRIPT, str(tmp_path / "none")],
                             capture_output=True, text=True)
    assert missing.returncode != 0
    assert missing.stderr.count("\n") == 1 and "none" in missing.stderr
