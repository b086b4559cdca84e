"""Reading a `pcsim run` result folder in the window tests
(test_run_window.sh, test_run_window_stitched.sh, test_run_window_wind.sh):
its summary.json, one pantograph's EN 50318 figures by key, its contact force
and position."""
import json

import h5py
import numpy as np


def summary(folder):
    with open(f"{folder}/summary.json") as f:
        return json.load(f)


def figures(folder, pantograph="pantograph"):
    return {f["key"]: f["value"] for f in summary(folder)["en50318"][pantograph]["figures"]}


def force_and_position(folder, pantograph="pantograph"):
    with h5py.File(f"{folder}/results.h5") as f:
        group = f[f"/pantographs/{pantograph}"]
        return group["contact_force"][:], group["position"][:]


class Runs:
    """The result folders of one test, by run name: d/<name>."""

    def __init__(self, folder):
        self.folder = folder

    def summary(self, name):
        return summary(f"{self.folder}/{name}")

    def figures(self, name, pantograph="pantograph"):
        return figures(f"{self.folder}/{name}", pantograph)

    def force_and_position(self, name, pantograph="pantograph"):
        return force_and_position(f"{self.folder}/{name}", pantograph)


def check_window_ranks(runs, full="full", one="window1", two="window2", bound=1e-8):
    """The window's contact positions are the full line's, and its run on 2
    ranks equals the one on 1 to within bound of the largest force (round-off:
    measured 7e-11, test_run_window.sh)."""
    f1, x1 = runs.force_and_position(one)
    f2, _ = runs.force_and_position(two)
    _, xf = runs.force_and_position(full)
    assert np.array_equal(x1, xf), "the window's positions are not the line's"
    rel = np.max(np.abs(f2 - f1)) / np.max(np.abs(f1))
    print(f"window 2 ranks vs 1: {rel:.1e}")
    assert rel < bound, rel
